// The automatic mesh (specimen.contact_elements: auto, mesh/MeshDesign.h): the built octree
// obeys the design's rule s(rho) = max(h_min, rho / n) cell by cell, s(rho) / 2^m for the top
// face's cells within the surface radius, so that the contact radius spans 2^m n to 2^(m+1) n
// surface elements from an eighth of the maximum depth on; the size estimate matches the built
// mesh, specimen.elements_per_radius sets n, and the case file reads, refuses and writes the
// keys as documented. Units: um, mN, GPa.
#include "../case_file_errors.h"
#include "../test_cases.h"
#include "case/CaseFile.h"
#include "indenter/IndenterFactory.h"
#include "mesh/IndentationMesh.h"
#include "mesh/MeshDesign.h"
#include "mesh/MeshEstimate.h"

#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <numbers>
#include <string>

using namespace indentsim;

namespace
{
  // The paper's J2 case to 6.0 um (frictionless rounded cone a = 2.48, delta = 0.005 um) with
  // the automatic mesh designed for `symmetry`.
  io::Case designed_paper_case(const std::string &symmetry)
  {
    io::Case c;
    c.material.model = "j2";
    c.specimen.symmetry = symmetry;
    c.specimen.contact_elements = io::automatic_contact_elements;
    c.loading.max_depth = 6.0;
    mesh::design_mesh(c, *indenter::create_indenter(c.indenter), /*size_given=*/false);
    return c;
  }

  // The largest edge of the top-face cell containing the surface point at the distance r from
  // the axis (along x) [um].
  template <int dim>
  double surface_edge_at(const dealii::Triangulation<dim> &triangulation, const double r)
  {
    double edge = 0;
    for (const auto &cell : triangulation.active_cell_iterators())
      {
        const dealii::BoundingBox<dim> box = cell->bounding_box();
        if (box.upper_bound(dim - 1) > -1e-9 && box.lower_bound(0) <= r && box.upper_bound(0) > r &&
            (dim == 2 || box.lower_bound(1) < 1e-9))
          edge = std::max(edge, box.upper_bound(0) - box.lower_bound(0));
      }
    return edge;
  }

  template <int dim>
  void check_rule(const io::Case &c)
  {
    dealii::parallel::distributed::Triangulation<dim> triangulation(MPI_COMM_WORLD);
    const mesh::MeshInfo   info = mesh::build_indentation_mesh(triangulation, c.specimen);
    const io::MeshGrading &g = c.specimen.grading;
    EXPECT_TRUE(info.graded);

    // Every cell is no larger than s(rho) at its point nearest to the tip, or s(rho) / 2^m on
    // the top face within the surface radius.
    const double surface_factor = std::pow(2., -double(g.surface_halvings));
    double       smallest = 1e300;
    for (const auto &cell : triangulation.active_cell_iterators())
      {
        const dealii::BoundingBox<dim> box = cell->bounding_box();
        double                         rho2 = 0, edge = 0;
        for (unsigned int d = 0; d < dim; ++d)
          {
            const double nearest = std::clamp(0., box.lower_bound(d), box.upper_bound(d));
            rho2 += nearest * nearest;
            edge = std::max(edge, box.upper_bound(d) - box.lower_bound(d));
          }
        const double rho = std::sqrt(rho2);
        const double s = mesh::target_element_size(g, rho);
        const bool   on_surface = box.upper_bound(dim - 1) > -1e-9 && rho <= g.surface_radius;
        ASSERT_LE(edge, (on_surface ? surface_factor : 1.) * s * (1 + 1e-9)) << "rho " << rho;
        smallest = std::min(smallest, edge);
      }
    EXPECT_GT(smallest, surface_factor * g.min_element / 2);
    EXPECT_LE(smallest, surface_factor * g.min_element);

    // The contact radius at h (the cross-section at 1.2 h) spans 2^m n to 2^(m+1) n surface
    // elements from h_max/8 on (more across the layers of a depth-graded specimen).
    const auto indenter = indenter::create_indenter(c.indenter);
    for (const double h : {0.75, 1.5, 3.0, 6.0})
      {
        const double a = std::sqrt(indenter->projected_area(1.2 * h) / M_PI);
        const double elements = a / surface_edge_at(triangulation, a);
        EXPECT_GE(elements, g.elements_per_radius / surface_factor * (1 - 1e-9)) << "h = " << h;
        if (g.layer_element == 0)
          {
            EXPECT_LE(elements, 2 * g.elements_per_radius / surface_factor) << "h = " << h;
          }
      }

    // The estimate counts the unbalanced octree: the balance adds a few per cent.
    dealii::DoFHandler<dim>     dofs(triangulation);
    const dealii::FESystem<dim> fe(dealii::FE_Q<dim>(1), dim);
    dofs.distribute_dofs(fe);
    const mesh::MeshSize estimate = mesh::estimate_indentation_mesh(c.specimen);
    EXPECT_NEAR(double(estimate.cells), double(triangulation.n_global_active_cells()),
                0.03 * triangulation.n_global_active_cells());
    EXPECT_NEAR(double(estimate.dofs), double(dofs.n_dofs()), 0.10 * dofs.n_dofs());
  }
} // namespace

