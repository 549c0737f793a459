// The size of a case's mesh from its keys, without building it: cells, vertices and DOFs of the
// indentation block (IndentationMesh.h) and of the tensile cube. `indentsim check` and `run`
// print it with the memory estimate (output/MemoryEstimate.h) before anything is computed.
// Units: um.
//
// The indentation block is a tensor-product coarse grid (the same spacings as
// build_indentation_mesh) whose B coarse cells inside the refined region are refined L times.
// p4est's 2:1 balance then refines the coarse cells around that block: a coarse neighbour that
// shares a face with the block is refined once, then its children touching the block again, up
// to level L - 1 (4^j refinements at level j), an edge neighbour 2^j, a corner neighbour 1 at
// each level j = 0 ... L - 2. Each refinement adds 7 cells and about 8 vertices (7 where its
// neighbours are refined as well, more beside unrefined cells). The count of cells is exact for the block refined this way (a test builds
// meshes and compares); the vertices are exact without balance cells, within 2 % with them
// above 20 000 DOFs and within 5 % on tiny meshes.
//
// The automatic mesh (specimen.contact_elements: auto) is counted as the leaves of its octree
// without the balance (cells within 3 %), its vertices as 1.06 (2D) or 1.42 (3D) per cell
// (DOFs within 10 %, tests/unit/test_mesh_design.cc).
#pragma once

#include "case/Case.h"

#include <cstdint>

namespace indentsim::mesh
{
  struct MeshSize
  {
    std::uint64_t cells = 0;
    std::uint64_t vertices = 0;
    std::uint64_t dofs = 0; // 3 per vertex (hanging and constrained ones included)
  };

  // Indentation block of `specimen` (its contact_elements, refined_region, size and symmetry, or
  // its grading).
  // Cases whose contact_elements cannot be meshed (refinement_levels_for < 0) give zeros.
  MeshSize estimate_indentation_mesh(const io::SpecimenParameters &specimen);

  // The tensile cube of elements_per_side^3 cells.
  MeshSize estimate_tensile_mesh(const io::SpecimenParameters &specimen);

  // Whichever test the case runs.
  MeshSize estimate_mesh(const io::Case &the_case);
} // namespace indentsim::mesh
