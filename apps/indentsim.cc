// indentsim: finite-element simulation of instrumented indentation.
// Units everywhere: um, mN, GPa (1 GPa*um^2 = 1 mN).
//
// Thin application layer: parse the command line and the case file, build the problem, run it,
// write the outputs. No physics here.
#include "analysis/AnalyzeCommand.h"
#include "calibration/CalibrationFile.h"
#include "calibration/CalibrationRunner.h"
#include "case/CaseFile.h"
#include "io/CommandLine.h"
#include "io/MpiStartup.h"
#include "mesh/MeshAdequacy.h"
#include "output/MemoryEstimate.h"
#include "output/OutputFile.h"
#include "output/PythonScripts.h"
#include "problems/IndentationProblem.h"
#include "problems/TensileProblem.h"
#include "study/StudyFile.h"
#include "study/StudyRunner.h"

#include <deal.II/base/mpi.h>
#include <deal.II/base/multithread_info.h>

#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

namespace
{
  using namespace indentsim;

  // An error message in one write: under mpirun, stderr and stdout reach the terminal through
  // separate channels, and a message written piecewise can be split by another line.
  void report(const std::string &prefix, const std::exception &error, const std::string &after = "")
  {
    std::cerr << (prefix + error.what() + "\n" + after) << std::flush;
  }

  // Writes the PNG plot of the load-penetration curve with the project's Python script.
  // With `measured_csv` (um, mN) the measured curve is overlaid.
  void plot_load_penetration(const std::string &directory, const std::string &measured_csv = "")
  {
    std::vector<std::string> arguments = {directory + "/load_penetration.csv"};
    if (!measured_csv.empty())
      arguments.insert(arguments.end(),
                       {measured_csv, "--label", "computed", "--label", "measured"});
    const std::string png = directory + "/load_penetration.png";
    arguments.insert(arguments.end(), {"-o", png});
    output::draw_plot("plot_load_penetration.py", arguments, png, std::cerr);
  }

  // Writes the PNG plot of the tensile curve(s): the case's model and, if present, J2.
  void plot_stress_strain(const std::string &directory, const std::string &model, bool with_j2)
  {
    std::vector<std::string> arguments = {directory + "/" + io::output_files::stress_strain_csv,
                                          "--label", model};
    if (with_j2)
      arguments.insert(arguments.end(),
                       {directory + "/" + io::output_files::stress_strain_j2_csv, "--label", "j2"});
    const std::string png = directory + "/" + io::output_files::stress_strain_png;
    arguments.insert(arguments.end(), {"-o", png});
    output::draw_plot("plot_stress_strain.py", arguments, png, std::cerr);
  }

