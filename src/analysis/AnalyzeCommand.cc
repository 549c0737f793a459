#include "analysis/AnalyzeCommand.h"

#include "analysis/CurveComparison.h"
#include "analysis/HardnessDepth.h"
#include "analysis/OliverPharr.h"
#include "case/CaseFile.h"
#include "indenter/IndenterFactory.h"
#include "output/OutputFile.h"
#include "output/PythonScripts.h"

#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <numbers>
#include <sstream>
#include <stdexcept>

namespace indentsim::analysis
{
  namespace
  {
    namespace fs = std::filesystem;

    std::string describe(const io::IndenterParameters &p)
    {
      std::ostringstream out;
      out << p.shape;
      using Shape = io::IndenterShape;
      if (p.shape == Shape::rounded_cone)
        out << " (a " << p.a << ", delta " << p.delta << " um)";
      else if (p.shape == Shape::sphere || p.shape == Shape::flat_punch)
        out << " (radius " << p.radius << " um)";
      else if (p.shape == Shape::cone)
        out << " (half-angle " << p.half_angle_deg << " deg, tip radius " << p.tip_radius << " um)";
      else if (p.shape == Shape::vickers || p.shape == Shape::berkovich)
        out << " (tip radius " << p.tip_radius << " um)";
      else if (p.shape == Shape::profile_table)
        out << " (" << p.file << ")";
      return out.str();
    }

    // Analyses and writes; returns the result for the summary.
    OliverPharrResult analyze_and_write(const LoadCurve                 &curve,
                                        const indenter::IndenterSurface &indenter,
                                        const io::IndenterParameters    &indenter_parameters,
                                        const OliverPharrSettings       &settings,
                                        const std::string &directory, const std::string &source)
    {
      const OliverPharrResult result = analyze(
          curve, [&](const double h) { return indenter.projected_area(h); }, settings);
      fs::create_directories(directory);
      const std::string json_path = directory + "/" + io::output_files::oliver_pharr_json;
      output::write_file(json_path,
                         to_json(result, settings, describe(indenter_parameters), source, &curve));
      const std::string png = directory + "/" + io::output_files::oliver_pharr_png;
      output::draw_plot("plot_oliver_pharr.py", {json_path, "-o", png}, png, std::cerr);
      return result;
    }

    void print_summary(std::ostream &out, const OliverPharrResult &r, const std::string &path)
    {
      out << std::setprecision(5) << "Oliver-Pharr (" << path << "):\n"
          << "  h_max " << r.max_depth << " um, P_max " << r.max_force
          << " mN, fit P = " << r.fit.alpha << " (h - " << r.fit.h_f << ")^" << r.fit.m << " on "
          << r.fit.n_points << " points (rms " << r.fit.rms_error << " mN)\n"
          << "  S " << r.stiffness << " mN/um, h_c " << r.contact_depth << " um, A "
          << r.contact_area << " um^2, H " << r.hardness << " GPa, E_r " << r.reduced_modulus
          << " GPa";
      if (r.sample_modulus)
        out << ", E " << *r.sample_modulus << " GPa";
      out << "\n  h_r/h_max " << r.residual_depth / r.max_depth << ", W_p/W_t "
          << r.plastic_work_ratio;
      if (r.true_contact_area)
        out << "\n  true contact area " << *r.true_contact_area << " um^2 (H " << *r.true_hardness
            << " GPa): Oliver-Pharr area error " << std::showpos << *r.area_error_percent
            << std::noshowpos << " %";
      if (!r.true_area_note.empty())
        out << "\n  " << r.true_area_note;
      out << '\n';
    }
  } // namespace

