// The output directory of a run: the names of the files a run writes, and the protection of
// an earlier run's results.
#pragma once

#include <array>
#include <string>

namespace indentsim::io
{
  // File names every run writes into its output directory; the writers use these names so that
  // the directory protection below recognizes an earlier run.
  namespace output_files
  {
    inline constexpr const char *load_penetration_csv = "load_penetration.csv";
    inline constexpr const char *load_penetration_png = "load_penetration.png";
    inline constexpr const char *stress_strain_csv = "stress_strain.csv";       // tensile
    inline constexpr const char *stress_strain_j2_csv = "stress_strain_j2.csv"; // compare_j2
    inline constexpr const char *stress_strain_png = "stress_strain.png";
    inline constexpr const char *resolved_case = "resolved_case.yaml";
    inline constexpr const char *log = "run.log";
    inline constexpr const char *run_summary = "run_summary.json"; // cost of the run
    // Pile-up of the top surface (analysis/PileUp.h) at maximum depth and after unloading.
    inline constexpr const char *pileup_json = "pileup.json";
    inline constexpr const char *pileup_max_depth_csv = "pileup_max_depth.csv";
    inline constexpr const char *pileup_unloaded_csv = "pileup_unloaded.csv";
    inline constexpr const char *pileup_profiles_csv = "pileup_profiles.csv";
    inline constexpr const char *pileup_max_depth_png = "pileup_max_depth.png";
    inline constexpr const char *pileup_unloaded_png = "pileup_unloaded.png";
    inline constexpr const char *pileup_profiles_png = "pileup_profiles.png";
    // Oliver-Pharr analysis of the unloading (analysis/OliverPharr.h).
    inline constexpr const char *oliver_pharr_json = "oliver_pharr.json";
    inline constexpr const char *oliver_pharr_png = "oliver_pharr.png";
    // The partial unloads' hardness-depth profile and Nix-Gao fit (analysis/HardnessDepth.h).
    inline constexpr const char *hardness_depth_csv = "hardness_depth.csv";
    inline constexpr const char *hardness_depth_json = "hardness_depth.json";
    inline constexpr const char *hardness_depth_png = "hardness_depth.png";
    // The measured curve (output.experimental_curve) converted, and the comparison with it.
    inline constexpr const char *experimental_curve_csv = "experimental_curve.csv";
    inline constexpr const char *experiment_comparison_json = "comparison_with_experiment.json";
    // Checkpoint of a stopped indentation run (rank_<r>.bin), read by `run --resume`; removed
    // when the run finishes.
    inline constexpr const char *checkpoint_directory = "checkpoint";
    // ParaView series: specimen.pvd, specimen_<step>.pvtu, specimen_<step>.<rank>.vtu.
    inline constexpr const char *paraview_basename = "specimen";

    // Exact names that mark an earlier run and are removed by --overwrite.
    inline constexpr std::array<const char *, 22> known_names = {{experimental_curve_csv,
                                                                  experiment_comparison_json,
                                                                  oliver_pharr_json,
                                                                  oliver_pharr_png,
                                                                  hardness_depth_csv,
                                                                  hardness_depth_json,
                                                                  hardness_depth_png,
                                                                  load_penetration_csv,
                                                                  load_penetration_png,
                                                                  stress_strain_csv,
                                                                  stress_strain_j2_csv,
                                                                  stress_strain_png,
                                                                  resolved_case,
                                                                  log,
                                                                  run_summary,
                                                                  pileup_json,
                                                                  pileup_max_depth_csv,
                                                                  pileup_unloaded_csv,
                                                                  pileup_profiles_csv,
                                                                  pileup_max_depth_png,
                                                                  pileup_unloaded_png,
                                                                  pileup_profiles_png}};
    // Files named paraview_basename* with these extensions are ours as well.
    inline constexpr std::array<const char *, 3> paraview_extensions = {{".pvd", ".vtu", ".pvtu"}};
  } // namespace output_files

  // Creates `directory` (with parents) and checks that it is writable by creating and removing a
  // probe file. If it already holds an earlier run's results (any of output_files) and
  // `overwrite` is false, throws CaseFileError telling the user to pass --overwrite or choose
  // another directory. With `overwrite` true, removes only our own known output files (the names
  // above, specimen*.pvd/.vtu/.pvtu and the folder `checkpoint` with its rank_*.bin files);
  // nothing else, and no other folder, is ever deleted.
  void prepare_output_directory(const std::string &directory, bool overwrite);
} // namespace indentsim::io
