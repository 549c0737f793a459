// A material point under homogeneous uniaxial Cauchy stress along the sample z axis, and the
// orientation that puts a crystal direction on that axis; shared by the crystal tests.
// Units: GPa.
#pragma once

#include "materials/MaterialModel.h"
#include "materials/crystal/Orientation.h"

#include "material_test_utilities.h"

#include <array>
#include <cmath>
#include <utility>
#include <vector>

namespace indentsim::testing
{
  using namespace indentsim::materials;
  using dealii::Tensor;

  // Homogeneous uniaxial Cauchy stress along the sample z axis at a material point: F is upper
  // triangular (which fixes the rotation), F_zz = stretch is prescribed and F_xx, F_xy, F_xz,
  // F_yy, F_yz are solved from sigma_xx = sigma_yy = sigma_xy = sigma_xz = sigma_yz = 0 by
  // Newton's method with a finite-difference Jacobian (independent of the model's tangent).
  struct UniaxialDriver
  {
    const MaterialModel &model;
    std::vector<double>  state;
    Tensor<2, 3>         F = identity();

    // Returns sigma_zz [GPa] after loading to `stretch` from the current state in one
    // increment; the state is updated.
    double load_to(const double stretch, UpdateStatus *status_out = nullptr)
    {
      static constexpr unsigned int unknown_i[5] = {0, 0, 0, 1, 1};
      static constexpr unsigned int unknown_j[5] = {0, 1, 2, 1, 2};
      static constexpr unsigned int equation_i[5] = {0, 1, 0, 0, 1};
      static constexpr unsigned int equation_j[5] = {0, 1, 1, 2, 2};
      F[2][2] = stretch;
      std::vector<double> state_new(state.size());
      const auto          residual = [&](const Tensor<2, 3> &F_trial, std::array<double, 5> &r,
                                double &sigma_zz) {
        MaterialPointResponse response;
        const UpdateStatus    status = model.update(F_trial, state, response, state_new, false);
        const double          J = dealii::determinant(F_trial);
        for (unsigned int e = 0; e < 5; ++e)
          r[e] = response.tau[equation_i[e]][equation_j[e]] / J;
        sigma_zz = response.tau[2][2] / J;
        return status;
      };
      double                sigma_zz = 0;
      std::array<double, 5> r;
      for (unsigned int iteration = 0; iteration < 40; ++iteration)
        {
          const UpdateStatus status = residual(F, r, sigma_zz);
          if (status_out)
            *status_out = status;
          if (status != UpdateStatus::success)
            return std::nan("");
          double norm = 0;
          for (const double a : r)
            norm = std::max(norm, std::abs(a));
          if (norm < 1e-13)
            break;
          double jacobian[5][6];
          for (unsigned int u = 0; u < 5; ++u)
            {
              const double          h = 1e-7;
              Tensor<2, 3>          F_plus = F, F_minus = F;
              std::array<double, 5> r_plus, r_minus;
              double                dummy;
              F_plus[unknown_i[u]][unknown_j[u]] += h;
              F_minus[unknown_i[u]][unknown_j[u]] -= h;
              residual(F_plus, r_plus, dummy);
              residual(F_minus, r_minus, dummy);
              for (unsigned int e = 0; e < 5; ++e)
                jacobian[e][u] = (r_plus[e] - r_minus[e]) / (2 * h);
            }
          for (unsigned int e = 0; e < 5; ++e)
            jacobian[e][5] = -r[e];
          // Gaussian elimination with partial pivoting.
          for (unsigned int k = 0; k < 5; ++k)
            {
              unsigned int pivot = k;
              for (unsigned int i = k + 1; i < 5; ++i)
                if (std::abs(jacobian[i][k]) > std::abs(jacobian[pivot][k]))
                  pivot = i;
              for (unsigned int j = 0; j < 6; ++j)
                std::swap(jacobian[k][j], jacobian[pivot][j]);
              for (unsigned int i = k + 1; i < 5; ++i)
                {
                  const double factor = jacobian[i][k] / jacobian[k][k];
                  for (unsigned int j = k; j < 6; ++j)
                    jacobian[i][j] -= factor * jacobian[k][j];
                }
            }
          double step[5];
          for (int k = 4; k >= 0; --k)
            {
              double sum = jacobian[k][5];
              for (unsigned int j = k + 1; j < 5; ++j)
                sum -= jacobian[k][j] * step[j];
              step[k] = sum / jacobian[k][k];
            }
          for (unsigned int u = 0; u < 5; ++u)
            F[unknown_i[u]][unknown_j[u]] += step[u];
        }
      residual(F, r, sigma_zz);
      state.assign(state_new.begin(), state_new.end());
      return sigma_zz;
    }
  };

  // g putting the crystal direction `axis` along the sample z (tensile) axis.
  inline Tensor<2, 3> axis_along_z(const std::array<double, 3> &axis)
  {
    // any crystal direction perpendicular to `axis` along sample x
    const std::array<double, 3> reference = (axis[0] == 0 && axis[1] == 0)
                                                ? std::array<double, 3>{{1, 0, 0}}
                                                : std::array<double, 3>{{-axis[1], axis[0], 0}};
    return rotation_from_surface_normal(axis, reference);
  }

  // The initial yield stress sigma_zz [GPa] in uniaxial tension from `state0`: the largest
  // stretch that leaves the point elastic, found by bisection (60 halvings) between 1 and
  // `plastic_stretch` (which must yield), each trial loaded in one increment from state0.
  inline double initial_yield_stress(const MaterialModel &model, const std::vector<double> &state0,
                                     const double plastic_stretch)
  {
    double elastic = 1.0, plastic = plastic_stretch;
    for (unsigned int k = 0; k < 60; ++k)
      {
        const double   middle = 0.5 * (elastic + plastic);
        UniaxialDriver driver{model, state0};
        driver.load_to(middle);
        (model.equivalent_plastic_strain(driver.state) > 0 ? plastic : elastic) = middle;
      }
    UniaxialDriver driver{model, state0};
    return driver.load_to(elastic);
  }

} // namespace indentsim::testing
