// The scalar rules of the augmented-Lagrangian Newton iteration (problems/IndentationNewton.cc),
// apart from any mesh, so that each can be tested alone. Residual norms in mN.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace indentsim::nonlinear
{
  // Backtracking line search on phi = |R|^2 / 2 along the Newton direction (phi'(0) = -2 phi(0)):
  // the minimiser of the quadratic model through phi(0) = previous_norm^2 / 2 and
  // phi(alpha) = norm^2 / 2, kept within [min_alpha, alpha / 2]. A failed evaluation (norm not
  // finite) counts as a huge residual.
  inline double line_search_step(const double alpha, const double previous_norm, const double norm,
                                 const double min_alpha)
  {
    const double phi0 = previous_norm * previous_norm,
                 phi1 = std::isfinite(norm) ? norm * norm : 1e300;
    return std::clamp(alpha * phi0 / (phi0 + phi1), min_alpha, alpha / 2);
  }

  // Inexact Newton: the relative tolerance of the linear solve follows the residual,
  // 0.1 |R| / |R_ref| within [1e-10, 1e-3], so that the linear error stays below the quadratic
  // Newton error and the last iterations keep their rate. The cap 1e-3 (not 1e-2) keeps the
  // contact active-set iteration on the path of the direct solver: looser solves make the
  // active set cycle. The floor `oversolving_floor` (1e-2 R_end / |R|, R_end the residual at
  // which the pass ends) stops the last iterate of a pass from being solved far below what the
  // pass needs: a loose solve leaves smooth displacement errors with a small residual, which move
  // plastic points and contact nodes across their switching surfaces, so the factor 1e-2 balances
  // Krylov iterations saved against Newton iterations lost.
  inline double linear_tolerance(const double norm, const double reference,
                                 const double oversolving_floor)
  {
    return std::clamp(std::max(0.1 * norm / reference, oversolving_floor), 1e-10, 1e-3);
  }

  // |R_it| / |R_it-1| of Newton iteration `it` of augmentation pass `pass` in the last increment
  // that reached it (the last slots shared by the later passes and iterations; 0: unknown).
  class ResidualReductions
  {
  public:
    double &at(const unsigned int pass, const unsigned int it)
    {
      return table_[std::min<unsigned int>(pass, n - 1)][std::min<unsigned int>(it, n - 1)];
    }

  private:
    static constexpr unsigned int        n = 6;
    std::array<std::array<double, n>, n> table_{};
  };

  // The residual an iterate is expected to have: from the quadratic rate of the last two full
  // Newton steps, |R_k+1| ~ |R_k|^3 / |R_k-1|^2, or else from the reduction the same iteration of
  // the same pass achieved in the last increment (`remembered`, 0: unknown); infinity if neither
  // is known. `norm_two_back` is 0 unless a full Newton step joined the last two iterates.
  inline double predicted_residual(const double norm_one_back, const double norm_two_back,
                                   const double remembered)
  {
    if (norm_two_back > 0)
      return norm_one_back * norm_one_back * norm_one_back / (norm_two_back * norm_two_back);
    if (remembered > 0)
      return norm_one_back * remembered;
    return std::numeric_limits<double>::infinity();
  }
} // namespace indentsim::nonlinear
