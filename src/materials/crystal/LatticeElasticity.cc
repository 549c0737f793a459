#include "materials/crystal/LatticeElasticity.h"

#include <array>

namespace indentsim::materials
{
  using namespace crystal;

  LatticeElasticity LatticeElasticity::cubic(const double C11, const double C12, const double C44)
  {
    return LatticeElasticity(Symmetry::cubic, {{{C11, C12, C12}, {C12, C11, C12}, {C12, C12, C11}}},
                             {C44, C44, C44});
  }

  LatticeElasticity LatticeElasticity::hexagonal(const double C11, const double C12,
                                                 const double C13, const double C33,
                                                 const double C44)
  {
    return LatticeElasticity(Symmetry::hexagonal,
                             {{{C11, C12, C13}, {C12, C11, C13}, {C13, C13, C33}}},
                             {(C11 - C12) / 2, C44, C44});
  }

  double LatticeElasticity::reference_modulus() const
  {
    return (normal[0][0] + normal[1][1] + normal[2][2] - normal[0][1] - normal[0][2] -
            normal[1][2] + 3.0 * (shear[0] + shear[1] + shear[2])) /
           15.0;
  }

  // With the unrolled n^iJ_ab = dP_iJ/dS_ab = H_ia G_Jb (+ H_ib G_Ja for a < b),
  // dE_ab/dF_kL = w_ab n^kL_ab (w = 1 on the diagonal, 1/2 off it), and L^e,
  //   dP_iJ/dF_kL = sum_ab N_ab n^iJ_aa n^kL_bb + sum_(a<b) G_ab n^iJ_ab n^kL_ab
  //                 + d_ik (G S_e G^T)_LJ,
  // symmetric in (iJ, kL) (hyperelasticity), so only half of it is formed.
  void LatticeElasticity::elastic_tangent(const Matrix &H, const Matrix &G, const Matrix &S_e,
                                          dealii::Tensor<4, 3> &dP_dF) const
  {
    const Matrix                         Q = multiply_transposed_second(multiply(G, S_e), G);
    std::array<std::array<double, 6>, 9> n_unrolled; // n_aa (3), n_ab (3)
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int J = 0; J < 3; ++J)
        {
          auto &v = n_unrolled[3 * i + J];
          for (unsigned int m = 0; m < 6; ++m)
            {
              const unsigned int a = sym_i[m], b = sym_j[m];
              v[m] = H[i][a] * G[J][b] + (m < 3 ? 0.0 : H[i][b] * G[J][a]);
            }
        }
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int J = 0; J < 3; ++J)
        {
          const auto &u = n_unrolled[3 * i + J];
          // N u_normal, formed once per row
          std::array<double, 3> Nu;
          for (unsigned int b = 0; b < 3; ++b)
            Nu[b] = normal[0][b] * u[0] + normal[1][b] * u[1] + normal[2][b] * u[2];
          for (unsigned int k = i; k < 3; ++k)
            for (unsigned int L = (k == i ? J : 0); L < 3; ++L)
              {
                const auto &v = n_unrolled[3 * k + L];
                double value = Nu[0] * v[0] + Nu[1] * v[1] + Nu[2] * v[2] + shear[0] * u[3] * v[3] +
                               shear[1] * u[4] * v[4] + shear[2] * u[5] * v[5];
                if (i == k)
                  value += Q[L][J];
                dP_dF[i][J][k][L] = value;
                dP_dF[k][L][i][J] = value;
              }
        }
  }

  const char *LatticeElasticity::parameter_error() const
  {
    // Sylvester's criterion on the normal block, and positive shear moduli.
    const auto  &N = normal;
    const double minor2 = N[0][0] * N[1][1] - N[0][1] * N[1][0];
    const double minor3 = N[0][0] * (N[1][1] * N[2][2] - N[1][2] * N[2][1]) -
                          N[0][1] * (N[1][0] * N[2][2] - N[1][2] * N[2][0]) +
                          N[0][2] * (N[1][0] * N[2][1] - N[1][1] * N[2][0]);
    const bool positive =
        N[0][0] > 0 && minor2 > 0 && minor3 > 0 && shear[0] > 0 && shear[1] > 0 && shear[2] > 0;
    if (positive)
      return nullptr;
    if (symmetry == Symmetry::cubic)
      return "cubic stiffness not positive definite (need C44 > 0, C11 > C12, C11 + 2 C12 > 0)";
    return "hexagonal stiffness not positive definite (need C44 > 0, C11 > |C12|, "
           "C33 (C11 + C12) > 2 C13^2)";
  }
} // namespace indentsim::materials
