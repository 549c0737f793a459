// The guards that keep a run from giving a wrong answer without a word: the mesh-size estimate
// behind the memory check, the count bounds of the case file, check's refusal of a refined
// region that cannot hold the predicted contact, the memory refusal, and the run's stop when
// the contact outgrows the refined region (mesh/MeshAdequacy.h, mesh/MeshEstimate.h,
// output/MemoryEstimate.h, problems/IndentationGuards.cc). Units: um, mN, GPa, MiB.
#include "../test_cases.h"
#include "../test_files.h"
#include "case/CaseFile.h"
#include "indenter/Cone.h"
#include "indenter/IndenterFactory.h"
#include "mesh/IndentationMesh.h"
#include "mesh/MeshAdequacy.h"
#include "mesh/MeshEstimate.h"
#include "output/MemoryEstimate.h"
#include "problems/IndentationProblem.h"

#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

using namespace indentsim;

namespace
{
  // The error message of parsing `yaml`, or "" if it was accepted.
  std::string error_of(const std::string &yaml)
  {
    try
      {
        io::parse_case_yaml(yaml, "guard.yaml");
      }
    catch (const io::CaseFileError &error)
      {
        return error.what();
      }
    return "";
  }

  // Sets an environment variable for the lifetime of the object.
  struct ScopedEnvironment
  {
    ScopedEnvironment(const char *name, const char *value)
      : name(name)
    {
      setenv(name, value, 1);
    }
    ~ScopedEnvironment() { unsetenv(name); }
    const char *name;
  };
} // namespace

// The estimated cells equal those of the built mesh (the 2:1 balance rule of MeshEstimate.h),
// and the DOFs lie within 2 % of them above 20 000 DOFs and within 5 % on the tiny meshes, for quarter and full models and 1 to 4 refinement
// levels, with and without cells beside and below the refined region.
TEST(MeshEstimate, MatchesBuiltMeshes)
{
  struct Specimen
  {
    std::array<double, 3> size, refined;
    unsigned int          n;
    const char           *symmetry;
  };
  const Specimen specimens[] = {
      {{{360, 360, 180}}, {{120, 120, 30}}, 12, "quarter"}, // the default example: L = 1
      {{{360, 360, 180}}, {{120, 120, 30}}, 24, "full"},    // L = 2
      {{{60, 60, 30}}, {{16, 16, 4}}, 16, "quarter"},       // tests' small case: L = 2
      {{{60, 60, 30}}, {{16, 16, 4}}, 16, "full"},
      {{{30, 30, 15}}, {{8, 8, 2}}, 8, "full"},       // L = 1
      {{{40, 20, 12}}, {{16, 8, 4}}, 32, "quarter"},  // L = 3, a rectangular region
      {{{16, 16, 8}}, {{16, 16, 4}}, 32, "quarter"},  // L = 3, no cells beside the region
      {{{40, 40, 12}}, {{16, 16, 4}}, 64, "quarter"}, // L = 4
  };
  for (const Specimen &s : specimens)
    {
      io::SpecimenParameters specimen;
      specimen.size = s.size;
      specimen.refined_region = s.refined;
      specimen.contact_elements = s.n;
      specimen.symmetry = s.symmetry;
      dealii::parallel::distributed::Triangulation<3> triangulation(MPI_COMM_WORLD);
      mesh::build_indentation_mesh(triangulation, specimen);
      dealii::DoFHandler<3>     dofs(triangulation);
      const dealii::FESystem<3> fe(dealii::FE_Q<3>(1), 3);
      dofs.distribute_dofs(fe);
      const mesh::MeshSize estimate = mesh::estimate_indentation_mesh(specimen);
      const std::string    name =
          std::to_string(s.n) + " " + s.symmetry + " on " + std::to_string(s.refined[0]) + " um";
      EXPECT_EQ(estimate.cells, triangulation.n_global_active_cells()) << name;
      const double tolerance = dofs.n_dofs() > 20000 ? 0.02 : 0.05;
      EXPECT_NEAR(double(estimate.dofs), double(dofs.n_dofs()), tolerance * dofs.n_dofs()) << name;
    }
}

