// Study files (study/StudyFile.h), the case key, the study command line, and the runner's
// bookkeeping (study/StudyRunner.h) with a stand-in executable instead of the solver.
// Units: um, mN, GPa.
#include "case/CaseFile.h"
#include "io/CommandLine.h"
#include "study/StudyFile.h"
#include "study/StudyRunner.h"

#include "../test_files.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <iostream>
#include <map>
#include <sstream>
#include <string>

namespace
{
  namespace fs = std::filesystem;
  using namespace indentsim;

  fs::path scratch(const std::string &name)
  {
    return test_files::scratch_directory("study", name);
  }

  fs::path write_text(const fs::path &path, const std::string &text)
  {
    std::ofstream out(path);
    out << text;
    return path;
  }

  const std::string base_case = "# a small base case\n"
                                "test: indentation\n"
                                "material:\n"
                                "  model: j2\n"
                                "  orientation: {surface_normal: [0, 0, 1], "
                                "reference_direction: [1, 0, 0]}\n"
                                "specimen:\n"
                                "  size: [360, 360, 180]\n"
                                "  contact_elements: 12\n"
                                "  symmetry: quarter\n"
                                "loading: {max_depth: 6.0, steps: 64}\n"
                                "output: {directory: results/base}\n";

  // A directory holding base.yaml; returns the path a study file there would have.
  fs::path study_directory(const std::string &name)
  {
    const fs::path dir = scratch(name);
    write_text(dir / "base.yaml", base_case);
    return dir / "study.yaml";
  }

  std::string error_of(const std::string &study_text, const fs::path &study_path)
  {
    try
      {
        study::parse_study_yaml(study_text, study_path.string());
      }
    catch (const study::StudyFileError &error)
      {
        return error.what();
      }
    return "";
  }
} // namespace

// The key hashes the resolved case: key order, comments, number spelling (6 / 6.0), defaults
// written out, output.directory and solver.threads do not change it.
TEST(StudyKey, SameResolvedCaseGivesTheSameKey)
{
  const std::string a = "# case A\n"
                        "test: indentation\n"
                        "material:\n"
                        "  model: j2        # J2\n"
                        "  young_modulus: 69.0\n"
                        "specimen:\n"
                        "  contact_elements: 12\n"
                        "  size: [360, 360, 180]\n"
                        "loading: {max_depth: 6.0}\n"
                        "output: {directory: results/a}\n";
  const std::string b = "output:\n"
                        "  directory: somewhere/else\n"
                        "loading:\n"
                        "  max_depth: 6\n"
                        "specimen: {size: [360.0, 360, 1.8e2], contact_elements: 12}\n"
                        "material: {poisson_ratio: 0.26, young_modulus: 69, model: j2}\n"
                        "solver: {threads: 2}\n"
                        "test: indentation\n";
  const io::Case    case_a = io::parse_case_yaml(a, "a.yaml");
  const io::Case    case_b = io::parse_case_yaml(b, "b.yaml");
  EXPECT_EQ(study::case_key(case_a), study::case_key(case_b));
  EXPECT_EQ(study::canonical_case_text(case_a), study::canonical_case_text(case_b));
  EXPECT_EQ(study::case_key(case_a).size(), 16u);
  EXPECT_EQ(study::case_key(case_a).find_first_not_of("0123456789abcdef"), std::string::npos);
}

// Any changed value (a mesh, a material constant, a loading key) gives another key.
TEST(StudyKey, ChangedValueGivesAnotherKey)
{
  const std::string text = "test: indentation\nmaterial: {model: j2}\n";
  const std::string key = study::case_key(io::parse_case_yaml(text, "a.yaml"));
  for (const std::string extra :
       {"specimen: {contact_elements: 16}\n", "material: {model: j2, young_modulus: 69.5}\n",
        "loading: {max_depth: 5.9}\n", "loading: {unload: false}\n", "indenter: {delta: 0.006}\n"})
    {
      std::string changed = text + extra;
      if (extra.rfind("material", 0) == 0)
        changed = "test: indentation\n" + extra;
      EXPECT_NE(study::case_key(io::parse_case_yaml(changed, "b.yaml")), key) << extra;
    }
}

