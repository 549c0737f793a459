// Anisotropic St-Venant-Kirchhoff elasticity of a crystal lattice (the paper's eq. 11):
//   Psi = 1/2 E_e : L^e : E_e,  S_e = L^e : E_e,
// with L^e in the lattice frame (SlipSystems.h states the frames) of cubic or hexagonal
// symmetry. Both have the form, in Voigt notation with engineering shear strains 2 E_ij,
//   S_aa = sum_b N_ab E_bb (a, b = x, y, z),   S_ab = 2 G_ab E_ab (a != b),
// cubic: N = (C11 - C12) I + C12 1 1^T, G = C44;
// hexagonal (c along z): N_xx = N_yy = C11, N_xy = C12, N_xz = N_yz = C13, N_zz = C33,
// G_yz = G_xz = C44, G_xy = C66 = (C11 - C12)/2 (transversely isotropic about c).
//
// An elasticity law for CrystalPlasticityModel (crystal/CrystalPlasticityModel.h) supplies:
//   stress(E)              S = L^e : E for a symmetric E; linear in E, so the integrator also uses
//                          it for the linearization dS = L^e : dE,
//   stiffness_scale()      a modulus [GPa] that makes the stress residuals strains,
//   reference_modulus()    MaterialModel::reference_modulus,
//   elastic_tangent(...)   dP/dF of P = H S_e G^T at fixed G (the elastic branch),
//   parameter_error()      nullptr, or what is wrong with the constants.
// Units: GPa.
#pragma once

#include "materials/crystal/SmallMatrix.h"

#include <deal.II/base/tensor.h>

#include <array>

namespace indentsim::materials
{
  struct LatticeElasticity
  {
    enum class Symmetry
    {
      cubic,
      hexagonal
    };
    Symmetry                             symmetry = Symmetry::cubic;
    std::array<std::array<double, 3>, 3> normal; // N_ab [GPa]
    std::array<double, 3>                shear; // G_xy, G_xz, G_yz [GPa] (SmallMatrix's 01, 02, 12)

    // The paper's Table 2 (aluminium): cubic with C11 = 106.7, C12 = 60.4, C44 = 28.3 GPa.
    LatticeElasticity()
      : LatticeElasticity(cubic(106.7, 60.4, 28.3))
    {
    }
    static LatticeElasticity cubic(double C11, double C12, double C44);
    static LatticeElasticity hexagonal(double C11, double C12, double C13, double C33, double C44);

    // S = L^e : E, E symmetric.
    crystal::Matrix stress(const crystal::Matrix &E) const
    {
      crystal::Matrix S;
      for (unsigned int a = 0; a < 3; ++a)
        S[a][a] = normal[a][0] * E[0][0] + normal[a][1] * E[1][1] + normal[a][2] * E[2][2];
      for (unsigned int m = 0; m < 3; ++m)
        {
          const unsigned int a = crystal::sym_i[3 + m], b = crystal::sym_j[3 + m];
          S[a][b] = S[b][a] = 2.0 * shear[m] * E[a][b];
        }
      return S;
    }

    // C44 (the shear modulus on the planes containing z).
    double stiffness_scale() const { return shear[2]; }

    // Voigt average shear modulus (sum N_aa - sum_(a<b) N_ab + 3 sum G) / 15 [GPa]; cubic:
    // (C11 - C12 + 3 C44) / 5.
    double reference_modulus() const;

    // dP/dF of P = H S_e G^T (H = F G, G fixed, S_e = L^e : E_e, E_e = 1/2 (H^T H - I)).
    void elastic_tangent(const crystal::Matrix &H, const crystal::Matrix &G,
                         const crystal::Matrix &S_e, dealii::Tensor<4, 3> &dP_dF) const;

    const char *parameter_error() const;

  private:
    LatticeElasticity(Symmetry symmetry, const std::array<std::array<double, 3>, 3> &normal,
                      const std::array<double, 3> &shear)
      : symmetry(symmetry)
      , normal(normal)
      , shear(shear)
    {
    }
  };
} // namespace indentsim::materials
