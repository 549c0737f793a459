#include "output/RunStatistics.h"

#include "io/JsonText.h"
#include "io/Version.h"
#include "output/OutputFile.h"

#include <deal.II/base/mpi.h>

#include <sys/resource.h>

#include <iomanip>

namespace indentsim::output
{
  namespace
  {
    void write_summary(std::ostream &out, const RunDescription &d, const RunStatistics &s,
                       const double memory_max, const double memory_sum, const double cell_loop_min,
                       const double cell_loop_max)
    {
      const auto text = [](const std::string &value) { return "\"" + value + "\""; };
      out << std::setprecision(10) << "{\n"
          << "  \"units\": \"times in s, memory in MiB, force in mN, stress in GPa\",\n"
          << "  \"version\": " << text(indentsim::version()) << ",\n"
          << "  \"test\": " << text(d.test) << ",\n"
          << "  \"material_model\": " << text(d.material_model) << ",\n"
          << "  \"linear_solver\": " << text(d.linear_solver) << ",\n"
          << "  \"cells\": " << d.cells << ",\n"
          << "  \"dofs\": " << d.dofs << ",\n"
          << "  \"mpi_ranks\": " << d.mpi_ranks << ",\n"
          << "  \"threads_per_rank\": " << d.threads << ",\n"
          << "  \"steps\": " << s.steps << ",\n"
          << "  \"cutbacks\": " << s.cutbacks << ",\n"
          << "  \"newton_iterations\": " << s.newton_iterations << ",\n"
          << "  \"augmentations\": " << s.augmentations << ",\n"
          << "  \"assemblies\": " << s.assemblies << ",\n"
          << "  \"residual_only_assemblies\": " << s.residual_only_assemblies << ",\n"
          << "  \"residual_first_misses\": " << s.residual_first_misses << ",\n"
          << "  \"contact_only_assemblies\": " << s.contact_only_assemblies << ",\n"
          << "  \"predictor_retries\": " << s.predictor_retries << ",\n"
          << "  \"linear_solves\": " << s.linear_solves << ",\n"
          << "  \"linear_iterations\": " << s.linear_iterations << ",\n"
          << "  \"preconditioner_setups\": " << s.preconditioner_setups << ",\n"
          << "  \"time_setup_s\": " << s.setup << ",\n"
          << "  \"time_assembly_s\": " << s.assembly << ",\n"
          << "  \"time_cell_loop_min_rank_s\": " << cell_loop_min << ",\n"
          << "  \"time_cell_loop_max_rank_s\": " << cell_loop_max << ",\n"
          << "  \"time_contact_s\": " << s.contact << ",\n"
          << "  \"time_linear_solve_s\": " << s.linear_solve << ",\n"
          << "  \"time_preconditioner_setup_s\": " << s.preconditioner_setup << ",\n"
          << "  \"time_output_s\": " << s.output << ",\n"
          << "  \"time_total_s\": " << s.total << ",\n"
          << "  \"peak_memory_per_rank_mib\": " << memory_max << ",\n"
          << "  \"peak_memory_total_mib\": " << memory_sum << ",\n"
          << "  \"warnings\": [";
      for (std::size_t i = 0; i < d.warnings.size(); ++i)
        out << (i == 0 ? "\n" : ",\n") << "    {\"topic\": " << io::json_string(d.warnings[i].topic)
            << ", \"text\": " << io::json_string(d.warnings[i].text) << "}";
      out << (d.warnings.empty() ? "" : "\n  ") << "],\n"
          << "  " << text(d.final_value_name) << ": " << d.final_value << "\n"
          << "}\n";
    }
  } // namespace

  double peak_memory_mib()
  {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return static_cast<double>(usage.ru_maxrss) / 1024.0; // Linux: kilobytes
  }

  void write_run_summary(const std::string &path, const RunDescription &d, const RunStatistics &s,
                         const MPI_Comm communicator)
  {
    const double memory = peak_memory_mib();
    const double memory_max = dealii::Utilities::MPI::max(memory, communicator);
    const double memory_sum = dealii::Utilities::MPI::sum(memory, communicator);
    const double cell_loop_min = dealii::Utilities::MPI::min(s.cell_loop, communicator);
    const double cell_loop_max = dealii::Utilities::MPI::max(s.cell_loop, communicator);
    write_collectively(communicator, [&]() {
      if (dealii::Utilities::MPI::this_mpi_process(communicator) == 0)
        write_file(path, [&](std::ostream &out) {
          write_summary(out, d, s, memory_max, memory_sum, cell_loop_min, cell_loop_max);
        });
    });
  }
} // namespace indentsim::output