// The hash is the standard 64-bit FNV-1a (published test vectors), and the key of the default
// J2 case is frozen: a changed canonical form would silently rerun every finished study. A
// changed default or a new key changes the key on purpose: the last change was the new key
// loading.spacing.
TEST(StudyKey, HashIsFnv1aAndStable)
{
  EXPECT_EQ(study::fnv1a_64(""), 0xcbf29ce484222325ull);
  EXPECT_EQ(study::fnv1a_64("a"), 0xaf63dc4c8601ec8cull);
  EXPECT_EQ(study::fnv1a_64("foobar"), 0x85944171f73967e8ull);
  const io::Case c = io::parse_case_yaml("test: indentation\nmaterial: {model: j2}\n", "a.yaml");
  EXPECT_EQ(study::case_key(c), "be229399fa3f2c79") << study::canonical_case_text(c);
}

// Overrides merge onto the base: maps key by key (siblings kept), scalars and lists replaced,
// null removes a key, new keys added, material.orientation replaced whole; the base unchanged.
TEST(StudyFile, OverridesMergeOntoTheBase)
{
  const YAML::Node base = YAML::Load(base_case);
  const YAML::Node overrides =
      YAML::Load("specimen: {contact_elements: 48, size: [400, 400, 200], symmetry: ~}\n"
                 "material: {orientation: {euler_bunge_deg: [0, 45, 0]}, young_modulus: 70}\n"
                 "contact: {friction_coefficient: 0.1}\n");
  const YAML::Node merged = study::merge_overrides(base, overrides);

  EXPECT_EQ(merged["specimen"]["contact_elements"].as<int>(), 48);
  EXPECT_EQ(merged["specimen"]["size"].size(), 3u);
  EXPECT_EQ(merged["specimen"]["size"][2].as<double>(), 200.);
  EXPECT_FALSE(merged["specimen"]["symmetry"].IsDefined());
  EXPECT_EQ(merged["material"]["model"].as<std::string>(), "j2"); // sibling kept
  EXPECT_EQ(merged["material"]["young_modulus"].as<double>(), 70.);
  EXPECT_FALSE(merged["material"]["orientation"]["surface_normal"].IsDefined());
  EXPECT_EQ(merged["material"]["orientation"]["euler_bunge_deg"][1].as<double>(), 45.);
  EXPECT_EQ(merged["loading"]["steps"].as<int>(), 64);
  EXPECT_EQ(merged["contact"]["friction_coefficient"].as<double>(), 0.1);
  // The base is untouched.
  EXPECT_EQ(base["specimen"]["contact_elements"].as<int>(), 12);
  EXPECT_EQ(base["specimen"]["symmetry"].as<std::string>(), "quarter");
  EXPECT_TRUE(base["material"]["orientation"]["surface_normal"].IsDefined());

  // Through the case reader: the merged case is valid and carries the overrides.
  const io::Case c = io::parse_case_yaml(YAML::Dump(merged), "merged.yaml");
  EXPECT_EQ(c.specimen.contact_elements, 48u);
  EXPECT_EQ(c.specimen.symmetry, "full");
  EXPECT_EQ(c.material.orientation.kind, "euler_bunge_deg");
}

// A study file resolves each case (base + overrides), names its directory by name and key, and
// reads groups, labels and report settings.
TEST(StudyFile, ResolvesCasesAndReportSettings)
{
  const fs::path     path = study_directory("resolves");
  const std::string  text = "output: out\n"
                            "report: {depth_at_force_mN: 821.2, tensile_strains: [0.1],\n"
                            "         paper_forces_mN: {mesh_j2: {48: 821.2, 72: 822.2}}}\n"
                            "cases:\n"
                            "  - {name: j2_n12, base: base.yaml, group: mesh_j2}\n"
                            "  - name: j2_n24\n"
                            "    base: base.yaml\n"
                            "    group: [mesh_j2]\n"
                            "    label: \"J2, 24x24\"\n"
                            "    overrides: {specimen: {contact_elements: 24}}\n";
  const study::Study s =
      study::parse_study_yaml(text, path.string(), (path.parent_path() / "o2").string());
  ASSERT_EQ(s.cases.size(), 2u);
  EXPECT_EQ(s.output_directory, (path.parent_path() / "o2").string()); // --output wins
  EXPECT_EQ(s.cases[0].resolved.specimen.contact_elements, 12u);
  EXPECT_EQ(s.cases[1].resolved.specimen.contact_elements, 24u);
  EXPECT_EQ(s.cases[1].resolved.specimen.symmetry, "quarter");
  EXPECT_EQ(s.cases[0].label, "j2_n12");
  EXPECT_EQ(s.cases[1].label, "J2, 24x24");
  EXPECT_EQ(s.cases[1].groups, std::vector<std::string>{"mesh_j2"});
  EXPECT_EQ(s.cases[1].directory,
            (path.parent_path() / "o2" / "cases" / ("j2_n24-" + s.cases[1].key)).string());
  EXPECT_EQ(s.cases[1].resolved.output.directory, s.cases[1].directory);
  EXPECT_EQ(s.cases[0].key,
            study::case_key(io::read_case_file((path.parent_path() / "base.yaml").string())));
  EXPECT_DOUBLE_EQ(s.report.depth_at_force_mN, 821.2);
  EXPECT_EQ(s.report.tensile_strains, std::vector<double>{0.1});
  EXPECT_DOUBLE_EQ(s.report.paper_forces_mN.at("mesh_j2").at(72), 822.2);
}

