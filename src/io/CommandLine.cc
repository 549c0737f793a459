// Command-line parsing for the indentsim executable. No physics here: main() only parses,
// reads the case and hands it on.
#include "io/CommandLine.h"
#include "io/TextNumber.h"
#include "io/Version.h"

#include <algorithm>
#include <cmath>

namespace indentsim::io
{
  namespace
  {
    [[noreturn]] void bad_usage(const std::string &problem)
    {
      throw CommandLineError(problem + "\n\n" + usage_text() +
                             "Run 'indentsim --help' for details.\n");
    }

    // The value of `option` given as "--option VALUE" or "--option=VALUE" at arguments[i]
    // (advances i past a separate value).
    std::string option_value(const std::vector<std::string> &arguments, std::size_t &i,
                             const std::string &option, const std::string &value_name)
    {
      const std::string &argument = arguments[i];
      std::string        value;
      if (argument == option)
        {
          if (i + 1 >= arguments.size() || arguments[i + 1].rfind("--", 0) == 0)
            bad_usage(option + " needs a value: " + option + " " + value_name);
          value = arguments[++i];
        }
      else
        value = argument.substr(option.size() + 1);
      if (value.empty())
        bad_usage(option + " needs a non-empty value: " + option + " " + value_name);
      return value;
    }

    // A whole number in [1, largest] for --ranks and --jobs.
    unsigned int positive_count(const std::string &option, const std::string &value,
                                const unsigned int largest)
    {
      unsigned long parsed = 0;
      std::size_t   used = 0;
      try
        {
          parsed = std::stoul(value, &used);
        }
      catch (const std::exception &)
        {
          used = 0;
        }
      if (used != value.size() || value[0] == '-' || value[0] == '+' || parsed < 1 ||
          parsed > largest)
        bad_usage(option + " " + value + ": expected a whole number from 1 to " +
                  std::to_string(largest));
      return static_cast<unsigned int>(parsed);
    }

    // indentsim study STUDY.yaml [--output DIR] [--ranks N] [--jobs J] [--launcher T]
    //                            [--dry-run] [--only NAME[,NAME...]]
    // indentsim calibrate CONFIG.yaml [--output DIR] [--ranks N] [--jobs J] [--launcher T]
    //                            [--dry-run]
    CommandLineOptions parse_study_arguments(const std::vector<std::string> &arguments)
    {
      CommandLineOptions options;
      const bool         calibrate = arguments[0] == "calibrate";
      const std::string  word = calibrate ? "calibrate" : "study";
      options.command = calibrate ? Command::calibrate : Command::study;
      bool ranks_given = false, jobs_given = false;
      for (std::size_t i = 1; i < arguments.size(); ++i)
        {
          const std::string &argument = arguments[i];
          const auto         is_option = [&argument](const std::string &option) {
            return argument == option || argument.rfind(option + "=", 0) == 0;
          };
          if (argument == "--help" || argument == "-h")
            {
              options = CommandLineOptions{};
              options.command = Command::help;
              return options;
            }
          else if (is_option("--output"))
            {
              if (options.output_directory)
                bad_usage("--output given twice");
              options.output_directory = option_value(arguments, i, "--output", "DIR");
            }
          else if (is_option("--ranks"))
            {
              if (ranks_given)
                bad_usage("--ranks given twice");
              ranks_given = true;
              options.study_ranks =
                  positive_count("--ranks", option_value(arguments, i, "--ranks", "N"), 1024);
            }
          else if (is_option("--jobs"))
            {
              if (jobs_given)
                bad_usage("--jobs given twice");
              jobs_given = true;
              options.study_jobs =
                  positive_count("--jobs", option_value(arguments, i, "--jobs", "J"), 64);
            }
          else if (is_option("--launcher"))
            {
              if (!options.study_launcher.empty())
                bad_usage("--launcher given twice");
              options.study_launcher = option_value(arguments, i, "--launcher", "TEMPLATE");
              if (options.study_launcher.find("{command}") == std::string::npos)
                bad_usage("--launcher " + options.study_launcher +
                          ": the template needs the word {command}, e.g. "
                          "'srun -n {ranks} {command}'");
            }
          else if (argument == "--dry-run")
            options.study_dry_run = true;
          else if (!calibrate && is_option("--only"))
            {
              const std::string list = option_value(arguments, i, "--only", "NAME[,NAME...]");
              std::size_t       start = 0;
              while (start <= list.size())
                {
                  const std::size_t comma = std::min(list.find(',', start), list.size());
                  const std::string name = list.substr(start, comma - start);
                  if (name.empty())
                    bad_usage("--only " + list +
                              ": an empty name; give case names or groups separated by commas");
                  options.study_only.push_back(name);
                  start = comma + 1;
                }
            }
          else if (!argument.empty() && argument[0] == '-')
            bad_usage("unknown option '" + argument + "' for '" + word +
                      "'; allowed: --output DIR, --ranks N, --jobs J, --launcher TEMPLATE, "
                      "--dry-run" +
                      (calibrate ? std::string() : std::string(", --only NAME[,NAME...]")));
          else if (options.study_file.empty())
            options.study_file = argument;
          else
            bad_usage("more than one " + std::string(calibrate ? "calibration" : "study") +
                      " file given ('" + options.study_file + "' and '" + argument + "')");
        }
      if (options.study_file.empty())
        bad_usage(calibrate
                      ? "'calibrate' needs a calibration file: indentsim calibrate CONFIG.yaml"
                      : "'study' needs a study file: indentsim study STUDY.yaml");
      return options;
    }