TEST(MeshDesign, AxisymmetricMeshFollowsTheRule)
{
  const io::Case c = designed_paper_case("axisymmetric");
  const auto    &g = c.specimen.grading;
  // a_d: the rounded cone's cross-section at h_c = 1.2 x 6.0 um, a (h_c + delta) (eq. 16).
  EXPECT_NEAR(g.contact_radius, 2.48 * (7.2 + 0.005), 1e-4);
  EXPECT_EQ(g.elements_per_radius, mesh::design::elements_per_radius_2d);
  EXPECT_EQ(g.surface_halvings, mesh::design::surface_halvings_2d);
  EXPECT_GE(g.surface_halvings, 1u);
  // The surface radius: the contact nodes' reach, 1.5 a_d (rounded up).
  EXPECT_GE(g.surface_radius, 1.5 * g.contact_radius);
  EXPECT_EQ(g.surface_radius, c.specimen.refined_region[0] / 2);
  EXPECT_NEAR(g.min_element, 2.48 * (0.9 + 0.005) / g.elements_per_radius, 1e-5);
  EXPECT_GE(c.specimen.size[0] / 2, mesh::design::specimen_radii * g.contact_radius);
  EXPECT_EQ(c.specimen.size[2], c.specimen.size[0] / 2);
  check_rule<2>(c);
}

// specimen.elements_per_radius: n = 16 instead of the default, every length of the design but
// h_min unchanged, and the mesh again follows the rule.
TEST(MeshDesign, ElementsPerRadiusSetsTheDesign)
{
  const io::Case given = io::parse_case_yaml(
      "test: indentation\nmaterial: {model: j2}\n"
      "specimen: {contact_elements: auto, symmetry: axisymmetric, elements_per_radius: 16}\n"
      "loading: {max_depth: 6.0}\n",
      "n16.yaml");
  const io::Case defaulted = designed_paper_case("axisymmetric");
  const auto    &g = given.specimen.grading, &d = defaulted.specimen.grading;
  EXPECT_EQ(g.elements_per_radius, 16.);
  EXPECT_EQ(g.far_elements_per_radius, 8.);
  EXPECT_NEAR(g.min_element * 16, d.min_element * d.elements_per_radius, 1e-12);
  EXPECT_EQ(g.contact_radius, d.contact_radius);
  EXPECT_EQ(g.surface_radius, d.surface_radius);
  EXPECT_EQ(given.specimen.size, defaulted.specimen.size);
  check_rule<2>(given);
  const std::string resolved = io::resolved_case_yaml(given);
  EXPECT_NE(resolved.find("elements_per_radius: 16"), std::string::npos) << resolved;
  EXPECT_NE(io::resolved_case_yaml(defaulted).find("elements_per_radius: auto"), std::string::npos);
}

