#include "materials/NeoHookean.h"
#include "materials/TensorFunctions.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace indentsim::materials
{
  bool admissible_deformation(const Tensor<2, 3> &F, double &J_minus_one)
  {
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        if (!std::isfinite(F[i][j]))
          return false;
    J_minus_one = determinant_minus_one(F);
    return std::isfinite(J_minus_one) && J_minus_one > -1.0;
  }

  NeoHookean::NeoHookean(const double young_modulus, const double poisson_ratio)
  {
    if (!(young_modulus > 0.0) || !std::isfinite(young_modulus))
      throw std::invalid_argument("NeoHookean: young_modulus = " + std::to_string(young_modulus) +
                                  " GPa; it must be positive and finite");
    if (!(poisson_ratio > -1.0 && poisson_ratio < 0.5))
      throw std::invalid_argument("NeoHookean: poisson_ratio = " + std::to_string(poisson_ratio) +
                                  "; it must lie in (-1, 0.5)");
    mu = young_modulus / (2.0 * (1.0 + poisson_ratio));
    lambda = young_modulus * poisson_ratio / ((1.0 + poisson_ratio) * (1.0 - 2.0 * poisson_ratio));
  }

  double NeoHookean::energy(const Tensor<2, 3> &F) const
  {
    double J_minus_one = 0.0;
    if (!admissible_deformation(F, J_minus_one))
      return std::numeric_limits<double>::infinity();
    // I1 - 3 = tr(F F^T) - 3 = 2 tr H + H : H with H = F - I.
    double I1_minus_3 = 0.0;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        {
          const double H_ij = F[i][j] - (i == j ? 1.0 : 0.0);
          I1_minus_3 += H_ij * H_ij + (i == j ? 2.0 * H_ij : 0.0);
        }
    const double log_I3 = 2.0 * std::log1p(J_minus_one);
    const double I3_minus_1 = J_minus_one * (J_minus_one + 2.0);
    return 0.5 * mu * (I1_minus_3 - log_I3) + 0.25 * lambda * (I3_minus_1 - log_I3);
  }

  dealii::SymmetricTensor<2, 3>
  NeoHookean::kirchhoff_stress(const dealii::SymmetricTensor<2, 3> &b_e,
                               const double                         J_minus_one) const
  {
    // eq. 3 applied to eq. 2; J^2 - 1 = (J - 1)(J + 1).
    const double                  pressure_term = 0.5 * lambda * J_minus_one * (J_minus_one + 2.0);
    dealii::SymmetricTensor<2, 3> tau;
    for (unsigned int k = 0; k < 6; ++k)
      tau.access_raw_entry(k) = mu * b_e.access_raw_entry(k);
    for (unsigned int k = 0; k < 3; ++k)
      tau.access_raw_entry(k) += pressure_term - mu;
    return tau;
  }

  void NeoHookean::elastic_response(const Tensor<2, 3>                  &F,
                                    const dealii::SymmetricTensor<2, 3> &C_p_inverse,
                                    const double J_minus_one, MaterialPointResponse &response,
                                    const bool compute_tangent) const
  {
    const Tensor<2, 3> F_inverse = inverse_3x3(F);
    const double       J = 1.0 + J_minus_one;
    const double       pressure_term = 0.5 * lambda * J_minus_one * (J_minus_one + 2.0);

    // F C_p^-1, shared by P and tau.
    Tensor<2, 3> F_C;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        {
          double sum = 0.0;
          for (unsigned int m = 0; m < 3; ++m)
            sum += F[i][m] * C_p_inverse[m][j];
          F_C[i][j] = sum;
        }

    // P = mu (F C_p^-1 - F^-T) + lambda/2 (J^2 - 1) F^-T;  tau = P F^T = mu (b_e - 1) + ...
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        response.P[i][j] = mu * F_C[i][j] + (pressure_term - mu) * F_inverse[j][i];
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = i; j < 3; ++j)
        {
          double b_ij = 0.0;
          for (unsigned int m = 0; m < 3; ++m)
            b_ij += F_C[i][m] * F[j][m];
          const double tau_ij = mu * b_ij + (i == j ? pressure_term - mu : 0.0);
          response.tau[i][j] = tau_ij;
          response.tau[j][i] = tau_ij;
        }

    if (!compute_tangent)
      return;
    const double c_1 = mu - pressure_term; // mu - lambda/2 (J^2 - 1)
    const double c_2 = lambda * J * J;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int J_index = 0; J_index < 3; ++J_index)
        for (unsigned int k = 0; k < 3; ++k)
          for (unsigned int L = 0; L < 3; ++L)
            response.dP_dF[i][J_index][k][L] = (i == k ? mu * C_p_inverse[L][J_index] : 0.0) +
                                               c_1 * F_inverse[L][i] * F_inverse[J_index][k] +
                                               c_2 * F_inverse[J_index][i] * F_inverse[L][k];
  }

  UpdateStatus NeoHookean::update(const Tensor<2, 3>    &F, std::span<const double> /*state_old*/,
                                  MaterialPointResponse &response, std::span<double> /*state_new*/,
                                  const bool             compute_tangent) const
  {
    double J_minus_one = 0.0;
    if (!admissible_deformation(F, J_minus_one))
      return UpdateStatus::invalid_deformation;
    elastic_response(F, dealii::unit_symmetric_tensor<3>(), J_minus_one, response, compute_tangent);
    return UpdateStatus::success;
  }
} // namespace indentsim::materials