    double parse_number(const std::string &option, const std::string &text)
    {
      const std::optional<double> value = parse_finite_number(text);
      if (!value)
        bad_usage(option + " needs a number; got '" + text + "'");
      return *value;
    }

    CommandLineOptions parse_analyze(const std::vector<std::string> &arguments)
    {
      CommandLineOptions options;
      options.command = Command::analyze;
      AnalyzeOptions &a = options.analyze;
      for (std::size_t i = 1; i < arguments.size(); ++i)
        {
          const std::string &argument = arguments[i];
          const auto         value = [&]() -> std::string {
            if (i + 1 >= arguments.size() || arguments[i + 1].empty())
              bad_usage(argument + " needs a value");
            return arguments[++i];
          };
          if (argument == "--help" || argument == "-h")
            {
              options = CommandLineOptions{};
              options.command = Command::help;
              return options;
            }
          else if (argument == "--indenter")
            a.indenter_shape = value();
          else if (argument == "--indenter-case")
            a.indenter_case = value();
          else if (argument == "--epsilon")
            {
              a.epsilon = parse_number(argument, value());
              if (!(*a.epsilon > 0 && *a.epsilon <= 1))
                bad_usage("--epsilon must lie in (0, 1]");
            }
          else if (argument == "--beta")
            {
              a.beta = parse_number(argument, value());
              if (!(a.beta > 0))
                bad_usage("--beta must be positive");
            }
          else if (argument == "--fit-range")
            {
              const std::string text = value();
              const auto        comma = text.find(',');
              if (comma == std::string::npos)
                bad_usage("--fit-range needs LO,HI (fractions of P_max); got '" + text + "'");
              a.fit_lower = parse_number(argument, text.substr(0, comma));
              a.fit_upper = parse_number(argument, text.substr(comma + 1));
              if (!(a.fit_lower >= 0 && a.fit_lower < a.fit_upper && a.fit_upper <= 1))
                bad_usage("--fit-range LO,HI needs 0 <= LO < HI <= 1; got '" + text + "'");
            }
          else if (argument == "--poisson")
            {
              a.sample_poisson_ratio = parse_number(argument, value());
              if (!(*a.sample_poisson_ratio > -1 && *a.sample_poisson_ratio < 0.5))
                bad_usage("--poisson must lie in (-1, 0.5)");
            }
          else if (argument == "--indenter-modulus")
            {
              a.indenter_modulus = parse_number(argument, value());
              if (!(*a.indenter_modulus > 0))
                bad_usage("--indenter-modulus must be positive [GPa]");
            }
          else if (argument == "--indenter-poisson")
            {
              a.indenter_poisson_ratio = parse_number(argument, value());
              if (!(a.indenter_poisson_ratio > -1 && a.indenter_poisson_ratio < 0.5))
                bad_usage("--indenter-poisson must lie in (-1, 0.5)");
            }
          else if (argument == "--output")
            options.output_directory = value();
          else if (argument == "--depth-column")
            a.depth_column = value();
          else if (argument == "--force-column")
            a.force_column = value();
          else if (argument == "--depth-unit")
            a.depth_unit = value();
          else if (argument == "--force-unit")
            a.force_unit = value();
          else if (!argument.empty() && argument[0] == '-')
            bad_usage("unknown option '" + argument + "' for analyze");
          else if (a.target.empty())
            a.target = argument;
          else
            bad_usage("analyze takes one run directory or CSV ('" + a.target + "' and '" +
                      argument + "' given)");
        }
      if (a.target.empty())
        bad_usage("'analyze' needs a run directory or a CSV: indentsim analyze RUN_DIR_OR_CSV");
      if (!a.indenter_shape.empty() && !a.indenter_case.empty())
        bad_usage("give either --indenter or --indenter-case, not both");
      return options;
    }
  } // namespace