  // `word` as one word for the shell (in single quotes unless it needs none).
  std::string shell_word(const std::string &word)
  {
    const bool plain = !word.empty() &&
                       word.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz"
                                              "0123456789_-+=.,/:@%") == std::string::npos;
    if (plain)
      return word;
    std::string quoted = "'";
    for (const char c : word)
      quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return quoted + "'";
  }

  // The command that resumes this run, as it was started: the program as it was called, the
  // case file, --output DIR if the directory is not the case file's own, and mpirun -np N for
  // several ranks. Run from the same working directory, it continues the run.
  std::string resume_command(const std::string &program, const io::CommandLineOptions &options,
                             const std::string &case_file_directory, const unsigned int n_ranks)
  {
    std::string command = n_ranks > 1 ? "mpirun -np " + std::to_string(n_ranks) + " " : "";
    command += shell_word(program) + " run " + shell_word(options.case_file);
    if (options.output_directory && *options.output_directory != case_file_directory)
      command += " --output " + shell_word(*options.output_directory);
    return command + " --resume";
  }

  // Returns false if the run was stopped (checkpoint written, no end-of-run outputs). dim = 2:
  // the axisymmetric model.
  template <int dim>
  bool run_indentation(const io::RunCase &run_case, const MPI_Comm communicator, const bool root,
                       const bool resume, const std::string &resume_hint)
  {
    const io::Case                   &the_case = run_case.the_case;
    problems::IndentationProblem<dim> problem(the_case, communicator, true, run_case.indenter);
    problem.set_resume_command(resume_hint);
    problem.setup();
    if (problem.run(the_case.output.directory, resume) ==
        problems::IndentationProblem<dim>::RunOutcome::stopped)
      return false;
    if (root)
      {
        // The run's curve as Oliver-Pharr and the comparison read it, straight from memory.
        const std::string  &directory = the_case.output.directory;
        analysis::LoadCurve curve;
        curve.source = directory + "/" + io::output_files::load_penetration_csv;
        for (const problems::StepRecord &record : problem.records())
          {
            curve.depth.push_back(record.depth);
            curve.force.push_back(record.force);
            curve.contact_area.push_back(record.contact_area);
            curve.segment.push_back(record.segment);
          }
        const bool compared = !the_case.output.experimental_curve.empty() &&
                              analysis::compare_with_experiment(
                                  analysis::without_partial_unloads(curve), directory,
                                  the_case.output.experimental_curve, std::cout, std::cerr);
        plot_load_penetration(
            directory, compared ? directory + "/" + io::output_files::experimental_curve_csv : "");
        const bool oliver_pharr =
            the_case.loading.unload &&
            analysis::analyze_run(curve, the_case, problem.indenter(), std::cout, std::cerr);
        const bool hardness_depth = the_case.loading.partial_unloads.enabled() &&
                                    analysis::analyze_partial_unloads_of_run(
                                        curve, the_case, problem.indenter(), std::cout, std::cerr);
        std::cout << "Results in " << directory
                  << ": load_penetration.csv (um, mN), load_penetration.png, specimen.pvd "
                     "(ParaView), pileup.json, pileup_*.csv/png (heights in um), "
                  << (oliver_pharr ? "oliver_pharr.json/png, " : "")
                  << (hardness_depth ? "hardness_depth.csv/json/png, " : "")
                  << (compared ? "comparison_with_experiment.json, experimental_curve.csv, " : "")
                  << "resolved_case.yaml, run.log\n";
        // The warnings again, by topic, where the run ends: a long run's scroll hides them.
        const std::vector<output::RunWarning> &warnings = problem.warnings();
        if (!warnings.empty())
          {
            std::cerr << "indentsim: " << warnings.size()
                      << (warnings.size() == 1 ? " warning" : " warnings") << " in this run (";
            for (std::size_t i = 0; i < warnings.size(); ++i)
              std::cerr << (i == 0 ? "" : ", ") << warnings[i].topic;
            std::cerr << "); the texts are in run.log and run_summary.json" << std::endl;
          }
      }
    return true;
  }

  void run_tensile(const io::Case &the_case, const MPI_Comm communicator, const bool root)
  {
    const std::string &directory = the_case.output.directory;
    {
      problems::TensileProblem problem(the_case, communicator);
      problem.setup();
      problem.run(directory, io::output_files::stress_strain_csv, true);
    }
    if (the_case.compare_j2)
      {
        // The same cube and loading with the isotropic model of material.young_modulus,
        // poisson_ratio, yield_stress and hardening_modulus.
        io::Case j2_case = the_case;
        j2_case.material.model = io::ModelKind::j2;
        problems::TensileProblem problem(j2_case, communicator);
        problem.setup();
        problem.run(directory, io::output_files::stress_strain_j2_csv, false);
      }
    if (root)
      {
        plot_stress_strain(directory, io::to_string(the_case.material.model), the_case.compare_j2);
        std::cout << "Results in " << directory
                  << ": stress_strain.csv (log strain, true stress in GPa, force in mN)"
                  << (the_case.compare_j2 ? ", stress_strain_j2.csv" : "")
                  << ", stress_strain.png, specimen_NNNN.pvtu (ParaView, final state), "
                     "resolved_case.yaml, run.log\n";
      }
  }

  int run(const io::CommandLineOptions &options, const std::string &program,
          const MPI_Comm communicator)
  {
    const bool root = dealii::Utilities::MPI::this_mpi_process(communicator) == 0;
    // Every rank reads and validates the case before any collective call, so that bad input
    // stops all ranks with the same message.
    std::string       case_file_directory;
    const io::RunCase run_case = io::read_case_for_run(options.case_file, [&](io::Case &the_case) {
      case_file_directory = the_case.output.directory;
      std::vector<std::string> changed;
      if (options.output_directory)
        {
          the_case.output.directory = *options.output_directory;
          changed.push_back("output.directory");
        }
      if (options.compare_j2)
        {
          the_case.compare_j2 = true;
          changed.push_back("compare_j2");
        }
      return changed;
    });
    const io::Case   &the_case = run_case.the_case;

    if (options.command == io::Command::check)
      {
        if (root)
          std::cout << io::resolved_case_yaml(the_case);
        // After the YAML, as comment lines: the output stays a valid case file.
        output::check_memory(the_case, communicator, std::cout, "# ");
        return 0;
      }
    // Collective; refuses a case that would not fit in memory before anything is written.
    output::check_memory(the_case, communicator, std::cout);

    if (options.resume && the_case.test != io::TestKind::indentation)
      throw io::CaseFileError("--resume: only indentation runs can be stopped and resumed ("
                              "a tensile run is short; rerun it with --overwrite)");
    const std::string &directory = the_case.output.directory;
    const std::string  resolved_case_path = directory + "/" + io::output_files::resolved_case;
    const std::string  resolved_text = io::resolved_case_yaml(the_case);
    bool               write_resolved = true;
    if (options.resume)
      {
        // Nothing is written before the checkpoint has been found to be this case's: a refused
        // resume leaves the directory as it was.
        if (problems::check_resume(the_case, communicator) == problems::ResumeState::finished)
          {
            if (root)
              std::cout << "The run in " << directory
                        << " is finished (run_summary.json, no checkpoint), with this case: "
                           "nothing to resume, nothing was changed. --overwrite computes it "
                           "again.\n";
            return 0;
          }
        // The result keys agree; the others (e.g. solver.threads) may have changed.
        std::ifstream      existing(resolved_case_path);
        std::ostringstream text;
        text << existing.rdbuf();
        write_resolved = text.str() != resolved_text;
      }
    else
      {
        std::string error;
        if (root)
          try
            {
              io::prepare_output_directory(directory, options.overwrite);
            }
          catch (const std::exception &e)
            {
              error = e.what();
            }
        error = dealii::Utilities::MPI::broadcast(communicator, error, 0);
        if (!error.empty())
          throw io::CaseFileError(error);
      }
    output::write_collectively(communicator, [&]() {
      if (root && write_resolved)
        output::write_file(resolved_case_path, resolved_text);
    });

    output::set_plots_enabled(the_case.output.plots);
    // Assembly threads per rank: solver.threads, or (0) the cores of the node divided among the
    // ranks on it, as MPI_InitFinalize set it up.
    if (the_case.solver.threads > 0)
      dealii::MultithreadInfo::set_thread_limit(the_case.solver.threads);
    if (root)
      std::cout << "Threads per MPI rank: " << dealii::MultithreadInfo::n_threads() << std::endl;

    if (the_case.test == io::TestKind::tensile)
      {
        run_tensile(the_case, communicator, root);
        return 0;
      }
    const std::string resume =
        resume_command(program, options, case_file_directory,
                       dealii::Utilities::MPI::n_mpi_processes(communicator));
    const bool finished =
        the_case.specimen.symmetry == io::Symmetry::axisymmetric
            ? run_indentation<2>(run_case, communicator, root, options.resume, resume)
            : run_indentation<3>(run_case, communicator, root, options.resume, resume);
    return finished ? 0 : 130; // stopped by a signal: the shell's convention for SIGINT
  }

  // indentsim calibrate: reads the calibration file and fits, running the forward cases as
  // child processes.
  int run_calibrate(const io::CommandLineOptions &options, const MPI_Comm communicator)
  {
    if (dealii::Utilities::MPI::n_mpi_processes(communicator) > 1)
      throw io::CaseFileError("indentsim calibrate starts each forward run itself and runs in "
                              "one process; use --ranks N to run every case on N MPI ranks");
    const calibration::Calibration the_calibration = calibration::read_calibration_file(
        options.study_file, options.output_directory.value_or(""));
    if (options.study_dry_run)
      {
        std::cout << "Calibration " << options.study_file
                  << " is valid: " << the_calibration.parameters.size() << " parameter(s), "
                  << the_calibration.data.size() << " data set(s), output "
                  << the_calibration.output_directory << ". Nothing was run or written.\n";
        return 0;
      }
    study::StudyRunSettings settings;
    settings.ranks = options.study_ranks;
    settings.jobs = options.study_jobs;
    settings.launcher = options.study_launcher;
    return calibration::run_calibration(the_calibration, settings, std::cout, std::cerr);
  }

  // indentsim study: reads the study file and runs its cases as child processes.
  int run_study(const io::CommandLineOptions &options, const MPI_Comm communicator)
  {
    if (dealii::Utilities::MPI::n_mpi_processes(communicator) > 1)
      throw io::CaseFileError("indentsim study starts each case itself and runs in one "
                              "process; use --ranks N to run every case on N MPI ranks");
    const study::Study the_study =
        study::read_study_file(options.study_file, options.output_directory.value_or(""));
    study::StudyRunSettings settings;
    settings.ranks = options.study_ranks;
    settings.jobs = options.study_jobs;
    settings.dry_run = options.study_dry_run;
    settings.only = options.study_only;
    settings.launcher = options.study_launcher;
    return study::StudyRunner(the_study, settings, std::cout).run();
  }
} // namespace

