// Runs a study's cases as child processes (posix_spawn), side by side up to --jobs, and writes
// the study index and the report. See StudyRunner.h. Units: um, mN, GPa; times in s.
#include "study/StudyRunner.h"

#include "case/CaseFile.h"
#include "io/JsonText.h"
#include "io/Version.h"
#include "output/PythonScripts.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <optional>
#include <sstream>
#include <system_error>
#include <thread>

extern char **environ;

namespace indentsim::study
{
  namespace
  {
    namespace fs = std::filesystem;
    using Clock = std::chrono::steady_clock;

    volatile std::sig_atomic_t stop_requested = 0;
    extern "C" void            request_stop(int)
    {
      stop_requested = 1;
    }

    std::string read_text(const fs::path &path)
    {
      std::ifstream      in(path);
      std::ostringstream text;
      text << in.rdbuf();
      return text.str();
    }

    // The number after "key": in a flat JSON text written by indentsim, if present.
    std::optional<double> json_number(const std::string &text, const std::string &key)
    {
      const std::string quoted = "\"" + key + "\":";
      const std::size_t found = text.find(quoted);
      if (found == std::string::npos)
        return std::nullopt;
      const char  *start = text.c_str() + found + quoted.size();
      char        *end = nullptr;
      const double value = std::strtod(start, &end);
      if (end == start)
        return std::nullopt;
      return value;
    }

    using io::json_string;

    std::string json_number_text(const double value)
    {
      std::ostringstream out;
      out << std::setprecision(12) << value;
      return out.str();
    }

    std::string json_string_list(const std::vector<std::string> &words)
    {
      std::string text = "[";
      for (std::size_t i = 0; i < words.size(); ++i)
        text += (i == 0 ? "" : ", ") + json_string(words[i]);
      return text + "]";
    }

    std::string shell_words(const std::vector<std::string> &words)
    {
      std::string text;
      for (const auto &word : words)
        {
          const bool plain = !word.empty() && word.find_first_of(" \t\"'$\\") == std::string::npos;
          text += (text.empty() ? "" : " ") + (plain ? word : "'" + word + "'");
        }
      return text;
    }

    std::string seconds_text(const double seconds)
    {
      std::ostringstream out;
      out << std::fixed << std::setprecision(1) << seconds << " s";
      return out.str();
    }

    // The environment this process was started with (/proc/self/environ: MPI_Init may have
    // added variables of this process's own MPI job, which a child must not inherit).
    std::vector<std::string> start_environment()
    {
      std::vector<std::string> variables;
      std::ifstream            in("/proc/self/environ", std::ios::binary);
      std::string              entry;
      while (in && std::getline(in, entry, '\0'))
        if (!entry.empty())
          variables.push_back(entry);
      if (variables.empty())
        for (char **e = environ; e != nullptr && *e != nullptr; ++e)
          variables.emplace_back(*e);
      return variables;
    }

    bool has_variable(const std::vector<std::string> &variables, const std::string &name)
    {
      return std::any_of(variables.begin(), variables.end(),
                         [&name](const std::string &v) { return v.rfind(name + "=", 0) == 0; });
    }

    void set_default(std::vector<std::string> &variables, const std::string &name,
                     const std::string &value)
    {
      if (!has_variable(variables, name))
        variables.push_back(name + "=" + value);
    }

    // Starts `arguments` (searched on PATH) with `variables`; stdout and stderr go to `log`
    // (truncated) unless it is empty, stdin is /dev/null. Returns the pid, or -1 with `error`.
    pid_t spawn(const std::vector<std::string> &arguments,
                const std::vector<std::string> &variables, const std::string &log,
                std::string &error)
    {
      posix_spawn_file_actions_t actions;
      posix_spawn_file_actions_init(&actions);
      posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
      if (!log.empty())
        {
          posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(),
                                           O_WRONLY | O_CREAT | O_TRUNC, 0644);
          posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
        }
      std::vector<char *> argv, envp;
      for (const auto &argument : arguments)
        argv.push_back(const_cast<char *>(argument.c_str()));
      argv.push_back(nullptr);
      for (const auto &variable : variables)
        envp.push_back(const_cast<char *>(variable.c_str()));
      envp.push_back(nullptr);
      pid_t     pid = -1;
      const int code = posix_spawnp(&pid, argv[0], &actions, nullptr, argv.data(), envp.data());
      posix_spawn_file_actions_destroy(&actions);
      if (code != 0)
        {
          error = "cannot start '" + arguments[0] + "': " + std::strerror(code);
          return -1;
        }
      return pid;
    }

