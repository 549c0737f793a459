#include "output/RunRecorder.h"

#include "io/Version.h"

#include <cmath>
#include <iomanip>
#include <sstream>

namespace indentsim::output
{
  std::string format_duration(const double seconds)
  {
    std::ostringstream s;
    const long         total = std::lround(seconds);
    s << total / 60 << "m" << std::setw(2) << std::setfill('0') << total % 60 << "s";
    return s.str();
  }

  namespace
  {
    void write_csv_header(std::ostream &out)
    {
      out << "step,cycle,segment,depth_um,force_mN,contact_radius_um,contact_area_um2,"
             "n_active_nodes,n_stick_nodes,n_slip_nodes,max_pressure_GPa,max_penetration_um,"
             "newton_iterations,augmentations,cutbacks,bottom_reaction_mN,plastic_zone_depth_um,"
             "plastic_zone_radius_um,plastic_zone_volume_um3,plastic_zone_layer_fraction,"
             "wall_time_s\n";
    }

    void write_csv_row(std::ostream &out, const nonlinear::StepRecord &r)
    {
      out << r.step << ',' << r.cycle << ',' << r.segment << ',' << std::setprecision(10) << r.depth
          << ',' << r.force << ',' << r.contact_radius << ',' << r.contact_area << ','
          << r.n_active_nodes << ',' << r.n_stick_nodes << ',' << r.n_slip_nodes << ','
          << r.max_pressure << ',' << std::setprecision(4) << r.max_penetration << ','
          << r.newton_iterations << ',' << r.augmentations << ',' << r.cutbacks << ','
          << std::setprecision(10) << r.bottom_reaction << ',' << std::setprecision(6)
          << r.plastic_zone_depth << ',' << r.plastic_zone_radius << ',' << r.plastic_zone_volume
          << ','
          << (r.plastic_zone_volume > 0 ? r.plastic_zone_layer_volume / r.plastic_zone_volume : 0.0)
          << ',' << std::setprecision(4) << r.wall_time << '\n';
    }

    void write_log_header(std::ostream &out, const RunLogHeader &header)
    {
      out << "# indentsim " << indentsim::version() << " run log. Units: um, mN, GPa, s.\n"
          << "# cells " << header.n_cells << ", DOFs " << header.n_dofs << ", constrained DOFs "
          << header.n_constrained_dofs << ", MPI ranks " << header.n_ranks << '\n'
          << "# step depth_um force_mN newton_iterations augmentations cutbacks "
             "max_penetration_um wall_time_s\n";
    }

    void write_log_row(std::ostream &out, const nonlinear::StepRecord &r)
    {
      out << r.step << ' ' << std::setprecision(8) << r.depth << ' ' << r.force << ' '
          << r.newton_iterations << ' ' << r.augmentations << ' ' << r.cutbacks << ' '
          << r.max_penetration << ' ' << std::setprecision(4) << r.wall_time << '\n';
    }
  } // namespace

  void RunRecorder::open(const std::string &directory, const RunLogHeader &header,
                         const std::vector<nonlinear::StepRecord> &records)
  {
    if (directory.empty())
      return;
    const std::string csv_path = directory + "/load_penetration.csv";
    const std::string log_path = directory + "/run.log";
    write_file(csv_path, [&](std::ostream &out) {
      write_csv_header(out);
      for (const nonlinear::StepRecord &r : records)
        write_csv_row(out, r);
    });
    write_file(log_path, [&](std::ostream &out) {
      write_log_header(out, header);
      for (const nonlinear::StepRecord &r : records)
        if (r.step > 0)
          write_log_row(out, r);
    });
    csv_.open(csv_path);
    log_.open(log_path);
  }

  void RunRecorder::flush(AppendFile &file)
  {
    try
      {
        file.flush();
      }
    catch (const OutputError &e)
      {
        if (!failure_)
          failure_ = e;
      }
  }

  void RunRecorder::csv_row(const nonlinear::StepRecord &r)
  {
    if (!csv_.is_open() || failure_)
      return;
    write_csv_row(csv_.stream(), r);
    flush(csv_);
  }

  void RunRecorder::log_row(const nonlinear::StepRecord &r)
  {
    if (!log_.is_open() || failure_)
      return;
    write_log_row(log_.stream(), r);
    flush(log_);
  }

  void RunRecorder::log_note(const std::string &text)
  {
    if (!log_.is_open() || failure_)
      return;
    log_.stream() << "# " << text << '\n';
    flush(log_);
  }

  void RunRecorder::throw_if_failed() const
  {
    if (failure_)
      throw *failure_;
  }

  std::ostream &operator<<(std::ostream &out, const ProgressLine &line)
  {
    const nonlinear::StepRecord &r = line.record;
    out << "step " << std::setw(3) << r.step << ' ' << std::left << std::setw(6) << r.segment
        << std::right;
    if (line.show_cycle)
      out << " cycle " << r.cycle;
    out << "  depth " << std::setprecision(6) << r.depth << " um  force " << r.force << " mN";
    if (line.force_target != nullptr)
      out << " (target " << *line.force_target << ")";
    out << "  (bottom reaction " << r.bottom_reaction << ")  active " << r.n_active_nodes;
    if (line.show_stick)
      out << " (stick " << r.n_stick_nodes << ")";
    out << "  Newton " << r.newton_iterations << "  aug " << r.augmentations << "  cut "
        << r.cutbacks << "  pen " << std::scientific << std::setprecision(1) << r.max_penetration
        << std::defaultfloat << "  wall " << format_duration(r.wall_time) << "  ETA ~"
        << format_duration(line.eta);
    return out;
  }
} // namespace indentsim::output