int main(int argc, char **argv)
{
  // A process without a launcher starts MPI as a singleton, without network transports and
  // with a session directory of its own (io/MpiStartup.h). Threads: determined from the cores
  // and the ranks per node (refined by solver.threads).
  io::SingletonStartup                     singleton;
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, dealii::numbers::invalid_unsigned_int);
  singleton.take_back();
  indentsim::linalg::LinearSolver::limit_library_threads();
  // A file-size limit (ulimit -f) makes a write fail with EFBIG, reported with the file's name
  // (exit code 4), instead of ending the process.
  std::signal(SIGXFSZ, SIG_IGN);
  const MPI_Comm communicator = MPI_COMM_WORLD;
  const bool     root = dealii::Utilities::MPI::this_mpi_process(communicator) == 0;
  try
    {
      const io::CommandLineOptions options = io::parse_command_line(argc, argv);
      switch (options.command)
        {
        case io::Command::help:
          if (root)
            std::cout << io::help_text();
          return 0;
        case io::Command::version:
          if (root)
            std::cout << io::version_text();
          return 0;
        case io::Command::analyze:
          // Serial post-processing: rank 0 only.
          if (root)
            try
              {
                analysis::analyze_command(options.analyze, options.output_directory);
              }
            catch (const std::invalid_argument &e) // bad input: named in the message
              {
                report("indentsim: error: ", e);
                return 1;
              }
            catch (const output::OutputError &e)
              {
                report("indentsim: error: ", e);
                return 4;
              }
          return 0;
        case io::Command::study:
          return run_study(options, communicator);
        case io::Command::calibrate:
          return run_calibrate(options, communicator);
        default:
          return run(options, argv[0], communicator);
        }
    }
  catch (const io::CommandLineError &e)
    {
      if (root)
        report("indentsim: ", e);
      return 2;
    }
  catch (const io::CaseFileError &e)
    {
      if (root)
        report("indentsim: error: ", e);
      return 1;
    }
  catch (const output::OutputError &e)
    {
      // Every rank has the same error (output::write_collectively); a file written on rank 0
      // alone fails there only.
      if (root)
        report("indentsim: error: ", e,
               "The files written before stay as they were (the last checkpoint, if any, is "
               "intact).\n");
      return 4;
    }
  catch (const mesh::MeshOutgrownError &e)
    {
      if (root)
        report("indentsim: the computation stopped: ", e);
      return 5;
    }
  catch (const std::exception &e)
    {
      if (root)
        report("indentsim: the computation stopped: ", e);
      return 3;
    }
}
