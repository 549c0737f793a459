// What the Jacobian at the optimum says of the fitted parameters: standard errors, 95 %
// intervals, correlations, and whether the data determine the parameters at all.
//
// With r (m residuals, weighted and relative, calibration/ResidualModel.h) and J = dr/dx at the
// optimum (m x p), the residual variance is s^2 = r.r / (m - p) and the covariance of the
// estimate C = s^2 (J^T J)^-1 (the Gauss-Newton approximation: independent errors of equal
// variance in the weighted residuals); standard error sqrt(C_jj), the 95 % interval
// x_j +- t_{0.975, m-p} sqrt(C_jj) (Student's t), correlation C_ij / sqrt(C_ii C_jj).
//
// Not identifiable (a loud warning, docs/calibration.md) when any of:
//   - J^T J is near-singular: with J's columns scaled to unit length, the smallest singular
//     value is below 1e-3 of the largest (or a column is 0: the parameter changes nothing);
//   - two parameters correlate above 0.95 in magnitude;
//   - a 95 % interval is wider than the parameter's bounds.
// Units: those of the parameters.
#pragma once

#include <array>
#include <string>
#include <vector>

namespace indentsim::calibration
{
  struct FitStatistics
  {
    std::vector<double>                standard_error;
    std::vector<std::array<double, 2>> ci95;
    std::vector<std::vector<double>>   correlation;
    double                             residual_variance = 0.; // s^2
    unsigned int                       degrees_of_freedom = 0; // m - p
    double                             t_quantile = 0.;        // t_{0.975, m-p}
    double                             scaled_condition = 0.;  // singular values, max / min
    bool                               identifiable = true;
    std::vector<std::string>           warnings; // each names the parameters involved
  };

  // `jacobian` row-major m x p; `names` and `bounds` ([min, max]) per parameter.
  FitStatistics fit_statistics(const std::vector<double> &x, const std::vector<double> &residuals,
                               const std::vector<double>                &jacobian,
                               const std::vector<std::string>           &names,
                               const std::vector<std::array<double, 2>> &bounds);
} // namespace indentsim::calibration