  std::string analyze_command(const io::AnalyzeOptions         &options,
                              const std::optional<std::string> &output_directory)
  {
    const fs::path target(options.target);
    if (!fs::exists(target))
      throw std::invalid_argument(options.target + ": no such run directory or CSV file");
    const bool        run_directory = fs::is_directory(target);
    const std::string csv_path = run_directory
                                     ? (target / io::output_files::load_penetration_csv).string()
                                     : target.string();
    if (run_directory && !fs::exists(csv_path))
      throw std::invalid_argument(options.target + ": a run directory needs " +
                                  io::output_files::load_penetration_csv + " (this one has none)");

    io::IndenterParameters indenter_parameters;
    if (!options.indenter_case.empty())
      indenter_parameters = io::read_case_file(options.indenter_case).indenter;
    else if (!options.indenter_shape.empty())
      {
        indenter_parameters.shape = options.indenter_shape;
        io::Case probe;
        probe.indenter = indenter_parameters;
        try
          {
            io::validate_case(probe);
          }
        catch (const std::exception &e)
          {
            throw std::invalid_argument("--indenter " + options.indenter_shape + ": " + e.what());
          }
        if (options.indenter_shape == "profile_table")
          throw std::invalid_argument("--indenter profile_table needs its table: use "
                                      "--indenter-case with a case file naming indenter.file");
      }
    else if (run_directory)
      {
        const std::string resolved = (target / io::output_files::resolved_case).string();
        if (!fs::exists(resolved))
          throw std::invalid_argument(options.target + ": the run directory has no " +
                                      io::output_files::resolved_case +
                                      "; name the indenter with --indenter or --indenter-case");
        indenter_parameters = io::read_case_file(resolved).indenter;
      }
    else
      throw std::invalid_argument(options.target +
                                  ": a CSV needs the indenter: --indenter "
                                  "vickers|berkovich|cone|rounded_cone|sphere|flat_punch or "
                                  "--indenter-case CASE.yaml");

    OliverPharrSettings settings;
    settings.epsilon =
        options.epsilon ? *options.epsilon : default_epsilon(to_string(indenter_parameters.shape));
    settings.beta = options.beta;
    settings.fit_lower = options.fit_lower;
    settings.fit_upper = options.fit_upper;
    settings.sample_poisson_ratio = options.sample_poisson_ratio;
    if (options.indenter_modulus)
      settings.indenter_modulus = *options.indenter_modulus;
    settings.indenter_poisson_ratio = options.indenter_poisson_ratio;

    // A run's partial unloads (its segment column) are not part of the full unloading; they
    // give the hardness-depth profile.
    const LoadCurve recorded =
        read_load_curve_csv(csv_path, options.depth_column, options.force_column,
                            options.depth_unit, options.force_unit);
    const LoadCurve   curve = without_partial_unloads(recorded);
    const std::string directory =
        output_directory ? *output_directory
        : run_directory  ? target.string()
                         : (target.has_parent_path() ? target.parent_path().string() : ".");
    const auto              indenter = indenter::create_indenter(indenter_parameters);
    const OliverPharrResult result =
        analyze_and_write(curve, *indenter, indenter_parameters, settings, directory, csv_path);
    const std::string json_path = directory + "/" + io::output_files::oliver_pharr_json;
    print_summary(std::cout, result, json_path);
    if (curve.depth.size() < recorded.depth.size())
      write_hardness_profile(recorded, *indenter, settings, directory, std::cout, std::cerr);
    return json_path;
  }

  namespace
  {
    // The Oliver-Pharr settings of a run's own analyses.
    OliverPharrSettings run_settings(const io::Case &the_case)
    {
      OliverPharrSettings settings;
      settings.epsilon = default_epsilon(to_string(the_case.indenter.shape));
      if (the_case.material.model != io::ModelKind::crystal)
        settings.sample_poisson_ratio = the_case.material.poisson_ratio;
      // One contact element across the contact radius at the least: the refined region's h_e
      // (mesh/IndentationMesh), or the automatic mesh's smallest edge h_min, beyond which its
      // elements grow as rho/n (mesh/MeshDesign.h).
      const io::SpecimenParameters &specimen = the_case.specimen;
      const double                  element = specimen.automatic_mesh()
                                                  ? specimen.grading.min_element
                                                  : specimen.refined_region[0] / specimen.contact_elements;
      settings.min_true_contact_area = std::numbers::pi * element * element;
      return settings;
    }
  } // namespace

  bool analyze_run(const LoadCurve &curve, const io::Case &the_case,
                   const indenter::IndenterSurface &indenter, std::ostream &summary,
                   std::ostream &warnings)
  {
    const std::string &run_directory = the_case.output.directory;
    try
      {
        const OliverPharrResult result =
            analyze_and_write(without_partial_unloads(curve), indenter, the_case.indenter,
                              run_settings(the_case), run_directory, curve.source);
        print_summary(summary, result, run_directory + "/" + io::output_files::oliver_pharr_json);
        return true;
      }
    catch (const output::OutputError &)
      {
        throw; // a write that failed is an error, not a missing analysis
      }
    catch (const std::exception &e)
      {
        warnings << "warning: no Oliver-Pharr analysis of " << run_directory << ": " << e.what()
                 << '\n';
        return false;
      }
  }