// The predicted contact of a sharp cone is its cross-section, h tan(alpha), along x and y; a
// Vickers pyramid at rotation 0 (faces towards +-x) reaches sqrt(A)/2 along x.
TEST(MeshAdequacy, IndenterExtentIsTheCrossSection)
{
  const indenter::Cone    cone(70.3, 0.0);
  const mesh::PatchExtent extent = mesh::indenter_extent(cone, 2.0);
  const double            expected = 2.0 * std::tan(70.3 * M_PI / 180);
  EXPECT_NEAR(extent.x, expected, 1e-6 * expected);
  EXPECT_NEAR(extent.y, expected, 1e-6 * expected);
  io::IndenterParameters vickers;
  vickers.shape = "vickers";
  const auto   pyramid = indenter::create_indenter(vickers);
  const double half_side = std::sqrt(pyramid->projected_area(2.0)) / 2;
  EXPECT_NEAR(mesh::indenter_extent(*pyramid, 2.0).x, half_side, 1e-3 * half_side);
}

// check refuses a refined region that cannot hold the contact predicted at the maximum depth
// (the case: 16 um region, the paper's cone to 3.9 um) and names the keys and sizes
// that would; the same case with a region that holds it is accepted.
TEST(MeshAdequacy, CheckRefusesARefinedRegionThatCannotHoldTheContact)
{
  const std::string base = "test: indentation\nmaterial:\n  model: j2\nspecimen:\n"
                           "  size: [60, 60, 30]\n  contact_elements: 16\n";
  const std::string error =
      error_of(base + "  refined_region: [16, 16, 4]\nloading:\n  max_depth: 3.9\n");
  EXPECT_NE(error.find("guard.yaml:"), std::string::npos) << error;
  EXPECT_NE(error.find("specimen.refined_region = [16, 16, 4]"), std::string::npos) << error;
  EXPECT_NE(error.find("cannot hold the contact"), std::string::npos) << error;
  EXPECT_NE(error.find("specimen.contact_elements: "), std::string::npos) << error;
  EXPECT_NE(error.find("loading.max_depth <= "), std::string::npos) << error;
  // 2.48 x 1.2 x 3.9 um = 11.6 um against 0.9 x 8 um.
  EXPECT_NE(error.find("11.6"), std::string::npos) << error;
  EXPECT_EQ(error_of(base + "  refined_region: [28, 28, 5]\nloading:\n  max_depth: 3.9\n"), "");
  // Force control: the contact area F / (3 sigma_y) = 300 mN / 0.915 GPa, a = 10.2 um.
  const std::string force =
      error_of(base + "  refined_region: [16, 16, 4]\nloading:\n  control: force\n  max_force: "
                      "300\n  max_depth: 3.9\n");
  EXPECT_NE(force.find("F/H"), std::string::npos) << force;
  EXPECT_NE(force.find("a smaller loading.max_force"), std::string::npos) << force;
}

// Every count key has an upper bound and its message states the allowed range, also for a
// value beyond the unsigned type.
TEST(CountBounds, EveryCountKeyStatesItsRange)
{
  const std::string                         base = "test: indentation\nmaterial:\n  model: j2\n";
  const std::pair<std::string, std::string> cases[] = {
      {"specimen:\n  contact_elements: 100000\n", "4 <= N <= 512"},
      {"specimen:\n  contact_elements: 99999999999\n", "4 <= N <= 512"},
      {"loading:\n  steps: 1000000\n", "1 <= steps <= 100000"},
      {"loading:\n  unload_steps: 1000000\n", "0 <= unload_steps <= 100000"},
      {"loading:\n  hold_steps: 1000000\n", "0 <= hold_steps <= 100000"},
      {"loading:\n  cycles: 1001\n", "1 <= cycles <= 1000"},
      {"loading:\n  unload_points: 10001\n", "0 <= unload_points <= 10000"},
      {"loading:\n  max_cutbacks: 31\n", "0 <= max_cutbacks <= 30"},
      {"contact:\n  max_augmentations: 1001\n", "1 <= max_augmentations <= 1000"},
      {"solver:\n  max_newton_iterations: 1001\n", "1 <= max_newton_iterations <= 1000"},
      {"solver:\n  threads: 1025\n", "between 0 (automatic) and 1024"},
      {"output:\n  vtu_every: 100001\n", "0 <= vtu_every <= 100000"},
      {"specimen:\n  elements_per_side: 201\n", "1 <= n <= 200"},
  };
  for (const auto &[yaml, range] : cases)
    {
      const std::string error = error_of(base + yaml);
      EXPECT_NE(error.find(range), std::string::npos) << yaml << " -> " << error;
    }
}

