// The exponential of a general 3x3 matrix and its derivative, for the plastic update
// F_p(t + dt) = exp(dt L_p) F_p(t) (eq. 12).
#pragma once

#include "materials/crystal/SmallMatrix.h"

#include <array>

namespace indentsim::materials::crystal
{
  // exp(X) by scaling and squaring of its Taylor series: X is scaled by 2^-s until its Frobenius
  // norm is <= 1/4, the series is summed until the next term is below 1e-17 (one term more than
  // the value needs, so that its derivative is as accurate as the value), then squared s times.
  Matrix exp_matrix(const Matrix &X);

  // exp(X) exactly as exp_matrix computes it (same scaling, terms and squarings, so the same
  // numbers) and its derivative dA/dX_ab (row-major ab). With the scaled Y = 2^-s X and the terms
  // T_j = Y^j / j! of the truncated series A_Y = sum_{k<=K} T_k,
  //   dA_Y/dY_ab = sum_{k=1..K} 1/k! sum_{j+m=k-1} Y^j e_a e_b^T Y^m
  //             = sum_j T_j e_a e_b^T G_j,   G_j = sum_{m<=K-1-j} j! m!/(j+m+1)! T_m,
  // then each squaring A <- A A carries dA <- dA A + A dA: the derivative of the computed
  // exp_matrix, not of the exact exponential, without carrying 9 derivatives through every
  // product as forward AD would.
  void exp_matrix_and_derivative(const Matrix &X, Matrix &A, std::array<Matrix, 9> &dA_dX);
} // namespace indentsim::materials::crystal