    // Exit code of a wait status; 128 + signal for a killed process.
    int exit_code_of(const int status)
    {
      if (WIFEXITED(status))
        return WEXITSTATUS(status);
      if (WIFSIGNALED(status))
        return 128 + WTERMSIG(status);
      return 255;
    }

    std::string self_executable()
    {
      std::error_code error;
      const fs::path  path = fs::read_symlink("/proc/self/exe", error);
      return error ? std::string("indentsim") : path.string();
    }

    // The headline result of a finished case, for the progress line.
    std::string result_summary(const StudyCase &study_case)
    {
      const std::string summary =
          read_text(fs::path(study_case.directory) / io::output_files::run_summary);
      std::ostringstream out;
      out << std::setprecision(6);
      if (const auto force = json_number(summary, "force_at_max_depth_mN"))
        out << "force at maximum depth " << *force << " mN";
      else if (const auto depth = json_number(summary, "depth_at_max_force_um"))
        out << "depth at maximum force " << *depth << " um";
      else if (const auto stress = json_number(summary, "final_true_stress_GPa"))
        out << "final true stress " << *stress << " GPa";
      // The run's warnings by topic (run_summary.json holds their texts).
      const std::vector<std::string> topics = warning_topics(study_case.directory);
      for (std::size_t i = 0; i < topics.size(); ++i)
        out << (i == 0 ? "; WARNING " : ", ") << topics[i];
      if (!topics.empty())
        out << " (see its run_summary.json)";
      return out.str();
    }
  } // namespace

  std::string to_string(const CaseState state)
  {
    switch (state)
      {
      case CaseState::finished:
        return "finished";
      case CaseState::failed:
        return "failed";
      case CaseState::unfinished:
        return "unfinished";
      default:
        return "not run";
      }
  }

  CaseState case_state(const StudyCase &study_case)
  {
    const fs::path  directory(study_case.directory);
    std::error_code error;
    if (!fs::is_directory(directory, error))
      return CaseState::not_started;
    const fs::path mark = directory / study_files::case_mark;
    if (!fs::exists(mark, error))
      return CaseState::unfinished;
    const std::string text = read_text(mark);
    const bool        completed = text.find("\"completed\": true") != std::string::npos;
    if (completed && fs::exists(directory / io::output_files::run_summary, error))
      return CaseState::finished;
    return completed ? CaseState::unfinished : CaseState::failed;
  }

  std::string last_lines(const std::string &path, const std::size_t count)
  {
    std::istringstream      in(read_text(path));
    std::deque<std::string> lines;
    std::string             line;
    while (std::getline(in, line))
      {
        lines.push_back(line);
        if (lines.size() > count)
          lines.pop_front();
      }
    std::string text;
    for (const auto &l : lines)
      text += "    | " + l + "\n";
    return text;
  }

  std::vector<std::string> warning_topics(const std::string &run_directory)
  {
    const std::string summary = read_text(fs::path(run_directory) / io::output_files::run_summary);
    const std::string key = "{\"topic\": \"";
    std::vector<std::string> topics;
    for (std::size_t at = summary.find(key); at != std::string::npos;
         at = summary.find(key, at + 1))
      {
        const std::size_t start = at + key.size();
        topics.push_back(summary.substr(start, summary.find('"', start) - start));
      }
    return topics;
  }

  int case_exit_code(const StudyCase &study_case)
  {
    const fs::path  mark = fs::path(study_case.directory) / study_files::case_mark;
    std::error_code error;
    if (!fs::exists(mark, error))
      return -1;
    const std::string text = read_text(mark);
    const std::string key = "\"exit_code\": ";
    const auto        at = text.find(key);
    return at == std::string::npos ? -1 : std::atoi(text.c_str() + at + key.size());
  }

  StudyRunner::StudyRunner(const Study &study, const StudyRunSettings &settings, std::ostream &out)
    : study_(study)
    , settings_(settings)
    , out_(out)
    , selected_(study.cases.size(), settings.only.empty())
  {
    if (!settings_.launcher.empty())
      launch_command(settings_.launcher, {},
                     settings_.ranks); // refuses a template without {command}
    if (settings_.executable.empty())
      settings_.executable = self_executable();
    if (settings_.report_script.empty() && !settings_.batch) // a batch writes no report
      settings_.report_script = indentsim::output::python_script("study_report.py");
    for (const auto &name : settings_.only)
      {
        bool found = false;
        for (std::size_t i = 0; i < study_.cases.size(); ++i)
          {
            const auto &c = study_.cases[i];
            if (c.name == name ||
                std::find(c.groups.begin(), c.groups.end(), name) != c.groups.end())
              {
                selected_[i] = true;
                found = true;
              }
          }
        if (!found)
          {
            std::vector<std::string> names;
            for (const auto &c : study_.cases)
              names.push_back(c.name);
            std::string allowed;
            for (const auto &n : names)
              allowed += (allowed.empty() ? "" : ", ") + n;
            throw StudyFileError(study_.source_file + ": --only " + name +
                                 ": no case or group of that name; cases: " + allowed +
                                 "; groups: " + io::join(known_groups, ", "));
          }
      }
  }

  std::vector<std::string> launch_command(const std::string              &launcher,
                                          const std::vector<std::string> &command,
                                          const unsigned int              ranks)
  {
    std::istringstream       words(launcher);
    std::vector<std::string> launched;
    bool                     has_command = false;
    for (std::string word; words >> word;)
      {
        if (word == "{command}")
          {
            launched.insert(launched.end(), command.begin(), command.end());
            has_command = true;
            continue;
          }
        for (std::size_t at; (at = word.find("{ranks}")) != std::string::npos;)
          word.replace(at, 7, std::to_string(ranks));
        launched.push_back(word);
      }
    if (!has_command)
      throw StudyFileError("--launcher '" + launcher +
                           "': the template must have the word {command} (where the case's "
                           "command goes) and may have {ranks}, e.g. 'srun -n {ranks} {command}'");
    return launched;
  }

  std::vector<std::string> StudyRunner::case_command(const StudyCase &study_case) const
  {
    const std::vector<std::string> command = {
        settings_.executable, "run",
        (fs::path(study_case.directory) / study_files::case_input).string(),
        resumable(study_case) ? "--resume" : "--overwrite"};
    if (!settings_.launcher.empty())
      return launch_command(settings_.launcher, command, settings_.ranks);
    if (settings_.ranks == 1)
      return command;
    return launch_command("mpirun -np {ranks} {command}", command, settings_.ranks);
  }

  // An interrupted indentation case continues from its checkpoint when that was written by
  // the same number of MPI ranks (rank_<N-1>.bin present, rank_<N>.bin absent); otherwise it
  // reruns from the start.
  bool StudyRunner::resumable(const StudyCase &study_case) const
  {
    const fs::path checkpoint =
        fs::path(study_case.directory) / io::output_files::checkpoint_directory;
    const auto rank_file = [&](const unsigned int rank) {
      return checkpoint / ("rank_" + std::to_string(rank) + ".bin");
    };
    std::error_code error;
    return fs::exists(rank_file(settings_.ranks - 1), error) &&
           !fs::exists(rank_file(settings_.ranks), error);
  }

  void StudyRunner::print_plan(const std::vector<CaseState> &states) const
  {
    std::size_t width = 4;
    for (const auto &c : study_.cases)
      width = std::max(width, c.name.size());
    out_ << "Study " << study_.source_file << ": " << study_.cases.size() << " cases, output "
         << study_.output_directory << "\n";
    for (std::size_t i = 0; i < study_.cases.size(); ++i)
      {
        const auto &c = study_.cases[i];
        std::string action;
        if (!selected_[i])
          action = "not selected (--only)";
        else if (states[i] == CaseState::finished)
          action = "finished: skipped";
        else if (states[i] == CaseState::unfinished)
          action = resumable(c) ? "interrupted: resumed from its checkpoint"
                                : "interrupted: rerun from the start";
        else if (states[i] == CaseState::failed)
          action = "failed before: rerun";
        else
          action = "to run";
        std::string groups;
        for (const auto &g : c.groups)
          groups += (groups.empty() ? "" : ",") + g;
        out_ << "  " << std::left << std::setw(int(width)) << c.name << "  " << c.key << "  "
             << std::setw(24) << (groups.empty() ? "-" : groups) << "  " << action << "\n"
             << std::right;
      }
  }

  int StudyRunner::run()
  {
    const std::vector<std::string> start_variables = start_environment();
    for (const std::string name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK"})
      if (has_variable(start_variables, name))
        throw StudyFileError("indentsim study starts each case itself and must not run under "
                             "mpirun; use --ranks N to run every case on N MPI ranks");

    Progress progress;
    for (const auto &c : study_.cases)
      progress.states.push_back(case_state(c));
    progress.ran_now.assign(study_.cases.size(), false);
    if (!settings_.batch)
      print_plan(progress.states);

    std::vector<std::size_t> to_run;
    std::size_t              n_skipped = 0;
    for (std::size_t i = 0; i < study_.cases.size(); ++i)
      if (selected_[i])
        {
          if (progress.states[i] == CaseState::finished)
            ++n_skipped;
          else
            to_run.push_back(i);
        }

    if (settings_.dry_run)
      {
        out_ << "Dry run: " << to_run.size() << " case(s) would run, " << n_skipped
             << " finished case(s) would be skipped. Commands:\n";
        for (const std::size_t i : to_run)
          out_ << "  " << shell_words(case_command(study_.cases[i])) << "\n";
        out_ << "Nothing was run or written.\n";
        return exit_ok;
      }

    prepare_output_directory();
    const auto study_start = Clock::now();
    progress.n_to_run = to_run.size();
    if (!settings_.batch)
      out_ << n_skipped << " finished case(s) skipped, " << to_run.size() << " to run\n"
           << std::flush;
    if (!run_cases(to_run, child_environment(start_variables), progress))
      return exit_interrupted;
    if (settings_.batch)
      return progress.n_failed > 0 ? exit_case_failed : exit_ok;

    write_index(progress.states, progress.ran_now);
    const int report_status = write_report();

    const double total = std::chrono::duration<double>(Clock::now() - study_start).count();
    out_ << "Study done in " << seconds_text(total) << ": " << (progress.n_done - progress.n_failed)
         << " case(s) run, " << n_skipped << " skipped (finished earlier), " << progress.n_failed
         << " failed.\n";
    if (report_status == 0)
      out_ << "Report: " << (fs::path(study_.output_directory) / "report.md").string() << "\n";
    out_ << std::flush;
    if (progress.n_failed > 0)
      return exit_case_failed;
    return report_status == 0 ? exit_ok : exit_report_failed;
  }

  void StudyRunner::prepare_output_directory() const
  {
    // The output directory, a copy of the study file, and the case directories.
    std::error_code error;
    fs::create_directories(fs::path(study_.output_directory) / "cases", error);
    if (error)
      throw StudyFileError("study output directory '" + study_.output_directory +
                           "' cannot be created: " + error.message());
    if (settings_.batch)
      return;
    std::ofstream copy(fs::path(study_.output_directory) / study_files::study_copy);
    copy << "# Copy of the study file " << fs::absolute(study_.source_file).string()
         << "\n# (base paths are relative to that file's directory).\n"
         << read_text(study_.source_file);
    if (!copy)
      throw StudyFileError("study output directory '" + study_.output_directory +
                           "' is not writable");
  }

  std::vector<std::string>
  StudyRunner::child_environment(const std::vector<std::string> &start_variables) const
  {
    // The starting environment, one BLAS thread, and the cores shared among the cases running
    // side by side (deal.II takes the smaller of this and its own count).
    std::vector<std::string> variables = start_variables;
    const unsigned int       cores = std::max(1u, std::thread::hardware_concurrency());
    set_default(variables, "OMP_NUM_THREADS", "1");
    if (settings_.jobs > 1)
      set_default(variables, "DEAL_II_NUM_THREADS",
                  std::to_string(std::max(1u, cores / (settings_.jobs * settings_.ranks))));
    if (settings_.ranks > 1)
      {
        if (::geteuid() == 0)
          {
            set_default(variables, "OMPI_ALLOW_RUN_AS_ROOT", "1");
            set_default(variables, "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1");
          }
        if (settings_.ranks > cores)
          set_default(variables, "OMPI_MCA_rmaps_base_oversubscribe", "1");
      }
    return variables;
  }

  bool StudyRunner::run_cases(const std::vector<std::size_t> &to_run,
                              const std::vector<std::string> &variables, Progress &progress)
  {
    struct sigaction action = {}, old_interrupt = {}, old_terminate = {};
    action.sa_handler = request_stop;
    sigemptyset(&action.sa_mask);
    stop_requested = 0;
    sigaction(SIGINT, &action, &old_interrupt);
    sigaction(SIGTERM, &action, &old_terminate);

    // Up to settings_.jobs children at a time, polled every 50 ms.
    std::vector<Running> running;
    std::size_t          next = 0;
    while ((next < to_run.size() || !running.empty()) && stop_requested == 0)
      {
        while (next < to_run.size() && running.size() < settings_.jobs)
          if (const auto job = start_case(to_run[next++], variables, progress))
            running.push_back(*job);

        std::this_thread::sleep_for(std::chrono::milliseconds(50));
        for (auto job = running.begin(); job != running.end();)
          {
            int         status = 0;
            const pid_t done = ::waitpid(job->pid, &status, WNOHANG);
            if (done == job->pid || (done < 0 && errno != EINTR))
              {
                finish_case(*job, done == job->pid ? exit_code_of(status) : 255, progress);
                job = running.erase(job);
              }
            else
              ++job;
          }
      }

    const bool interrupted = stop_requested != 0;
    if (interrupted)
      {
        out_ << "Interrupted: stopping " << running.size() << " running case(s); "
             << "rerun the same command to continue (finished cases are kept).\n"
             << std::flush;
        for (const auto &job : running)
          ::kill(job.pid, SIGTERM);
        for (const auto &job : running)
          {
            int status = 0;
            ::waitpid(job.pid, &status, 0);
          }
      }
    sigaction(SIGINT, &old_interrupt, nullptr);
    sigaction(SIGTERM, &old_terminate, nullptr);
    return !interrupted;
  }

  std::optional<StudyRunner::Running>
  StudyRunner::start_case(const std::size_t index, const std::vector<std::string> &variables,
                          Progress &progress)
  {
    const StudyCase &c = study_.cases[index];
    const fs::path   directory(c.directory);
    std::error_code  error;
    fs::create_directories(directory, error);
    fs::remove(directory / study_files::case_mark, error);
    Running     job{index, -1, Clock::now()};
    std::string problem;
    try
      {
        io::write_resolved_case(c.resolved, (directory / study_files::case_input).string());
        const auto command = case_command(c);
        out_ << "run  " << c.name << " (" << to_string(progress.states[index])
             << "): " << shell_words(command) << "\n"
             << std::flush;
        job.pid =
            spawn(command, variables, (directory / study_files::console_log).string(), problem);
      }
    catch (const std::exception &e)
      {
        problem = e.what();
      }
    if (job.pid >= 0)
      return job;
    std::ofstream log(directory / study_files::console_log);
    log << "indentsim study: " << problem << "\n";
    log.close();
    finish_case(job, 127, progress);
    return std::nullopt;
  }

  void StudyRunner::finish_case(const Running &job, const int exit_code, Progress &progress)
  {
    const StudyCase &c = study_.cases[job.index];
    const double     seconds = std::chrono::duration<double>(Clock::now() - job.start).count();
    const fs::path   directory(c.directory);
    const bool completed = exit_code == 0 && fs::exists(directory / io::output_files::run_summary);
    std::ofstream mark(directory / study_files::case_mark);
    mark << "{\n"
         << "  \"units\": \"times in s\",\n"
         << "  \"name\": " << json_string(c.name) << ",\n"
         << "  \"key\": " << json_string(c.key) << ",\n"
         << "  \"completed\": " << (completed ? "true" : "false") << ",\n"
         << "  \"exit_code\": " << exit_code << ",\n"
         << "  \"wall_time_s\": " << json_number_text(seconds) << ",\n"
         << "  \"mpi_ranks\": " << settings_.ranks << ",\n"
         << "  \"command\": " << json_string(shell_words(case_command(c))) << ",\n"
         << "  \"version\": " << json_string(std::string("indentsim ") + indentsim::version())
         << "\n}\n";
    mark.close();
    ++progress.n_done;
    progress.ran_now[job.index] = true;
    progress.states[job.index] = completed ? CaseState::finished : CaseState::failed;
    const std::string counter =
        "[" + std::to_string(progress.n_done) + "/" + std::to_string(progress.n_to_run) + "] ";
    if (completed)
      out_ << counter << c.name << ": finished in " << seconds_text(seconds) << "; "
           << result_summary(c) << "\n";
    else
      {
        ++progress.n_failed;
        out_ << counter << c.name << ": FAILED (exit code " << exit_code
             << (exit_code == 0 ? ", but no run_summary.json" : std::string()) << ") after "
             << seconds_text(seconds) << "; console output in "
             << (directory / study_files::console_log).string() << ", last lines:\n"
             << last_lines((directory / study_files::console_log).string(), 12);
      }
    out_ << std::flush;
  }

  void StudyRunner::write_index(const std::vector<CaseState> &states,
                                const std::vector<bool>      &ran_now) const
  {
    const fs::path path = fs::path(study_.output_directory) / study_files::index;
    std::ofstream  out(path);
    const auto    &report = study_.report;
    out << "{\n"
        << "  \"units\": \"lengths um, forces mN, stresses GPa, times s\",\n"
        << "  \"study_file\": " << json_string(fs::absolute(study_.source_file).string()) << ",\n"
        << "  \"output_directory\": " << json_string(study_.output_directory) << ",\n"
        << "  \"version\": " << json_string(std::string("indentsim ") + indentsim::version())
        << ",\n"
        << "  \"mpi_ranks\": " << settings_.ranks << ",\n"
        << "  \"jobs\": " << settings_.jobs << ",\n"
        << "  \"report\": {\n"
        << "    \"title\": " << json_string(report.title) << ",\n"
        << "    \"depth_at_force_mN\": " << json_number_text(report.depth_at_force_mN) << ",\n"
        << "    \"tensile_strains\": [";
    for (std::size_t i = 0; i < report.tensile_strains.size(); ++i)
      out << (i == 0 ? "" : ", ") << json_number_text(report.tensile_strains[i]);
    out << "],\n"
        << "    \"paper_max_depth_um\": " << json_number_text(report.paper_max_depth_um) << ",\n"
        << "    \"paper_note\": " << json_string(report.paper_note) << ",\n"
        << "    \"paper_forces_mN\": {";
    bool first_group = true;
    for (const auto &[group, forces] : report.paper_forces_mN)
      {
        out << (first_group ? "" : ", ") << json_string(group) << ": {";
        bool first = true;
        for (const auto &[elements, force] : forces)
          {
            out << (first ? "" : ", ") << json_string(std::to_string(elements)) << ": "
                << json_number_text(force);
            first = false;
          }
        out << "}";
        first_group = false;
      }
    out << "}\n  },\n  \"cases\": [\n";
    for (std::size_t i = 0; i < study_.cases.size(); ++i)
      {
        const StudyCase &c = study_.cases[i];
        const io::Case  &resolved = c.resolved;
        const auto      &orientation = resolved.material.orientation;
        const auto       numbers = [](const auto &values) {
          std::string text = "[";
          for (std::size_t k = 0; k < values.size(); ++k)
            text += (k == 0 ? "" : ", ") + json_number_text(values[k]);
          return text + "]";
        };
        out << "    {\"name\": " << json_string(c.name) << ", \"label\": " << json_string(c.label)
            << ", \"groups\": " << json_string_list(c.groups) << ",\n"
            << "     \"key\": " << json_string(c.key) << ", \"directory\": "
            << json_string(
                   fs::path(c.directory).lexically_relative(study_.output_directory).string())
            << ", \"status\": " << json_string(to_string(states[i]))
            << ", \"ran_now\": " << (ran_now[i] ? "true" : "false") << ",\n"
            << "     \"base_file\": " << json_string(c.base_file)
            << ", \"overrides\": " << json_string(c.overrides_text) << ",\n"
            << "     \"test\": " << json_string(io::to_string(resolved.test))
            << ", \"model\": " << json_string(io::to_string(resolved.material.model))
            << ", \"compare_j2\": " << (resolved.compare_j2 ? "true" : "false")
            << ", \"contact_elements\": " << resolved.specimen.contact_elements
            << ", \"refined_region_um\": " << numbers(resolved.specimen.refined_region)
            << ", \"symmetry\": " << json_string(io::to_string(resolved.specimen.symmetry))
            << ", \"indenter\": " << json_string(io::to_string(resolved.indenter.shape))
            << ", \"control\": " << json_string(io::to_string(resolved.loading.control))
            << ", \"max_depth_um\": " << json_number_text(resolved.loading.max_depth) << ",\n"
            << "     \"orientation\": "
            << (orientation.kind == io::OrientationKind::surface_normal
                    ? "{\"surface_normal\": " + numbers(orientation.surface_normal) +
                          ", \"reference_direction\": " + numbers(orientation.reference_direction) +
                          "}"
                    : "{\"euler_bunge_deg\": " + numbers(orientation.euler_bunge_deg) + "}")
            << ", \"grains\": " << json_string(io::to_string(resolved.specimen.grains))
            << ", \"seed\": " << resolved.specimen.seed
            << ", \"elements_per_side\": " << resolved.specimen.elements_per_side
            << ", \"max_strain\": " << json_number_text(resolved.loading.max_strain) << "}"
            << (i + 1 < study_.cases.size() ? "," : "") << "\n";
      }
    out << "  ]\n}\n";
    if (!out)
      throw StudyFileError("cannot write '" + path.string() + "'");
  }

  int StudyRunner::write_report() const
  {
    std::vector<std::string> variables = start_environment();
    std::string              problem;
    out_ << "Writing the report: python3 " << settings_.report_script << " "
         << study_.output_directory << "\n"
         << std::flush;
    const pid_t pid = spawn({"python3", settings_.report_script, study_.output_directory},
                            variables, "", problem);
    if (pid < 0)
      {
        out_ << "warning: the report could not be written: " << problem << "\n";
        return 1;
      }
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR)
      {
      }
    const int code = exit_code_of(status);
    if (code != 0)
      out_ << "warning: the report script " << settings_.report_script << " failed (exit code "
           << code << ")\n";
    return code;
  }
} // namespace indentsim::study