// A case whose estimated memory exceeds the available memory is refused with the estimate and
// the key to change (the largest contact_elements that fits); the default case fits. The
// available memory is fixed through INDENTSIM_AVAILABLE_MEMORY_MB so that the test does not
// depend on the machine; the estimate is the real one.
TEST(MemoryEstimate, RefusesACaseThatDoesNotFit)
{
  const ScopedEnvironment available("INDENTSIM_AVAILABLE_MEMORY_MB", "16000");
  io::Case                the_case = io::parse_case_yaml(
                     "test: indentation\nmaterial:\n  model: j2\nspecimen:\n  contact_elements: 256\n",
                     "huge.yaml");
  std::ostringstream out;
  try
    {
      output::check_memory(the_case, MPI_COMM_SELF, out);
      FAIL() << "not refused: " << out.str();
    }
  catch (const io::CaseFileError &error)
    {
      const std::string message = error.what();
      EXPECT_NE(message.find("huge.yaml"), std::string::npos) << message;
      EXPECT_NE(message.find("specimen.contact_elements = 256"), std::string::npos) << message;
      EXPECT_NE(message.find("DOFs"), std::string::npos) << message;
      EXPECT_NE(message.find(" fits"), std::string::npos) << message;
    }
  EXPECT_NE(out.str().find("Estimated size: "), std::string::npos) << out.str();

  the_case.specimen.contact_elements = 12;
  std::ostringstream fits;
  EXPECT_NO_THROW(output::check_memory(the_case, MPI_COMM_SELF, fits));
  // The default example's mesh: 1368 cells, 5643 DOFs (docs/user-guide.md).
  EXPECT_NE(fits.str().find("1368 cells, 5643 DOFs"), std::string::npos) << fits.str();
}

// A run stops (mesh::MeshOutgrownError) at the first step whose contact covers more than 90 %
// of the refined half-width, naming the keys and sizes that would hold it; the curve up to that
// step is kept in memory and in load_penetration.csv, and run.log says why it stopped.
TEST(RunGuards, ContactOutgrowingTheRefinedRegionStopsTheRun)
{
  io::Case c = test_cases::small_j2_case("quarter");
  c.specimen.size = {{20., 20., 10.}};
  c.specimen.refined_region = {{4., 4., 2.}};
  c.specimen.contact_elements = 8; // 0.5 um elements; half-width 2 um
  c.loading.max_depth = 1.5;       // contact radius about 4.8 um at the end
  c.loading.steps = 6;
  const auto                      directory = test_files::scratch_directory("guards", "outgrown");
  problems::IndentationProblem<3> problem(c, MPI_COMM_WORLD, false);
  problem.setup();
  std::string message;
  try
    {
      problem.run(directory.string());
      FAIL() << "the run did not stop";
    }
  catch (const mesh::MeshOutgrownError &error)
    {
      message = error.what();
    }
  EXPECT_NE(message.find("specimen.refined_region"), std::string::npos) << message;
  EXPECT_NE(message.find("specimen.contact_elements: "), std::string::npos) << message;
  EXPECT_NE(message.find("loading.max_depth"), std::string::npos) << message;
  const auto &records = problem.records();
  ASSERT_GE(records.size(), 2u);
  EXPECT_LT(records.back().depth, c.loading.max_depth);
  // The stop came at the first step beyond the margin (the largest radius of the patch is at
  // least its largest |x|, and within a few per cent of it for this axisymmetric contact).
  EXPECT_GT(records.back().contact_radius, 0.9 * 2.0);
  for (std::size_t i = 1; i + 1 < records.size(); ++i)
    EXPECT_LE(records[i].contact_radius, 1.05 * 0.9 * 2.0) << "step " << i;
  const std::string csv = test_files::read_text(directory / "load_penetration.csv");
  const std::string log = test_files::read_text(directory / "run.log");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), long(records.size()) + 1) << csv;
  EXPECT_NE(log.find("# stopped: the contact reached"), std::string::npos) << log;
}

