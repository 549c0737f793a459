// Eight doubles as one vector (GCC's vector extension): a row of an element tangent over eight
// nodes (the hexahedron, one component at a time) or eight dofs (the axisymmetric
// quadrilateral). One AVX-512 register, two AVX2 ones, four SSE2 ones: the element kernels build
// their tangents from such rows in functions cloned for AVX2 and AVX-512
// ([[gnu::target_clones]], the clone chosen at load time).
#pragma once

#include <cstring>

namespace indentsim::fem::tangent_row
{
  using Row = double __attribute__((vector_size(64)));

  inline Row load(const double *p)
  {
    Row r;
    std::memcpy(&r, p, sizeof(Row));
    return r;
  }

  inline void store(double *p, const Row &r)
  {
    std::memcpy(p, &r, sizeof(Row));
  }
} // namespace indentsim::fem::tangent_row
