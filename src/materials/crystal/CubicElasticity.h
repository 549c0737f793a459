// Anisotropic St-Venant-Kirchhoff elasticity of a cubic lattice (the paper's eq. 11):
//   Psi = 1/2 E_e : L^e : E_e,  S_e = L^e : E_e,
// L^e with C11, C12, C44 (Voigt notation, engineering shear strains 2 E_ij) in the lattice frame.
//
// An elasticity law for CrystalPlasticityModel (crystal/CrystalPlasticityModel.h) supplies:
//   stress(E)              S = L^e : E for a symmetric E; linear in E, so the integrator also uses
//                          it for the linearization dS = L^e : dE,
//   stiffness_scale()      a modulus [GPa] that makes the stress residuals strains,
//   reference_modulus()    MaterialModel::reference_modulus,
//   elastic_tangent(...)   dP/dF of P = H S_e G^T at fixed G (the elastic branch),
//   parameter_error()      nullptr, or what is wrong with the constants.
// A hexagonal lattice adds a struct with the same members (C11, C12, C13, C33, C44).
#pragma once

#include "materials/crystal/SmallMatrix.h"

#include <deal.II/base/tensor.h>

namespace indentsim::materials
{
  struct CubicElasticity
  {
    double C11 = 106.7, C12 = 60.4, C44 = 28.3; // [GPa]

    // S = L^e : E, E symmetric.
    crystal::Matrix stress(const crystal::Matrix &E) const
    {
      crystal::Matrix S;
      const double    trace_E = E[0][0] + E[1][1] + E[2][2];
      for (unsigned int i = 0; i < 3; ++i)
        {
          S[i][i] = (C11 - C12) * E[i][i] + C12 * trace_E;
          for (unsigned int j = i + 1; j < 3; ++j)
            {
              S[i][j] = 2.0 * C44 * E[i][j];
              S[j][i] = S[i][j];
            }
        }
      return S;
    }

    double stiffness_scale() const { return C44; }

    // Voigt average shear modulus (C11 - C12 + 3 C44) / 5 [GPa].
    double reference_modulus() const { return (C11 - C12 + 3.0 * C44) / 5.0; }

    // dP/dF of P = H S_e G^T (H = F G, G fixed, S_e = L^e : E_e, E_e = 1/2 (H^T H - I)).
    void elastic_tangent(const crystal::Matrix &H, const crystal::Matrix &G,
                         const crystal::Matrix &S_e, dealii::Tensor<4, 3> &dP_dF) const;

    const char *parameter_error() const;
  };
} // namespace indentsim::materials