// The shipped study files are valid, and paper.yaml has the paper's parts: five tensile seeds,
// J2 and crystal at 12, 24, 48, 72 contact elements, orientations (001), (011), (111).
TEST(StudyFile, ShippedStudiesAreValid)
{
  const std::string  root = INDENTSIM_SOURCE_DIR;
  const study::Study quick = study::read_study_file(root + "/studies/quick.yaml");
  EXPECT_EQ(quick.cases.size(), 5u);
  const study::Study paper = study::read_study_file(root + "/studies/paper.yaml");
  std::map<std::string, std::vector<unsigned int>> meshes;
  std::size_t                                      n_tensile = 0;
  for (const auto &c : paper.cases)
    for (const auto &g : c.groups)
      {
        if (g == "tensile")
          {
            ++n_tensile;
            EXPECT_TRUE(c.resolved.compare_j2) << c.name;
          }
        else
          meshes[g].push_back(c.resolved.specimen.contact_elements);
      }
  EXPECT_EQ(n_tensile, 5u);
  EXPECT_EQ(meshes["mesh_j2"], (std::vector<unsigned int>{12, 24, 48, 72}));
  EXPECT_EQ(meshes["mesh_crystal"], (std::vector<unsigned int>{12, 24, 48, 72}));
  EXPECT_EQ(meshes["orientation"].size(), 9u);
  EXPECT_DOUBLE_EQ(paper.report.paper_forces_mN.at("mesh_crystal").at(48), 830.3);
  EXPECT_DOUBLE_EQ(paper.report.depth_at_force_mN, 821.2);
}