// The paper's J2 block (12 x 12, full model) under a Berkovich pyramid whose edge along -x runs
// over the nodes of the plane y = 0, a mirror plane of the pyramid, the material and the mesh.
// With the edges rounded by 0.1 nm the node on the edge slides off onto one face at about
// 2 um (docs/user-guide.md, "Indenters"): the lateral force F_y exceeds 1 % of F_z and the run
// warns (mirror_symmetry). With 5 nm the node stays on the edge, F_y vanishes and nothing warns.
TEST(RunGuards, ContactThatBreaksAMirrorSymmetryWarns)
{
  for (const double radius : {1e-4, 5e-3})
    {
      io::Case c;
      c.material.model = "j2";
      c.indenter.shape = "berkovich";
      c.indenter.tip_radius = radius;
      c.loading.max_depth = 2.25;
      c.loading.steps = 24; // the 0.094 um steps of the example (6 um in 64 steps)
      c.loading.unload = false;
      c.output.plots = false;
      const auto directory =
          test_files::scratch_directory("guards", "mirror_" + std::to_string(radius));
      problems::IndentationProblem<3> problem(c, MPI_COMM_WORLD, false);
      problem.setup();
      problem.run(directory.string());
      const auto &warnings = problem.warnings();
      const bool  warned = std::any_of(warnings.begin(), warnings.end(), [](const auto &w) {
        return w.text.find("mirror-symmetric about the plane y = 0") != std::string::npos;
      });
      EXPECT_EQ(warned, radius < 1e-3) << "tip radius " << radius;
      EXPECT_NEAR(problem.records().back().depth, 2.25, 1e-12);
      const std::string log = test_files::read_text(directory / "run.log");
      EXPECT_EQ(log.find("the contact force has the lateral component") != std::string::npos,
                radius < 1e-3)
          << log;
    }
}

namespace
{
  // The warning topics that run_summary.json lists, in order.
  std::vector<std::string> summary_warning_topics(const std::filesystem::path &directory)
  {
    const std::string        text = test_files::read_text(directory / "run_summary.json");
    const std::regex         topic("\\{\"topic\": \"([^\"]*)\", \"text\": \"");
    std::vector<std::string> topics;
    for (auto it = std::sregex_iterator(text.begin(), text.end(), topic);
         it != std::sregex_iterator(); ++it)
      topics.push_back((*it)[1]);
    EXPECT_NE(text.find("\"warnings\": ["), std::string::npos) << text;
    return topics;
  }
} // namespace

// A Vickers pyramid at 0 deg has all four faces along the mesh lines: the run warns that the
// force climbs in stairs and names the turn that avoids them. At 45 deg (the quarter model's
// other choice) no face runs along them and nothing warns. A 4 x 4 quarter model, two steps.
// run_summary.json lists the warning, also after a stop at step 1 and a resume (the guard looks
// only at the first step).
TEST(RunGuards, PyramidWithEveryFaceAlongTheMeshLinesWarns)
{
  for (const double rotation : {0., 45.})
    {
      io::Case c;
      c.material.model = "j2";
      c.indenter.shape = "vickers";
      c.indenter.tip_radius = 0.05;
      c.indenter.rotation_deg = rotation;
      c.specimen.symmetry = "quarter";
      c.specimen.contact_elements = 4;
      c.loading.max_depth = 0.5;
      c.loading.steps = 2;
      c.loading.unload = false;
      c.output.plots = false;
      const auto directory =
          test_files::scratch_directory("guards", "faces_" + std::to_string(int(rotation)));
      problems::IndentationProblem<3> problem(c, MPI_COMM_WORLD, false);
      problem.setup();
      problem.run(directory.string());
      const auto &warnings = problem.warnings();
      const auto  warning = std::find_if(warnings.begin(), warnings.end(), [](const auto &w) {
        return w.text.find("runs parallel to the mesh lines") != std::string::npos;
      });
      EXPECT_EQ(warning != warnings.end(), rotation == 0.) << "rotation " << rotation;
      if (warning != warnings.end())
        {
          EXPECT_NE(warning->text.find("indenter.rotation_deg = 0"), std::string::npos)
              << warning->text;
          EXPECT_NE(warning->text.find("rotation_deg: 22.5"), std::string::npos) << warning->text;
        }
      EXPECT_NEAR(problem.records().back().depth, 0.5, 1e-12);
      // The 4 x 4 mesh also warns that few elements span the contact.
      const std::vector<std::string> expected =
          rotation == 0. ? std::vector<std::string>{"faces_along_mesh_lines", "contact_resolution"}
                         : std::vector<std::string>{"contact_resolution"};
      EXPECT_EQ(summary_warning_topics(directory), expected) << "rotation " << rotation;

      const auto resumed_directory =
          test_files::scratch_directory("guards", "faces_resumed_" + std::to_string(int(rotation)));
      {
        problems::IndentationProblem<3> stopped(c, MPI_COMM_WORLD, false);
        stopped.setup();
        stopped.stop_after_step(1);
        stopped.run(resumed_directory.string());
      }
      problems::IndentationProblem<3> resumed(c, MPI_COMM_WORLD, false);
      resumed.setup();
      resumed.run(resumed_directory.string(), true);
      EXPECT_NEAR(resumed.records().back().depth, 0.5, 1e-12);
      EXPECT_EQ(summary_warning_topics(resumed_directory), expected) << "rotation " << rotation;
    }
}
