// Command-line parsing for the indentsim executable. No physics here: main() only parses,
// reads the case and hands it on.
#include <io/CommandLine.h>

#ifndef INDENTSIM_VERSION
#  define INDENTSIM_VERSION "unknown"
#endif

namespace indentsim::io
{
  namespace
  {
    [[noreturn]] void bad_usage(const std::string &problem)
    {
      throw CommandLineError(problem + "\n\n" + usage_text() +
                             "Run 'indentsim --help' for details.\n");
    }
  } // namespace

  std::string usage_text()
  {
    return "Usage:\n"
           "  indentsim run CASE.yaml [--output DIR] [--overwrite] [--compare-j2]\n"
           "  indentsim check CASE.yaml [--output DIR] [--compare-j2]\n"
           "  indentsim --help\n"
           "  indentsim --version\n";
  }

  std::string help_text()
  {
    return "indentsim: finite-element simulation of instrumented indentation\n"
           "(finite-strain solid, rigid analytic indenter, frictionless contact) and of the\n"
           "uniaxial tensile test used to calibrate the material (test: tensile).\n\n" +
           usage_text() +
           "\n"
           "Commands:\n"
           "  run CASE.yaml     Validate the case file, then compute. Writes into the output\n"
           "                    directory: load_penetration.csv, load_penetration.png,\n"
           "                    resolved_case.yaml (every default filled in), ParaView files\n"
           "                    (PVD + VTU/PVTU) and a log; for test: tensile\n"
           "                    stress_strain.csv, stress_strain.png instead of the first two.\n"
           "  check CASE.yaml   Validate the case file and print the resolved case; no\n"
           "                    computation, nothing is written.\n"
           "\n"
           "Options:\n"
           "  --output DIR      Write results to DIR instead of output.directory of the case.\n"
           "                    A relative path is relative to the current directory.\n"
           "  --overwrite       Replace the results of an earlier run in the output directory\n"
           "                    (without it, such a directory is refused; only indentsim's own\n"
           "                    output files are removed).\n"
           "  --compare-j2      Tensile test: also run J2 plasticity (material.young_modulus,\n"
           "                    poisson_ratio, yield_stress, hardening_modulus) on the same\n"
           "                    mesh and loading; writes stress_strain_j2.csv (sets the case\n"
           "                    key compare_j2: true).\n"
           "  -h, --help        Show this help.\n"
           "  --version         Show the version.\n"
           "\n"
           "Units everywhere (case file and outputs): lengths in um, forces in mN, stresses and\n"
           "moduli in GPa (1 GPa*um^2 = 1 mN).\n"
           "Parallel runs: mpirun -np 2 indentsim run CASE.yaml\n";
  }

  std::string version_text() { return std::string("indentsim ") + INDENTSIM_VERSION + "\n"; }

  CommandLineOptions parse_command_line(const std::vector<std::string> &arguments)
  {
    CommandLineOptions options;
    if (arguments.empty())
      bad_usage("no command given");

    const std::string &first = arguments[0];
    if (first == "--help" || first == "-h" || first == "help")
      {
        if (arguments.size() > 1)
          bad_usage("'" + first + "' takes no further arguments");
        options.command = Command::help;
        return options;
      }
    if (first == "--version")
      {
        if (arguments.size() > 1)
          bad_usage("'--version' takes no further arguments");
        options.command = Command::version;
        return options;
      }
    if (first == "run")
      options.command = Command::run;
    else if (first == "check")
      options.command = Command::check;
    else if (!first.empty() && first[0] == '-')
      bad_usage("unknown option '" + first + "' (a command comes first: run or check)");
    else
      bad_usage("unknown command '" + first + "'; allowed: run, check, --help, --version");

    for (std::size_t i = 1; i < arguments.size(); ++i)
      {
        const std::string &argument = arguments[i];
        if (argument == "--help" || argument == "-h")
          {
            options = CommandLineOptions{};
            options.command = Command::help;
            return options;
          }
        else if (argument == "--output" || argument.rfind("--output=", 0) == 0)
          {
            if (options.output_directory)
              bad_usage("--output given twice");
            std::string value;
            if (argument == "--output")
              {
                if (i + 1 >= arguments.size() || arguments[i + 1].empty() ||
                    arguments[i + 1].rfind("--", 0) == 0)
                  bad_usage("--output needs a directory: --output DIR");
                value = arguments[++i];
              }
            else
              value = argument.substr(std::string("--output=").size());
            if (value.empty())
              bad_usage("--output needs a non-empty directory: --output DIR");
            options.output_directory = value;
          }
        else if (argument == "--overwrite")
          {
            if (options.command != Command::run)
              bad_usage("--overwrite is only meaningful with 'run' ('check' writes nothing)");
            options.overwrite = true;
          }
        else if (argument == "--compare-j2")
          options.compare_j2 = true;
        else if (!argument.empty() && argument[0] == '-')
          bad_usage("unknown option '" + argument +
                    "'; allowed: --output DIR, --overwrite, --compare-j2");
        else if (options.case_file.empty())
          options.case_file = argument;
        else
          bad_usage("more than one case file given ('" + options.case_file + "' and '" +
                    argument + "')");
      }

    if (options.case_file.empty())
      bad_usage("'" + first + "' needs a case file: indentsim " + first + " CASE.yaml");
    return options;
  }

  CommandLineOptions parse_command_line(const int argc, const char *const *argv)
  {
    std::vector<std::string> arguments;
    for (int i = 1; i < argc; ++i)
      arguments.emplace_back(argv[i]);
    return parse_command_line(arguments);
  }
} // namespace indentsim::io
