#include "mesh/IndentationMesh.h"

#include "mesh/MeshDesign.h"

#include <deal.II/base/mpi.h>
#include <deal.II/grid/grid_generator.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace indentsim::mesh
{
  using namespace dealii;

  int refinement_levels_for(const unsigned int n)
  {
    if (n < 2 || n % 2 != 0)
      return -1;
    int levels = 0;
    while (n % (1u << (levels + 2)) == 0 && (1u << (levels + 1)) * 3 <= n)
      ++levels;
    return levels;
  }

  std::vector<double> graded_spacing(const double length, const double first, const double ratio)
  {
    std::vector<double> sizes;
    if (length <= 0)
      return sizes;
    double sum = 0, next = first;
    while (sum + next <= length * (1 + 1e-12))
      {
        sizes.push_back(next);
        sum += next;
        next *= ratio;
      }
    if (sizes.empty())
      return {length};
    // Fill the remainder by stretching all cells proportionally (keeps the grading ratio).
    for (double &s : sizes)
      s *= length / sum;
    return sizes;
  }

  double MeshInfo::element_size_at(const double radius) const
  {
    return graded ? target_element_size(grading, radius) : contact_element_size;
  }

  namespace
  {
    // The (r, z) section's edges as colorize numbers them (r = 0, r = R, z = -Lz, z = 0: 0, 1,
    // 2, 3) renamed to the block's ids (axis, outer, bottom, top).
    void name_section_edges(parallel::distributed::Triangulation<2> &triangulation)
    {
      for (const auto &cell : triangulation.active_cell_iterators())
        for (const auto &face : cell->face_iterators())
          if (face->at_boundary() && face->boundary_id() >= 2)
            face->set_boundary_id(face->boundary_id() == 2 ? boundary::bottom : boundary::top);
    }

    // The automatic mesh's coarse grid (mesh/MeshDesign.h), with the boundary ids of
    // IndentationMesh.h.
    template <int dim>
    void coarse_block(parallel::distributed::Triangulation<dim> &triangulation,
                      const io::SpecimenParameters              &specimen)
    {
      const CoarseGrid          grid = coarse_grid(specimen);
      std::vector<unsigned int> repetitions(dim);
      Point<dim>                p1, p2;
      for (unsigned int d = 0; d < dim; ++d)
        {
          repetitions[d] = static_cast<unsigned int>(grid.cells[d]);
          p1[d] = grid.lower[d];
          p2[d] = grid.upper[d];
        }
      GridGenerator::subdivided_hyper_rectangle(triangulation, repetitions, p1, p2,
                                                /*colorize=*/true);
      if constexpr (dim == 2)
        name_section_edges(triangulation);
    }

    // Whether the octree halves `cell` (an axis-aligned box).
    template <int dim>
    bool needs_halving(const io::MeshGrading &grading, const CellAccessor<dim, dim> &cell)
    {
      const BoundingBox<dim> box = cell.bounding_box();
      std::array<double, 3>  lower{}, upper{};
      for (unsigned int d = 0; d < dim; ++d)
        {
          lower[d] = box.lower_bound(d);
          upper[d] = box.upper_bound(d);
        }
      return mesh::needs_halving(grading, lower, upper, dim);
    }

    // specimen.contact_elements: auto: halve every cell larger than s(rho) until none is.
    template <int dim>
    MeshInfo build_graded_mesh(parallel::distributed::Triangulation<dim> &triangulation,
                               const io::SpecimenParameters              &specimen)
    {
      MeshInfo info;
      info.axisymmetric = (dim == 2);
      info.quarter = (specimen.symmetry == io::Symmetry::quarter);
      info.graded = true;
      info.grading = specimen.grading;
      info.refined_half_x = specimen.refined_region[0] / 2;
      info.refined_half_y = dim == 2 ? info.refined_half_x : specimen.refined_region[1] / 2;
      info.refined_depth = specimen.refined_region[2];
      info.contact_element_size =
          target_element_size(specimen.grading, specimen.grading.contact_radius);
      info.fine_layer_thickness = specimen.grading.min_element;
      coarse_block(triangulation, specimen);

      for (unsigned int pass = 0;; ++pass)
        {
          bool refined = false;
          for (const auto &cell : triangulation.active_cell_iterators())
            if (cell->is_locally_owned())
              {
                if (needs_halving(specimen.grading, *cell))
                  {
                    cell->set_refine_flag();
                    refined = true;
                  }
              }
          if (!Utilities::MPI::logical_or(refined, triangulation.get_communicator()))
            {
              info.refinement_levels = pass;
              break;
            }
          triangulation.execute_coarsening_and_refinement();
        }
      return info;
    }
  } // namespace

  template <int dim>
  MeshInfo build_indentation_mesh(parallel::distributed::Triangulation<dim> &triangulation,
                                  const io::SpecimenParameters              &specimen)
  {
    if (specimen.automatic_mesh())
      return build_graded_mesh(triangulation, specimen);
    const unsigned int n = specimen.contact_elements;
    const int          levels = refinement_levels_for(n);
    if (levels < 0)
      throw std::invalid_argument("specimen.contact_elements = " + std::to_string(n) +
                                  " cannot be meshed: it must be an even number >= 2");

    MeshInfo info;
    info.axisymmetric = (dim == 2);
    // The axisymmetric section is meshed as the quarter model's x >= 0 half.
    info.quarter = (specimen.symmetry == io::Symmetry::quarter);
    const bool half_line = info.quarter || info.axisymmetric;
    info.refinement_levels = levels;
    info.contact_element_size = specimen.refined_region[0] / n;
    info.refined_half_x = specimen.refined_region[0] / 2;
    // The axisymmetric model's refined region is a disc of radius refined_region_x / 2.
    info.refined_half_y = dim == 2 ? info.refined_half_x : specimen.refined_region[1] / 2;

    const double coarse = info.contact_element_size * (1u << levels);
    const double grading = 1.6; // size ratio of neighbouring coarse cells outside the region

    // Spacing along x or y: refined region cells of size `coarse` (approximately in y when the
    // region is not square), graded cells outside.
    auto lateral_spacing = [&](const double half_length, const double half_refined) {
      const unsigned int        n_half = std::max(1, int(std::lround(half_refined / coarse)));
      std::vector<double>       inner(n_half, half_refined / n_half);
      const std::vector<double> outer =
          graded_spacing(half_length - half_refined, half_refined / n_half, grading);
      std::vector<double> half_spacing(inner);
      half_spacing.insert(half_spacing.end(), outer.begin(), outer.end());
      if (half_line)
        return half_spacing;
      std::vector<double> full(half_spacing.rbegin(), half_spacing.rend());
      full.insert(full.end(), half_spacing.begin(), half_spacing.end());
      return full;
    };

    const std::vector<double> x_spacing =
        lateral_spacing(specimen.size[0] / 2, specimen.refined_region[0] / 2);
    const std::vector<double> y_spacing =
        lateral_spacing(specimen.size[1] / 2, specimen.refined_region[1] / 2);

    // Depth: the refined region's depth in whole layers of about `coarse`, graded below.
    const double              depth = specimen.refined_region[2];
    const unsigned int        n_layers = std::max(1, int(std::lround(depth / coarse)));
    std::vector<double>       z_spacing_top(n_layers, depth / n_layers);
    const std::vector<double> below =
        graded_spacing(specimen.size[2] - depth, depth / n_layers, grading);
    // subdivided_hyper_rectangle orders cells from p1 (bottom) to p2 (top).
    std::vector<double> z_spacing(below.rbegin(), below.rend());
    z_spacing.insert(z_spacing.end(), z_spacing_top.begin(), z_spacing_top.end());

    info.fine_layer_thickness = depth / n_layers / (1u << levels);
    info.refined_depth = depth;

    if constexpr (dim == 3)
      {
        const Point<3> p1(info.quarter ? 0. : -specimen.size[0] / 2,
                          info.quarter ? 0. : -specimen.size[1] / 2, -specimen.size[2]);
        const Point<3> p2(specimen.size[0] / 2, specimen.size[1] / 2, 0.);
        GridGenerator::subdivided_hyper_rectangle(triangulation, {x_spacing, y_spacing, z_spacing},
                                                  p1, p2,
                                                  /*colorize=*/true);
      }
    else
      {
        GridGenerator::subdivided_hyper_rectangle(triangulation, {x_spacing, z_spacing},
                                                  Point<2>(0., -specimen.size[2]),
                                                  Point<2>(specimen.size[0] / 2, 0.),
                                                  /*colorize=*/true);
        name_section_edges(triangulation);
      }

    // Refine the cells inside the refined region L times; p4est balances the rest 2:1.
    const double tol = 1e-8 * specimen.size[0];
    for (int level = 0; level < levels; ++level)
      {
        for (const auto &cell : triangulation.active_cell_iterators())
          if (cell->is_locally_owned())
            {
              const Point<dim> c = cell->center();
              const bool       lateral = dim == 2 || std::abs(c[1]) < info.refined_half_y - tol;
              if (std::abs(c[0]) < info.refined_half_x - tol && lateral &&
                  c[dim - 1] > -depth + tol)
                cell->set_refine_flag();
            }
        triangulation.execute_coarsening_and_refinement();
      }
    return info;
  }

  template MeshInfo build_indentation_mesh(parallel::distributed::Triangulation<2> &,
                                           const io::SpecimenParameters &);
  template MeshInfo build_indentation_mesh(parallel::distributed::Triangulation<3> &,
                                           const io::SpecimenParameters &);
} // namespace indentsim::mesh