// Bad study input raises StudyFileError naming the study file (and line), the case, the key,
// the value and what is allowed; nothing crashes.
TEST(StudyFile, BadInputNamesFileKeyValueAndRule)
{
  const fs::path    path = study_directory("bad_input");
  const std::string file = path.string();
  const auto        case_entry = [](const std::string &fields) {
    return "cases:\n  - {name: c1, base: base.yaml" + fields + "}\n";
  };
  const std::vector<std::pair<std::string, std::vector<std::string>>> bad = {
      {"case:\n  - {name: c1, base: base.yaml}\n", {":1:", "unknown key 'case'", "cases"}},
      {"output: o\n", {"missing key 'cases'"}},
      {"cases: []\n", {"non-empty list"}},
      {case_entry(", overrides: {specimen: {contact_elements: 10}}"),
       {":2:", "case 'c1'", "specimen.contact_elements", "10", "multiple of 4"}},
      {case_entry(", overrides: {specimen: {contact_element: 16}}"),
       {"case 'c1'", "unknown key 'specimen.contact_element'", "contact_elements"}},
      {case_entry(", overrides: {material: {poisson_ratio: 0.5}}"),
       {"material.poisson_ratio", "0.5", "-1 < nu < 0.5"}},
      {case_entry(", overrides: {output: {directory: x}}"),
       {"overrides.output.directory", "set by the study"}},
      {case_entry(", overrides: [1, 2]"), {"overrides = [1, 2]", "expected a mapping"}},
      {case_entry(", group: mesh"), {"group = mesh", "mesh_j2", "orientation"}},
      {case_entry(", group: mesh_crystal"), {"group mesh_crystal needs material.model: crystal"}},
      {case_entry(", group: tensile"), {"group tensile needs test: tensile"}},
      {case_entry(", colour: red"), {"unknown key 'cases[0].colour'", "name, base"}},
      {"cases:\n  - {name: c1, base: missing.yaml}\n", {"base = missing.yaml", "no case file"}},
      {"cases:\n  - {base: base.yaml}\n", {"missing key 'name'"}},
      {"cases:\n  - {name: \"a b\", base: base.yaml}\n", {"\"a b\"", "letters, digits"}},
      {"cases:\n  - {name: c1, base: base.yaml}\n  - {name: c1, base: base.yaml, overrides: "
       "{loading: {steps: 8}}}\n",
       {"case name 'c1' given twice"}},
      {"cases:\n  - {name: c1, base: base.yaml}\n  - {name: c2, base: base.yaml, overrides: "
       "{output: {vtu_every: 0}}}\n",
       {"'c2' resolves to the same case as 'c1'", "group: [a, b]"}},
      {"cases:\n  - {name: c1, base: base.yaml, group: mesh_j2}\n  - {name: c2, base: base.yaml, "
       "group: mesh_j2, overrides: {loading: {steps: 8}}}\n",
       {"both have contact_elements 12", "one case per mesh"}},
      {"report: {paper_forces_mN: {mesh_j2: {50: 821.2}}}\n" + case_entry(""),
       {"report.paper_forces_mN.mesh_j2", "'50'", "multiple of 4"}},
      {"report: {depth_at_force_mN: -3}\n" + case_entry(""),
       {"report.depth_at_force_mN = -3", "> 0"}},
      {"report: {tensile_strains: 0.1}\n" + case_entry(""), {"report.tensile_strains = 0.1"}},
      {"cases:\n  - {name: c1, base: base.yaml\n", {"YAML syntax error"}},
      {"- just\n- a list\n", {"a study file is a mapping"}},
      {case_entry("") + "---\ncases: []\n", {":3:", "a second YAML document", "ignored"}},
      {"cases:\n\t- {name: c1, base: base.yaml}\n", {":2:", "a tab in the indentation"}},
      {std::string("output: o\ncases: \0\n", 19), {":2:", "binary content (a NUL byte"}},
  };
  for (const auto &[text, parts] : bad)
    {
      const std::string message = error_of(text, path);
      SCOPED_TRACE("study file:\n" + text + "\nmessage: " + message);
      ASSERT_FALSE(message.empty()) << "no StudyFileError thrown";
      EXPECT_EQ(message.rfind(file, 0), 0u) << "message does not start with the study file";
      for (const auto &part : parts)
        EXPECT_NE(message.find(part), std::string::npos) << "missing '" << part << "'";
    }

  // A syntax error in the base file names the base file and its line.
  write_text(path.parent_path() / "broken.yaml", "test: indentation\nmaterial: [j2\n");
  const std::string message = error_of("cases:\n  - {name: c1, base: broken.yaml}\n", path);
  EXPECT_NE(message.find("broken.yaml:"), std::string::npos) << message;
  EXPECT_NE(message.find("YAML syntax error"), std::string::npos) << message;
  EXPECT_NE(message.find("case 'c1'"), std::string::npos) << message;

  EXPECT_THROW(study::read_study_file((path.parent_path() / "none.yaml").string()),
               study::StudyFileError);
}

// The documented study command forms parse; bad values are usage errors.
TEST(StudyCommandLine, ParsesOptionsAndRejectsBadValues)
{
  auto options = io::parse_command_line({"study", "s.yaml"});
  EXPECT_EQ(options.command, io::Command::study);
  EXPECT_EQ(options.study_file, "s.yaml");
  EXPECT_EQ(options.study_ranks, 1u);
  EXPECT_EQ(options.study_jobs, 1u);
  EXPECT_FALSE(options.study_dry_run);
  EXPECT_TRUE(options.study_only.empty());

  options = io::parse_command_line({"study", "--jobs", "2", "s.yaml", "--ranks=4", "--dry-run",
                                    "--only", "j2_n12,mesh_crystal", "--output", "out"});
  EXPECT_EQ(options.study_file, "s.yaml");
  EXPECT_EQ(options.study_jobs, 2u);
  EXPECT_EQ(options.study_ranks, 4u);
  EXPECT_TRUE(options.study_dry_run);
  EXPECT_EQ(options.study_only, (std::vector<std::string>{"j2_n12", "mesh_crystal"}));
  EXPECT_EQ(options.output_directory.value_or(""), "out");
  EXPECT_EQ(io::parse_command_line({"study", "s.yaml", "-h"}).command, io::Command::help);

  for (const std::vector<std::string> &arguments :
       std::vector<std::vector<std::string>>{{"study"},
                                             {"study", "a.yaml", "b.yaml"},
                                             {"study", "a.yaml", "--ranks", "0"},
                                             {"study", "a.yaml", "--ranks", "two"},
                                             {"study", "a.yaml", "--jobs"},
                                             {"study", "a.yaml", "--jobs", "-1"},
                                             {"study", "a.yaml", "--only", "a,,b"},
                                             {"study", "a.yaml", "--overwrite"},
                                             {"study", "a.yaml", "--jobs", "1", "--jobs", "2"}})
    EXPECT_THROW(io::parse_command_line(arguments), io::CommandLineError) << arguments.back();
  const std::string help = io::help_text();
  for (const std::string fragment :
       {"study STUDY.yaml", "--ranks N", "--jobs J", "--dry-run", "--only NAME"})
    EXPECT_NE(help.find(fragment), std::string::npos) << fragment;
}

