// Standard errors, intervals, correlations and identifiability (see FitStatistics.h).
#include "calibration/FitStatistics.h"

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/lapack_full_matrix.h>

#include <boost/math/distributions/students_t.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace indentsim::calibration
{
  namespace
  {
    constexpr double near_singular = 1e-3;    // smallest / largest scaled singular value
    constexpr double high_correlation = 0.95; // |rho_ij|

    std::string text(const double value)
    {
      std::ostringstream out;
      out.precision(4);
      out << value;
      return out.str();
    }
  } // namespace

  FitStatistics fit_statistics(const std::vector<double> &x, const std::vector<double> &residuals,
                               const std::vector<double>                &jacobian,
                               const std::vector<std::string>           &names,
                               const std::vector<std::array<double, 2>> &bounds)
  {
    const std::size_t p = x.size(), m = residuals.size();
    FitStatistics     s;
    const double      infinity = std::numeric_limits<double>::infinity();
    s.standard_error.assign(p, infinity);
    s.ci95.assign(p, {-infinity, infinity});
    s.correlation.assign(p, std::vector<double>(p, 0.));
    s.degrees_of_freedom = m > p ? static_cast<unsigned int>(m - p) : 0;
    double sum_of_squares = 0.;
    for (const double r : residuals)
      sum_of_squares += r * r;
    s.residual_variance = s.degrees_of_freedom > 0 ? sum_of_squares / s.degrees_of_freedom : 0.;
    s.t_quantile =
        s.degrees_of_freedom > 0
            ? boost::math::quantile(boost::math::students_t(double(s.degrees_of_freedom)), 0.975)
            : infinity;

    // J with unit columns (D = the column norms), its singular values.
    std::vector<double> norm(p, 0.);
    for (std::size_t i = 0; i < m; ++i)
      for (std::size_t j = 0; j < p; ++j)
        norm[j] += jacobian[i * p + j] * jacobian[i * p + j];
    std::vector<std::string> insensitive;
    for (std::size_t j = 0; j < p; ++j)
      {
        norm[j] = std::sqrt(norm[j]);
        if (!(norm[j] > 0.))
          insensitive.push_back(names[j]);
      }
    if (!insensitive.empty())
      {
        s.identifiable = false;
        s.scaled_condition = infinity;
        std::string list;
        for (const auto &n : insensitive)
          list += (list.empty() ? "" : ", ") + n;
        s.warnings.push_back("the data do not change with " + list +
                             ": nothing here determines it; add data that it affects");
        return s;
      }
    dealii::LAPACKFullMatrix<double> scaled(m, p);
    for (std::size_t i = 0; i < m; ++i)
      for (std::size_t j = 0; j < p; ++j)
        scaled(i, j) = jacobian[i * p + j] / norm[j];
    scaled.compute_svd();
    const unsigned int n_values = static_cast<unsigned int>(std::min(m, p));
    double             largest = 0., smallest = infinity;
    for (unsigned int k = 0; k < n_values; ++k)
      {
        largest = std::max(largest, scaled.singular_value(k));
        smallest = std::min(smallest, scaled.singular_value(k));
      }
    if (m < p)
      smallest = 0.;
    s.scaled_condition = smallest > 0. ? largest / smallest : infinity;
    if (!(smallest > near_singular * largest))
      {
        s.identifiable = false;
        std::string list;
        for (const auto &n : names)
          list += (list.empty() ? "" : ", ") + n;
        s.warnings.push_back("the normal matrix is near-singular (scaled condition number " +
                             text(s.scaled_condition) + "): the data cannot separate " + list);
        if (!(smallest > 1e-12 * largest))
          return s;
      }

    // (Jn^T Jn)^-1, then C = s^2 D^-1 (Jn^T Jn)^-1 D^-1.
    dealii::FullMatrix<double> inverse(p, p);
    for (std::size_t a = 0; a < p; ++a)
      for (std::size_t b = 0; b < p; ++b)
        {
          double sum = 0.;
          for (std::size_t i = 0; i < m; ++i)
            sum += jacobian[i * p + a] * jacobian[i * p + b] / (norm[a] * norm[b]);
          inverse(a, b) = sum;
        }
    inverse.gauss_jordan();
    for (std::size_t a = 0; a < p; ++a)
      {
        s.standard_error[a] = std::sqrt(s.residual_variance * inverse(a, a)) / norm[a];
        s.ci95[a] = {
            {x[a] - s.t_quantile * s.standard_error[a], x[a] + s.t_quantile * s.standard_error[a]}};
        for (std::size_t b = 0; b < p; ++b)
          s.correlation[a][b] = inverse(a, b) / std::sqrt(inverse(a, a) * inverse(b, b));
      }
    for (std::size_t a = 0; a < p; ++a)
      for (std::size_t b = a + 1; b < p; ++b)
        if (std::abs(s.correlation[a][b]) > high_correlation)
          {
            s.identifiable = false;
            s.warnings.push_back(names[a] + " and " + names[b] + " correlate (" +
                                 text(s.correlation[a][b]) +
                                 "): the data fix a combination of the two, not each");
          }
    for (std::size_t a = 0; a < p; ++a)
      if (s.ci95[a][1] - s.ci95[a][0] > bounds[a][1] - bounds[a][0])
        {
          s.identifiable = false;
          s.warnings.push_back(names[a] + ": the 95 % interval [" + text(s.ci95[a][0]) + ", " +
                               text(s.ci95[a][1]) + "] is wider than its bounds [" +
                               text(bounds[a][0]) + ", " + text(bounds[a][1]) + "]");
        }
    return s;
  }
} // namespace indentsim::calibration