// specimen.surface_refinement: the top face's cells under the contact 2^m times smaller than
// s(rho); auto is 2 (m = 1) in axisymmetric mode and 1 (m = 0) in 3D; only the surface changes.
TEST(MeshDesign, SurfaceRefinementSetsTheSurfaceHalvings)
{
  const auto designed = [](const std::string &specimen) {
    return io::parse_case_yaml("test: indentation\nmaterial: {model: j2}\nspecimen: {" + specimen +
                                   "}\nloading: {max_depth: 6.0}\n",
                               "surface.yaml");
  };
  const io::Case four = designed("contact_elements: auto, symmetry: axisymmetric, "
                                 "surface_refinement: 4");
  const io::Case axisymmetric = designed_paper_case("axisymmetric");
  EXPECT_EQ(four.specimen.grading.surface_halvings, 2u);
  EXPECT_EQ(axisymmetric.specimen.grading.surface_halvings, 1u);
  io::MeshGrading without_surface = four.specimen.grading;
  without_surface.surface_halvings = axisymmetric.specimen.grading.surface_halvings;
  EXPECT_EQ(without_surface, axisymmetric.specimen.grading);
  check_rule<2>(four);
  const io::Case quarter = designed("contact_elements: auto, symmetry: quarter, "
                                    "surface_refinement: 2");
  EXPECT_EQ(quarter.specimen.grading.surface_halvings, 1u);
  EXPECT_EQ(designed_paper_case("quarter").specimen.grading.surface_halvings, 0u);
  EXPECT_NE(io::resolved_case_yaml(four).find("surface_refinement: 4"), std::string::npos);
  EXPECT_NE(io::resolved_case_yaml(axisymmetric).find("surface_refinement: auto"),
            std::string::npos);
}

TEST(MeshDesign, QuarterMeshFollowsTheRule)
{
  const io::Case c = designed_paper_case("quarter");
  EXPECT_EQ(c.specimen.grading.elements_per_radius, mesh::design::elements_per_radius_3d);
  check_rule<3>(c);
}

// A pyramid's elements are sized by the radius of the circle of its cross-section's area:
// Vickers and Berkovich pyramids, whose area functions agree to 0.04 %, get the same elements
// (sized by their largest extent, the Berkovich elements would be 1.75 times the Vickers ones),
// while the contact nodes still cover 1.5 times each pyramid's cross-section.
TEST(MeshDesign, PyramidsAreSizedByTheirArea)
{
  const auto designed = [](const std::string &shape) {
    io::Case c;
    c.material.model = "j2";
    c.indenter.shape = shape;
    c.specimen.symmetry = "full";
    c.specimen.contact_elements = io::automatic_contact_elements;
    c.loading.max_depth = 4.0;
    mesh::design_mesh(c, *indenter::create_indenter(c.indenter), /*size_given=*/false);
    return c;
  };
  const double   h_c = 1.2 * 4.0, deg = std::numbers::pi / 180;
  const io::Case vickers = designed("vickers"), berkovich = designed("berkovich");
  // Closed forms of the sharp pyramids: area 4 tan^2(68 deg) h^2 and 3 sqrt(3) tan^2(65.27 deg)
  // h^2; extent along x: tan(68 deg) h (half-side) and 2 tan(65.27 deg) h (corner).
  const double tan_v = std::tan(68 * deg), tan_b = std::tan(65.27 * deg);
  EXPECT_NEAR(vickers.specimen.grading.contact_radius,
              h_c * std::sqrt(4 * tan_v * tan_v / std::numbers::pi), 1e-6 * h_c);
  EXPECT_NEAR(berkovich.specimen.grading.contact_radius,
              h_c * std::sqrt(3 * std::sqrt(3.) * tan_b * tan_b / std::numbers::pi), 1e-6 * h_c);
  EXPECT_NEAR(berkovich.specimen.grading.min_element / vickers.specimen.grading.min_element, 1,
              1e-3);
  // The contact nodes' box: 1.5 times the cross-section's extent along x and y (the Vickers
  // faces face x and y at rotation 0; a Berkovich corner points along -x).
  EXPECT_GE(vickers.specimen.refined_region[0] / 2, 1.5 * tan_v * h_c);
  EXPECT_GE(berkovich.specimen.refined_region[0] / 2, 1.5 * 2 * tan_b * h_c);
  EXPECT_GE(berkovich.specimen.refined_region[1] / 2, 1.5 * 2 * tan_b * h_c);
}

