// indentsim: finite-element simulation of instrumented indentation.
// Units everywhere: um, mN, GPa (1 GPa*um^2 = 1 mN).
//
// Thin application layer: parse the command line and the case file, build the problem, run it,
// write the outputs. No physics here.
#include "io/CaseFile.h"
#include "io/CommandLine.h"
#include "solver/IndentationProblem.h"

#include <deal.II/base/mpi.h>

#include <cstdlib>
#include <filesystem>
#include <iostream>

namespace
{
  using namespace indentsim;

  // Writes the PNG plot of the load-penetration curve with the project's Python script.
  void plot_load_penetration(const std::string &directory)
  {
    const std::string script =
      std::string(INDENTSIM_SOURCE_DIR) + "/python/plot_load_penetration.py";
    const std::string command = "python3 \"" + script + "\" \"" + directory +
                                "/load_penetration.csv\" -o \"" + directory +
                                "/load_penetration.png\"";
    if (std::system(command.c_str()) != 0)
      std::cerr << "warning: the plot " << directory
                << "/load_penetration.png could not be written (command: " << command << ")\n";
  }

  int run(const io::CommandLineOptions &options, const MPI_Comm communicator)
  {
    const bool root = dealii::Utilities::MPI::this_mpi_process(communicator) == 0;
    // Every rank reads and validates the case before any collective call, so that bad input
    // stops all ranks with the same message.
    io::Case the_case = io::read_case_file(options.case_file);
    if (options.output_directory)
      the_case.output.directory = *options.output_directory;

    if (options.command == io::Command::check)
      {
        if (root)
          std::cout << io::resolved_case_yaml(the_case);
        return 0;
      }

    std::string error;
    if (root)
      try
        {
          io::prepare_output_directory(the_case.output.directory, options.overwrite);
          io::write_resolved_case(the_case, the_case.output.directory + "/resolved_case.yaml");
        }
      catch (const std::exception &e)
        {
          error = e.what();
        }
    error = dealii::Utilities::MPI::broadcast(communicator, error, 0);
    if (!error.empty())
      throw io::CaseFileError(error);

    solver::IndentationProblem problem(the_case, communicator);
    problem.setup();
    problem.run(the_case.output.directory);
    if (root)
      {
        plot_load_penetration(the_case.output.directory);
        std::cout << "Results in " << the_case.output.directory
                  << ": load_penetration.csv (um, mN), load_penetration.png, specimen.pvd "
                     "(ParaView), resolved_case.yaml, run.log\n";
      }
    return 0;
  }
} // namespace

int main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
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
          default:
            return run(options, communicator);
        }
    }
  catch (const io::CommandLineError &e)
    {
      if (root)
        std::cerr << "indentsim: " << e.what() << '\n';
      return 2;
    }
  catch (const io::CaseFileError &e)
    {
      if (root)
        std::cerr << "indentsim: error: " << e.what() << '\n';
      return 1;
    }
  catch (const std::exception &e)
    {
      if (root)
        std::cerr << "indentsim: the computation stopped: " << e.what() << '\n';
      return 3;
    }
}