  std::string usage_text()
  {
    return "Usage:\n"
           "  indentsim run CASE.yaml [--output DIR] [--overwrite | --resume] [--compare-j2]\n"
           "  indentsim check CASE.yaml [--output DIR] [--compare-j2]\n"
           "  indentsim analyze RUN_DIR_OR_CSV [--indenter SHAPE | --indenter-case CASE.yaml]\n"
           "                    [--epsilon E] [--beta B] [--fit-range LO,HI] [--poisson NU]\n"
           "                    [--indenter-modulus E --indenter-poisson NU] [--output DIR]\n"
           "                    [--depth-column NAME] [--force-column NAME]\n"
           "                    [--depth-unit um|nm|mm] [--force-unit mN|uN|N]\n"
           "  indentsim study STUDY.yaml [--output DIR] [--ranks N] [--jobs J] [--dry-run]\n"
           "                  [--only NAME[,NAME...]] [--launcher TEMPLATE]\n"
           "  indentsim calibrate CONFIG.yaml [--output DIR] [--ranks N] [--jobs J] [--dry-run]\n"
           "                  [--launcher TEMPLATE]\n"
           "  indentsim --help\n"
           "  indentsim --version\n";
  }

  std::string help_text()
  {
    return "indentsim: finite-element simulation of instrumented indentation\n"
           "(finite-strain neo-Hookean, J2 or crystal-plasticity solid, rigid analytic indenter,\n"
           "frictionless or Coulomb contact; 3D or axisymmetric) and of the uniaxial tensile\n"
           "test used to calibrate the material (test: tensile). Units: um, mN, GPa.\n\n" +
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
           "  analyze RUN_DIR_OR_CSV\n"
           "                    Oliver-Pharr analysis of the unloading curve: power-law fit on\n"
           "                    the upper unloading (--fit-range, default 0.5,1 of P_max),\n"
           "                    stiffness, contact depth, area from the indenter's area\n"
           "                    function, hardness, reduced modulus, residual depth, plastic\n"
           "                    work ratio; for a run directory also the simulation's true\n"
           "                    contact area (the method's pile-up error). Writes\n"
           "                    oliver_pharr.json and oliver_pharr.png into the run directory\n"
           "                    or next to the CSV (or --output DIR), replacing only those two.\n"
           "                    A run directory takes its indenter from resolved_case.yaml; a\n"
           "                    CSV needs --indenter (vickers, berkovich, cone, rounded_cone,\n"
           "                    sphere, flat_punch with their default keys) or --indenter-case\n"
           "                    (the indenter block of a case file). CSV columns: the first\n"
           "                    named depth*/h* and force*/load*/P*, units from the name\n"
           "                    (depth_nm, force_uN, 'depth (um)') or --depth-unit/--force-unit.\n"
           "                    epsilon defaults to 0.727 (cones), 1 (flat punch), 0.75 (others);\n"
           "                    --poisson NU adds the sample's Young modulus; the indenter is\n"
           "                    rigid unless --indenter-modulus (diamond: 1141, nu 0.07).\n"
           "  study STUDY.yaml  Run the cases of a study file (a base case file plus overrides\n"
           "                    per case) and write report.md (+ report.html, PNG figures) into\n"
           "                    the study's output directory. Each case runs as its own process\n"
           "                    in cases/<name>-<key>/, <key> a hash of its resolved case; a\n"
           "                    rerun skips finished cases and resumes interrupted ones\n"
           "                    from their checkpoint (same --ranks), else reruns them.\n"
           "                    Exit code 3 if a case failed (the others still run).\n"
           "  calibrate CONFIG.yaml\n"
           "                    Fit numeric keys of a base case (bounded) to measured curves\n"
           "                    by weighted least squares (Ceres Solver, Levenberg-Marquardt,\n"
           "                    Jacobians by finite differences run as parallel cases). Every\n"
           "                    forward run is a study case: cached by the hash of its resolved\n"
           "                    case, so a rerun continues where an interrupted one stopped.\n"
           "                    Writes calibration.json (values, standard errors, 95 %\n"
           "                    intervals, correlations, identifiability), iterations.csv,\n"
           "                    the fitted curves and report.md; docs/calibration.md.\n"
           "\n"
           "Options:\n"
           "  --output DIR      Write results to DIR instead of output.directory of the case.\n"
           "                    A relative path is relative to the current directory.\n"
           "  --overwrite       Replace the results of an earlier run in the output directory\n"
           "                    (without it, such a directory is refused; only indentsim's own\n"
           "                    output files are removed).\n"
           "  --resume          Indentation: continue a run stopped with Ctrl-C (SIGINT) or\n"
           "                    SIGTERM (exit code 130) from the checkpoint in its output\n"
           "                    directory (output.checkpoint_interval_s: also written every\n"
           "                    300 s). Needs the same case file and the same number of MPI\n"
           "                    ranks; not with --overwrite. A refused resume (it names the\n"
           "                    keys that differ) and a resume of a finished run change\n"
           "                    nothing.\n"
           "  --compare-j2      Tensile test: also run J2 plasticity (material.young_modulus,\n"
           "                    poisson_ratio, yield_stress, hardening_modulus) on the same\n"
           "                    mesh and loading; writes stress_strain_j2.csv (sets the case\n"
           "                    key compare_j2: true).\n"
           "  study options:    --output DIR replaces the study's output directory;\n"
           "                    --ranks N runs each case under mpirun -np N (default 1);\n"
           "                    --jobs J runs up to J cases side by side (default 1);\n"
           "                    --dry-run validates and lists the cases (finished or to run);\n"
           "                    --only NAME[,NAME...] runs only these cases or groups;\n"
           "                    --launcher TEMPLATE starts each case through a scheduler,\n"
           "                    {command} and {ranks} replaced: 'srun -n {ranks} {command}'.\n"
           "  calibrate options: as for study, without --only; --dry-run checks the\n"
           "                    configuration and the data and runs nothing.\n"
           "  -h, --help        Show this help.\n"
           "  --version         Show the version.\n"
           "\n"
           "Exit codes: 0 success; 1 bad input (case, study or measured-curve file, output\n"
           "directory); 2 bad command line; 3 the computation stopped (study: a case failed);\n"
           "4 an output file could not be written (the message names the file and the system's\n"
           "reason, e.g. a full disk; the files written before and the last checkpoint stay);\n"
           "5 the contact outgrew the refined region (the message names the keys to change);\n"
           "130 stopped by Ctrl-C or SIGTERM after a checkpoint.\n"
           "\n"
           "Units everywhere (case file and outputs): lengths in um, forces in mN, stresses and\n"
           "moduli in GPa (1 GPa*um^2 = 1 mN).\n"
           "Parallel runs: mpirun -np 2 indentsim run CASE.yaml\n";
  }

