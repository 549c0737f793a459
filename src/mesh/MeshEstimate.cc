#include "mesh/MeshEstimate.h"

#include "mesh/IndentationMesh.h"
#include "mesh/MeshDesign.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace indentsim::mesh
{
  namespace
  {
    // Coarse cells along one lateral axis as build_indentation_mesh lays them out: `inner`
    // cells on each side of the axis inside the refined region, `outer` graded ones beyond it.
    struct AxisCount
    {
      std::uint64_t inner = 0, outer = 0;
    };

    AxisCount lateral_count(const double half_length, const double half_refined,
                            const double coarse)
    {
      AxisCount count;
      count.inner = std::max(1, int(std::lround(half_refined / coarse)));
      const double remaining = half_length - half_refined;
      count.outer =
          remaining > 0 ? graded_spacing(remaining, half_refined / count.inner, 1.6).size() : 0;
      return count;
    }

    std::uint64_t power(const std::uint64_t base, const unsigned int exponent)
    {
      std::uint64_t result = 1;
      for (unsigned int i = 0; i < exponent; ++i)
        result *= base;
      return result;
    }

    // The (r, z) section: the refined block of bx x bz coarse cells refined L times, its 2:1
    // transition along its open side and bottom (each level's transition cell splits in 4).
    MeshSize axisymmetric_mesh(const AxisCount &x, const std::uint64_t z_inner,
                               const std::uint64_t z_outer, const unsigned int L)
    {
      const std::uint64_t bx = x.inner, bz = z_inner, nx = x.inner + x.outer,
                          nz = z_inner + z_outer;
      const std::uint64_t open_x = x.outer > 0 ? 1 : 0, open_bottom = z_outer > 0 ? 1 : 0;
      const std::uint64_t edge = open_x * bz + open_bottom * bx, corner = open_x * open_bottom;
      std::uint64_t       refinements = 0;
      for (unsigned int j = 0; j + 2 <= L; ++j)
        refinements += edge * power(2, j) + corner;
      const std::uint64_t fine = std::uint64_t(1) << L;
      MeshSize            size;
      size.cells = nx * nz - bx * bz + bx * bz * power(4, L) + 3 * refinements;
      size.vertices = (bx * fine + 1) * (bz * fine + 1) + (nx + 1) * (nz + 1) -
                      (bx + 1) * (bz + 1) + 4 * refinements;
      size.dofs = 2 * size.vertices;
      return size;
    }

    // The automatic mesh: the leaves of the octree build_graded_mesh refines (needs_halving,
    // mesh/MeshDesign.h), without p4est's 2:1 balance. Counting stops beyond `limit` leaves
    // (the memory estimate refuses such meshes).
    struct LeafCounter
    {
      const io::MeshGrading &grading;
      unsigned int           dim;
      std::uint64_t          leaves = 0, limit = 200'000'000;

      void count(const std::array<double, 3> &lower, const std::array<double, 3> &upper)
      {
        if (leaves > limit)
          return;
        if (!needs_halving(grading, lower, upper, dim))
          {
            ++leaves;
            return;
          }
        for (unsigned int child = 0; child < (1u << dim); ++child)
          {
            std::array<double, 3> child_lower = lower, child_upper = upper;
            for (unsigned int d = 0; d < dim; ++d)
              {
                const double middle = 0.5 * (lower[d] + upper[d]);
                ((child >> d & 1u) ? child_lower[d] : child_upper[d]) = middle;
              }
            count(child_lower, child_upper);
          }
      }
    };

    // Vertices per cell of a balanced graded octree (measured on the built meshes of the
    // paper's case: 2D 1.06, 3D 1.42, hanging nodes included; tests/unit compares).
    MeshSize graded_mesh(const io::SpecimenParameters &specimen)
    {
      const CoarseGrid      grid = coarse_grid(specimen);
      LeafCounter           counter{specimen.grading, grid.dim};
      std::array<double, 3> edge{};
      for (unsigned int d = 0; d < grid.dim; ++d)
        edge[d] = (grid.upper[d] - grid.lower[d]) / grid.cells[d];
      for (long i = 0; i < grid.cells[0]; ++i)
        for (long j = 0; j < grid.cells[1]; ++j)
          for (long k = 0; k < grid.cells[2]; ++k)
            {
              const std::array<long, 3> index = {{i, j, k}};
              std::array<double, 3>     lower{}, upper{};
              for (unsigned int d = 0; d < grid.dim; ++d)
                {
                  lower[d] = grid.lower[d] + index[d] * edge[d];
                  upper[d] = lower[d] + edge[d];
                }
              counter.count(lower, upper);
            }
      MeshSize size;
      size.cells = counter.leaves;
      size.vertices =
          static_cast<std::uint64_t>(double(size.cells) * (grid.dim == 2 ? 1.06 : 1.42));
      size.dofs = grid.dim * size.vertices;
      return size;
    }
  } // namespace

  MeshSize estimate_indentation_mesh(const io::SpecimenParameters &specimen)
  {
    if (specimen.automatic_mesh())
      return graded_mesh(specimen);
    const int levels = refinement_levels_for(specimen.contact_elements);
    if (levels < 0)
      return {};
    const unsigned int L = static_cast<unsigned int>(levels);
    const bool         quarter = specimen.symmetry == io::Symmetry::quarter;
    const double coarse = specimen.refined_region[0] / specimen.contact_elements * double(1u << L);

    const AxisCount x = lateral_count(specimen.size[0] / 2, specimen.refined_region[0] / 2, coarse);
    const AxisCount y = lateral_count(specimen.size[1] / 2, specimen.refined_region[1] / 2, coarse);
    const double    depth = specimen.refined_region[2];
    const std::uint64_t z_inner = std::max(1, int(std::lround(depth / coarse)));
    const std::uint64_t z_outer =
        specimen.size[2] > depth
            ? graded_spacing(specimen.size[2] - depth, depth / z_inner, 1.6).size()
            : 0;
    if (specimen.symmetry == io::Symmetry::axisymmetric)
      return axisymmetric_mesh(x, z_inner, z_outer, L);

    // Coarse grid and the block of refined coarse cells (touching the top face; in the quarter
    // model also the symmetry planes).
    const std::uint64_t sides = quarter ? 1 : 2;
    const std::uint64_t bx = sides * x.inner, by = sides * y.inner, bz = z_inner;
    const std::uint64_t nx = sides * (x.inner + x.outer), ny = sides * (y.inner + y.outer),
                        nz = z_inner + z_outer;
    const std::uint64_t block = bx * by * bz, coarse_cells = nx * ny * nz;

    // Coarse neighbours of the block by face, edge and corner: the block's lateral sides that
    // have cells beyond them (`open_x` of 0, 1 or 2) and its bottom.
    const std::uint64_t open_x = x.outer > 0 ? sides : 0, open_y = y.outer > 0 ? sides : 0;
    const std::uint64_t open_bottom = z_outer > 0 ? 1 : 0;
    const std::uint64_t face = open_x * by * bz + open_y * bx * bz + open_bottom * bx * by;
    const std::uint64_t edge = open_x * open_y * bz + open_bottom * (open_x * by + open_y * bx);
    const std::uint64_t corner = open_bottom * open_x * open_y;
    std::uint64_t       refinements = 0;
    for (unsigned int j = 0; j + 2 <= L; ++j)
      refinements += face * power(4, j) + edge * power(2, j) + corner;

    const std::uint64_t fine = std::uint64_t(1) << L;
    MeshSize            size;
    size.cells = coarse_cells - block + block * power(8, L) + 7 * refinements;
    size.vertices = (bx * fine + 1) * (by * fine + 1) * (bz * fine + 1) +
                    (nx + 1) * (ny + 1) * (nz + 1) - (bx + 1) * (by + 1) * (bz + 1) +
                    8 * refinements;
    size.dofs = 3 * size.vertices;
    return size;
  }

  MeshSize estimate_tensile_mesh(const io::SpecimenParameters &specimen)
  {
    const std::uint64_t n = specimen.elements_per_side;
    MeshSize            size;
    size.cells = n * n * n;
    size.vertices = (n + 1) * (n + 1) * (n + 1);
    size.dofs = 3 * size.vertices;
    return size;
  }

  MeshSize estimate_mesh(const io::Case &the_case)
  {
    return the_case.test == io::TestKind::tensile ? estimate_tensile_mesh(the_case.specimen)
                                                  : estimate_indentation_mesh(the_case.specimen);
  }
} // namespace indentsim::mesh