namespace
{
  const std::string auto_case = "test: indentation\n"
                                "material: {model: j2}\n"
                                "specimen: {contact_elements: auto, symmetry: axisymmetric}\n"
                                "loading: {max_depth: 6.0}\n";

} // namespace

// `auto` designs size and refined_region; the resolved case reads back to the identical case.
TEST(MeshDesign, CaseFileDesignsAndWritesTheMesh)
{
  const io::Case c = io::parse_case_yaml(auto_case, "auto.yaml");
  EXPECT_TRUE(c.specimen.automatic_mesh());
  const double a_d = c.specimen.grading.contact_radius;
  EXPECT_NEAR(a_d, 2.48 * (7.2 + 0.005), 1e-4);
  EXPECT_GE(c.specimen.size[0], 2 * mesh::design::specimen_radii * a_d);
  EXPECT_LE(c.specimen.size[0], 2 * 1.1 * mesh::design::specimen_radii * a_d);
  EXPECT_GE(c.specimen.refined_region[0], 2 * mesh::design::contact_region_radii * a_d);

  const std::string resolved = io::resolved_case_yaml(c);
  EXPECT_NE(resolved.find("contact_elements: auto"), std::string::npos) << resolved;
  EXPECT_EQ(resolved.find("refined_region:"), std::string::npos) << resolved;
  EXPECT_NE(resolved.find("# designed"), std::string::npos) << resolved;
  io::Case again = io::parse_case_yaml(resolved, "resolved.yaml");
  again.source_file = c.source_file;
  EXPECT_TRUE(again == c) << resolved;

  // A given size is kept.
  const io::Case given = io::parse_case_yaml(
      "test: indentation\nmaterial: {model: j2}\n"
      "specimen: {contact_elements: auto, symmetry: axisymmetric, size: [400, 400, 200]}\n",
      "auto.yaml");
  EXPECT_EQ(given.specimen.size[0], 400.);
  EXPECT_EQ(given.specimen.size[2], 200.);
}