  std::string version_text()
  {
    return std::string("indentsim ") + indentsim::version() + "\n";
  }

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
    if (first == "analyze")
      return parse_analyze(arguments);
    if (first == "study" || first == "calibrate")
      return parse_study_arguments(arguments);
    if (first == "run")
      options.command = Command::run;
    else if (first == "check")
      options.command = Command::check;
    else if (!first.empty() && first[0] == '-')
      bad_usage("unknown option '" + first +
                "' (a command comes first: run, check, analyze, study or calibrate)");
    else
      bad_usage("unknown command '" + first +
                "'; allowed: run, check, analyze, study, calibrate, --help, --version");

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
        else if (argument == "--resume")
          {
            if (options.command != Command::run)
              bad_usage("--resume is only meaningful with 'run'");
            options.resume = true;
          }
        else if (argument == "--compare-j2")
          options.compare_j2 = true;
        else if (!argument.empty() && argument[0] == '-')
          bad_usage("unknown option '" + argument +
                    "'; allowed: --output DIR, --overwrite, --resume, --compare-j2");
        else if (options.case_file.empty())
          options.case_file = argument;
        else
          bad_usage("more than one case file given ('" + options.case_file + "' and '" + argument +
                    "')");
      }

    if (options.case_file.empty())
      bad_usage("'" + first + "' needs a case file: indentsim " + first + " CASE.yaml");
    if (options.resume && options.overwrite)
      bad_usage("--resume continues the run in the output directory, --overwrite replaces it; "
                "give one of them");
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