namespace
{
  // A stand-in for `indentsim run CASE.yaml --overwrite`: writes run_summary.json next to the
  // case and logs the run; a case whose directory starts with "bad-" fails with exit code 3, one
  // starting with "ok2-" lists a warning.
  const std::string fake_solver = "#!/bin/sh\n"
                                  "dir=$(dirname \"$2\")\n"
                                  "echo \"$(basename \"$dir\")\" >> \"$dir/../../runs.log\"\n"
                                  "case \"$(basename \"$dir\")\" in bad-*) echo 'failing on "
                                  "purpose'; exit 3;; esac\n"
                                  "case \"$(basename \"$dir\")\" in ok2-*) w='[{\"topic\": "
                                  "\"contact_resolution\", \"text\": \"t\"}]';; *) w='[]';; esac\n"
                                  "printf '{\"force_at_max_depth_mN\": 1.5, \"warnings\": %s}\\n' "
                                  "\"$w\" > \"$dir/run_summary.json\"\n";
  const std::string fake_report = "import sys\n"
                                  "open(sys.argv[1] + '/report.md', 'w').write('fake report\\n')\n";

  struct RunnerFixture
  {
    fs::path                dir;
    study::StudyRunSettings settings;

    explicit RunnerFixture(const std::string &name)
      : dir(study_directory(name).parent_path())
    {
      write_text(dir / "fake_solver.sh", fake_solver);
      fs::permissions(dir / "fake_solver.sh", fs::perms::owner_all);
      write_text(dir / "fake_report.py", fake_report);
      settings.executable = (dir / "fake_solver.sh").string();
      settings.report_script = (dir / "fake_report.py").string();
      settings.jobs = 2;
    }

    study::Study study(const std::string &cases) const
    {
      return study::parse_study_yaml("output: " + (dir / "out").string() + "\ncases:\n" + cases,
                                     (dir / "study.yaml").string());
    }

    int run(const study::Study &s, std::string &output) const
    {
      std::ostringstream out;
      const int          code = study::StudyRunner(s, settings, out).run();
      output = out.str();
      return code;
    }

    std::string runs() const { return test_files::read_text(dir / "out" / "runs.log"); }
  };

  std::size_t count(const std::string &text, const std::string &word)
  {
    std::size_t n = 0;
    for (std::size_t at = text.find(word); at != std::string::npos; at = text.find(word, at + 1))
      ++n;
    return n;
  }

  const std::string three_cases = "  - {name: ok1, base: base.yaml}\n"
                                  "  - {name: bad, base: base.yaml, overrides: {specimen: "
                                  "{contact_elements: 16}}}\n"
                                  "  - {name: ok2, base: base.yaml, overrides: {specimen: "
                                  "{contact_elements: 24}}}\n";
} // namespace

// A failed case is reported and the others still run (exit code 3); finished cases are marked
// and skipped on a rerun, which reruns only the failed one.
TEST(StudyRunner, FailedCaseDoesNotStopTheOthersAndFinishedOnesAreSkipped)
{
  const RunnerFixture fixture("runner_failure");
  const study::Study  s = fixture.study(three_cases);
  std::string         output;
  EXPECT_EQ(fixture.run(s, output), study::exit_case_failed) << output;
  EXPECT_NE(output.find("bad: FAILED (exit code 3)"), std::string::npos) << output;
  EXPECT_NE(output.find("failing on purpose"), std::string::npos) << output;
  // The progress line names the warnings of a case's run_summary.json (only ok2 has one).
  EXPECT_NE(output.find("force at maximum depth 1.5 mN; WARNING contact_resolution (see its "
                        "run_summary.json)"),
            std::string::npos)
      << output;
  EXPECT_EQ(count(output, "WARNING"), 1u) << output;
  EXPECT_EQ(study::case_state(s.cases[0]), study::CaseState::finished);
  EXPECT_EQ(study::case_state(s.cases[1]), study::CaseState::failed);
  EXPECT_EQ(study::case_state(s.cases[2]), study::CaseState::finished);
  EXPECT_EQ(count(fixture.runs(), "ok1-"), 1u);
  EXPECT_TRUE(fs::exists(fixture.dir / "out" / "report.md"));
  EXPECT_TRUE(fs::exists(fs::path(s.cases[0].directory) / "case.yaml"));
  const std::string index = test_files::read_text(fixture.dir / "out" / "study.json");
  EXPECT_NE(index.find("\"status\": \"failed\""), std::string::npos) << index;
  EXPECT_EQ(count(index, "\"status\": \"finished\""), 2u) << index;

  EXPECT_EQ(fixture.run(s, output), study::exit_case_failed) << output;
  EXPECT_NE(output.find("2 finished case(s) skipped, 1 to run"), std::string::npos) << output;
  EXPECT_EQ(count(fixture.runs(), "ok1-"), 1u);
  EXPECT_EQ(count(fixture.runs(), "ok2-"), 1u);
  EXPECT_EQ(count(fixture.runs(), "bad-"), 2u);
}

