#include "materials/crystal/CubicElasticity.h"

#include <array>

namespace indentsim::materials
{
  using namespace crystal;

  // With the unrolled n^iJ_ab = dP_iJ/dS_ab = H_ia G_Jb (+ H_ib G_Ja for a < b),
  // dE_ab/dF_kL = w_ab n^kL_ab (w = 1 on the diagonal, 1/2 off it), and the cubic L^e,
  //   dP_iJ/dF_kL = (C11 - C12) sum_a n^iJ_aa n^kL_aa + C12 s^iJ s^kL
  //                 + C44 sum_(a<b) n^iJ_ab n^kL_ab + d_ik (G S_e G^T)_LJ,   s = sum_a n_aa,
  // symmetric in (iJ, kL) (hyperelasticity), so only half of it is formed.
  void CubicElasticity::elastic_tangent(const Matrix &H, const Matrix &G, const Matrix &S_e,
                                        dealii::Tensor<4, 3> &dP_dF) const
  {
    const Matrix                         Q = multiply_transposed_second(multiply(G, S_e), G);
    std::array<std::array<double, 7>, 9> n_unrolled; // n_aa (3), n_ab (3), s
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int J = 0; J < 3; ++J)
        {
          auto &v = n_unrolled[3 * i + J];
          for (unsigned int m = 0; m < 6; ++m)
            {
              const unsigned int a = sym_i[m], b = sym_j[m];
              v[m] = H[i][a] * G[J][b] + (m < 3 ? 0.0 : H[i][b] * G[J][a]);
            }
          v[6] = v[0] + v[1] + v[2];
        }
    const double normal = C11 - C12;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int J = 0; J < 3; ++J)
        {
          const auto &u = n_unrolled[3 * i + J];
          for (unsigned int k = i; k < 3; ++k)
            for (unsigned int L = (k == i ? J : 0); L < 3; ++L)
              {
                const auto &v = n_unrolled[3 * k + L];
                double      value = normal * (u[0] * v[0] + u[1] * v[1] + u[2] * v[2]) +
                               C12 * u[6] * v[6] + C44 * (u[3] * v[3] + u[4] * v[4] + u[5] * v[5]);
                if (i == k)
                  value += Q[L][J];
                dP_dF[i][J][k][L] = value;
                dP_dF[k][L][i][J] = value;
              }
        }
  }

  const char *CubicElasticity::parameter_error() const
  {
    if (!(C44 > 0 && C11 - C12 > 0 && C11 + 2 * C12 > 0))
      return "cubic stiffness not positive definite (need C44 > 0, C11 > C12, C11 + 2 C12 > 0)";
    return nullptr;
  }
} // namespace indentsim::materials