  bool analyze_partial_unloads_of_run(const LoadCurve &curve, const io::Case &the_case,
                                      const indenter::IndenterSurface &indenter,
                                      std::ostream &summary, std::ostream &warnings)
  {
    return write_hardness_profile(curve, indenter, run_settings(the_case),
                                  the_case.output.directory, summary, warnings);
  }

  bool write_hardness_profile(const LoadCurve &curve, const indenter::IndenterSurface &indenter,
                              const OliverPharrSettings &settings, const std::string &directory,
                              std::ostream &summary, std::ostream &warnings)
  {
    std::vector<std::string>         skipped;
    const std::vector<HardnessPoint> points = analyze_partial_unloads(
        curve, [&](const double h) { return indenter.projected_area(h); }, settings, skipped);
    for (const std::string &why : skipped)
      warnings << "warning: hardness-depth profile of " << directory << ": left out " << why
               << '\n';
    if (points.empty())
      {
        warnings << "warning: no hardness-depth profile of " << directory
                 << ": no partial unload could be analysed\n";
        return false;
      }
    std::vector<double> depth, hardness;
    for (const HardnessPoint &p : points)
      {
        depth.push_back(p.depth);
        hardness.push_back(p.estimate.hardness);
      }
    const std::optional<NixGaoFit> nix_gao = fit_nix_gao(depth, hardness);
    const std::string json_path = directory + "/" + io::output_files::hardness_depth_json;
    output::write_file(directory + "/" + io::output_files::hardness_depth_csv, to_csv(points));
    output::write_file(json_path, to_json(points, nix_gao, skipped, curve.source));
    const std::string png = directory + "/" + io::output_files::hardness_depth_png;
    output::draw_plot("plot_hardness_depth.py", {json_path, "-o", png}, png, warnings);
    summary << std::setprecision(4) << "Hardness-depth profile (" << json_path
            << "): " << points.size() << " partial unloads from " << points.front().depth << " to "
            << points.back().depth << " um, H " << points.front().estimate.hardness << " to "
            << points.back().estimate.hardness << " GPa";
    if (nix_gao && nix_gao->knee_significant())
      summary << "; Nix-Gao knee at " << nix_gao->knee_depth << " um, shallow branch H_0 "
              << nix_gao->layer_hardness << " GPa";
    else if (nix_gao)
      summary << "; Nix-Gao: no significant knee (F = " << nix_gao->f_statistic
              << "): one straight line describes H^2(1/h)";
    summary << '\n';
    return true;
  }

  bool compare_with_experiment(const LoadCurve &computed, const std::string &run_directory,
                               const std::string &measured_csv, std::ostream &summary,
                               std::ostream &warnings)
  {
    try
      {
        const LoadCurve      measured = read_load_curve_csv(measured_csv);
        const CurveDeviation deviation = compare_loading(computed, measured);
        const auto           write = [&](const std::string &name, const std::string &text) {
          output::write_file(run_directory + "/" + name, text);
        };
        write(io::output_files::experiment_comparison_json, to_json(deviation, measured_csv));
        write(io::output_files::experimental_curve_csv, to_csv(measured));
        summary << std::setprecision(5) << "Against the measured curve " << measured_csv
                << ": RMS deviation of the loading " << deviation.rms_mN << " mN ("
                << 100 * deviation.rms_relative << " % of the force at " << deviation.max_depth
                << " um) over " << deviation.n_points << " measured points";
        if (deviation.deviation_at_max_depth_percent)
          summary << "; at " << deviation.max_depth << " um computed " << deviation.computed_force
                  << " mN, measured " << *deviation.measured_force << " mN (" << std::showpos
                  << *deviation.deviation_at_max_depth_percent << std::noshowpos << " %)";
        summary << '\n';
        return true;
      }
    catch (const output::OutputError &)
      {
        throw; // a write that failed is an error, not a missing comparison
      }
    catch (const std::exception &e)
      {
        warnings << "warning: no comparison with the measured curve " << measured_csv << ": "
                 << e.what() << '\n';
        return false;
      }
  }
} // namespace indentsim::analysis