TEST(MeshDesign, CaseFileRefusals)
{
  using test_case_files::expect_rejected;
  expect_rejected(
      "test: indentation\nmaterial: {model: j2}\n"
      "specimen: {contact_elements: auto, refined_region: [60, 60, 30]}\n",
      {"bad.yaml:3", "specimen.refined_region = [60, 60, 30]", "designs the refined region"});
  expect_rejected("test: indentation\nmaterial: {model: j2}\nspecimen: {contact_elements: 0}\n",
                  {"specimen.contact_elements = 0", "allowed: auto, or N must be a multiple of 4"});
  expect_rejected(
      "test: indentation\nmaterial: {model: j2}\nspecimen: {contact_elements: automatic}\n",
      {"specimen.contact_elements = automatic: unknown word"});
  expect_rejected("test: indentation\nmaterial: {model: j2}\n"
                  "specimen: {contact_elements: 12, elements_per_radius: 16}\n",
                  {"specimen.elements_per_radius = 16", "give specimen.contact_elements: auto"});
  expect_rejected("test: indentation\nmaterial: {model: j2}\n"
                  "specimen: {contact_elements: auto, elements_per_radius: 1}\n",
                  {"specimen.elements_per_radius = 1", "2 <= n <= 64"});
  expect_rejected("test: indentation\nmaterial: {model: j2}\n"
                  "specimen: {contact_elements: 12, surface_refinement: 2}\n",
                  {"specimen.surface_refinement = 2", "give specimen.contact_elements: auto"});
  expect_rejected("test: indentation\nmaterial: {model: j2}\n"
                  "specimen: {contact_elements: auto, surface_refinement: 3}\n",
                  {"specimen.surface_refinement = 3", "allowed: auto, 1, 2, 4 or 8"});
  expect_rejected("test: indentation\nmaterial: {model: j2}\n"
                  "specimen: {contact_elements: auto, surface_refinement: 16}\n",
                  {"specimen.surface_refinement = 16", "1, 2, 4 or 8"});
  expect_rejected("test: indentation\nmaterial: {model: j2}\n"
                  "specimen: {contact_elements: 12, elements_across_layers: 2}\n",
                  {"specimen.elements_across_layers = 2", "give specimen.contact_elements: auto"});
  expect_rejected("test: indentation\nmaterial: {model: j2}\n"
                  "specimen: {contact_elements: auto, elements_across_layers: 0}\n",
                  {"specimen.elements_across_layers = 0", "1 <= m <= 16"});
}

// A depth-graded specimen: four elements across its thinnest layer wherever the near field
// reaches above the last layer's bottom, the rest of the design unchanged (and followed).
TEST(MeshDesign, LayersGetFourElementsAcrossTheThinnest)
{
  io::Case              c = designed_paper_case("axisymmetric");
  const io::MeshGrading plain = c.specimen.grading;
  c.material.layers = {{0.6, "{yield_stress: 0.6}"}, {0, "{}"}, {0.9, "{yield_stress: 0.4}"}};
  mesh::design_mesh(c, *indenter::create_indenter(c.indenter), /*size_given=*/false);
  const io::MeshGrading &g = c.specimen.grading;
  EXPECT_DOUBLE_EQ(g.layered_depth, 1.5);
  EXPECT_DOUBLE_EQ(g.layer_element, 0.6 / 4);
  EXPECT_EQ(g.min_element, plain.min_element);
  EXPECT_EQ(g.graded_radius, plain.graded_radius);
  check_rule<2>(c);

  dealii::parallel::distributed::Triangulation<2> triangulation(MPI_COMM_WORLD);
  mesh::build_indentation_mesh(triangulation, c.specimen);
  double largest_in_layers = 0, largest_below = 0;
  for (const auto &cell : triangulation.active_cell_iterators())
    {
      const dealii::BoundingBox<2> box = cell->bounding_box();
      const double rho = std::hypot(box.lower_bound(0), std::min(0., box.upper_bound(1)));
      const double edge = box.upper_bound(0) - box.lower_bound(0);
      if (rho > g.graded_radius)
        continue;
      if (-box.upper_bound(1) < g.layered_depth)
        largest_in_layers = std::max(largest_in_layers, edge);
      else if (-box.upper_bound(1) > 2 * g.layered_depth && box.lower_bound(0) > 10)
        largest_below = std::max(largest_below, edge);
    }
  EXPECT_LE(largest_in_layers, g.layer_element * (1 + 1e-9));
  EXPECT_GT(largest_below, 2 * g.layer_element); // the refinement stays in the layers
  std::cout << "[ layers ] near field: largest edge " << largest_in_layers
            << " um across the layers, " << largest_below << " um below them; "
            << triangulation.n_active_cells() << " cells" << std::endl;

  // specimen.elements_across_layers: m elements across the thinnest layer.
  c.specimen.elements_across_layers = 2;
  mesh::design_mesh(c, *indenter::create_indenter(c.indenter), /*size_given=*/false);
  EXPECT_DOUBLE_EQ(c.specimen.grading.layer_element, 0.6 / 2);
}