// A case directory without its completion mark (an interrupted run) is rerun from the start;
// --only restricts the run to the named cases or groups; --dry-run writes nothing.
TEST(StudyRunner, RerunsInterruptedCaseOnlySelectsAndDryRunWritesNothing)
{
  RunnerFixture      fixture("runner_interrupted");
  const study::Study s = fixture.study("  - {name: ok1, base: base.yaml, group: mesh_j2}\n"
                                       "  - {name: ok2, base: base.yaml, overrides: {specimen: "
                                       "{contact_elements: 24}}}\n");
  std::string        output;
  fixture.settings.dry_run = true;
  EXPECT_EQ(fixture.run(s, output), study::exit_ok);
  EXPECT_NE(output.find("2 case(s) would run"), std::string::npos) << output;
  EXPECT_FALSE(fs::exists(fixture.dir / "out"));

  fixture.settings.dry_run = false;
  fixture.settings.only = {"mesh_j2"};
  EXPECT_EQ(fixture.run(s, output), study::exit_ok) << output;
  EXPECT_EQ(study::case_state(s.cases[0]), study::CaseState::finished);
  EXPECT_EQ(study::case_state(s.cases[1]), study::CaseState::not_started);

  fixture.settings.only.clear();
  EXPECT_EQ(fixture.run(s, output), study::exit_ok) << output;
  EXPECT_EQ(count(fixture.runs(), "ok1-"), 1u);
  EXPECT_EQ(count(fixture.runs(), "ok2-"), 1u);

  // Interrupted: the run left its directory but no mark.
  fs::remove(fs::path(s.cases[1].directory) / study::study_files::case_mark);
  EXPECT_EQ(study::case_state(s.cases[1]), study::CaseState::unfinished);
  EXPECT_EQ(fixture.run(s, output), study::exit_ok) << output;
  EXPECT_NE(output.find("interrupted: rerun from the start"), std::string::npos) << output;
  EXPECT_EQ(count(fixture.runs(), "ok1-"), 1u);
  EXPECT_EQ(count(fixture.runs(), "ok2-"), 2u);

  // Interrupted with a checkpoint of the same rank count: resumed (--resume); of another rank
  // count: rerun from the start (--overwrite).
  fs::remove(fs::path(s.cases[1].directory) / study::study_files::case_mark);
  const fs::path checkpoint = fs::path(s.cases[1].directory) / "checkpoint";
  fs::create_directories(checkpoint);
  write_text(checkpoint / "rank_0.bin", "x");
  fixture.settings.dry_run = true;
  EXPECT_EQ(fixture.run(s, output), study::exit_ok);
  EXPECT_NE(output.find("interrupted: resumed from its checkpoint"), std::string::npos) << output;
  EXPECT_NE(output.find("case.yaml --resume"), std::string::npos) << output;
  write_text(checkpoint / "rank_1.bin", "x"); // written by 2 ranks, the study runs 1
  EXPECT_EQ(fixture.run(s, output), study::exit_ok);
  EXPECT_NE(output.find("interrupted: rerun from the start"), std::string::npos) << output;
  EXPECT_NE(output.find("case.yaml --overwrite"), std::string::npos) << output;
  fixture.settings.dry_run = false;

  fixture.settings.only = {"nonesuch"};
  EXPECT_THROW(study::StudyRunner(s, fixture.settings, std::cout), study::StudyFileError);
}
