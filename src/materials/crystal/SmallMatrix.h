// Small dense 3x3 matrices in plain doubles for the crystal-plasticity integrator: products,
// the unrolled symmetric storage of strains, contractions and integer powers. The integrator
// works on std::array rather than dealii::Tensor so that every loop has fixed bounds the
// compiler unrolls, and forms only the products it needs (A^T B, A B^T) without transposes.
#pragma once

#include <deal.II/base/tensor.h>

#include <array>
#include <cmath>

namespace indentsim::materials::crystal
{
  using Matrix = std::array<std::array<double, 3>, 3>;
  // A symmetric matrix unrolled as 00, 11, 22, 01, 02, 12 (deal.II's order).
  using Symmetric = std::array<double, 6>;

  inline constexpr unsigned int sym_i[6] = {0, 1, 2, 0, 0, 1};
  inline constexpr unsigned int sym_j[6] = {0, 1, 2, 1, 2, 2};

  inline Matrix identity_matrix()
  {
    Matrix I;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        I[i][j] = (i == j ? 1.0 : 0.0);
    return I;
  }

  // A B
  inline Matrix multiply(const Matrix &A, const Matrix &B)
  {
    Matrix C;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        {
          double sum = A[i][0] * B[0][j];
          sum += A[i][1] * B[1][j];
          sum += A[i][2] * B[2][j];
          C[i][j] = sum;
        }
    return C;
  }

  // A^T B
  inline Matrix multiply_transposed_first(const Matrix &A, const Matrix &B)
  {
    Matrix C;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        {
          double sum = A[0][i] * B[0][j];
          sum += A[1][i] * B[1][j];
          sum += A[2][i] * B[2][j];
          C[i][j] = sum;
        }
    return C;
  }

  // A B^T
  inline Matrix multiply_transposed_second(const Matrix &A, const Matrix &B)
  {
    Matrix C;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        {
          double sum = A[i][0] * B[j][0];
          sum += A[i][1] * B[j][1];
          sum += A[i][2] * B[j][2];
          C[i][j] = sum;
        }
    return C;
  }

  // A : B
  inline double contract(const Matrix &A, const Matrix &B)
  {
    double sum = 0.0;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        sum += A[i][j] * B[i][j];
    return sum;
  }

  inline Matrix to_matrix(const dealii::Tensor<2, 3> &T)
  {
    Matrix M;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        M[i][j] = T[i][j];
    return M;
  }

  // The full matrix of an unrolled symmetric one.
  inline Matrix symmetric_matrix(const double *unrolled)
  {
    Matrix E;
    for (unsigned int k = 0; k < 6; ++k)
      {
        E[sym_i[k]][sym_j[k]] = unrolled[k];
        E[sym_j[k]][sym_i[k]] = unrolled[k];
      }
    return E;
  }

  // The unrolled Green-Lagrange strain 1/2 (C - I) of a right Cauchy-Green tensor C.
  inline Symmetric green_lagrange_strain(const Matrix &C)
  {
    Symmetric E;
    for (unsigned int k = 0; k < 6; ++k)
      E[k] = 0.5 * (C[sym_i[k]][sym_j[k]] - (k < 3 ? 1.0 : 0.0));
    return E;
  }

  // C = 2 E + I of an unrolled strain E.
  inline Matrix right_cauchy_green(const double *E)
  {
    Matrix C = identity_matrix();
    for (unsigned int k = 0; k < 6; ++k)
      {
        C[sym_i[k]][sym_j[k]] += 2.0 * E[k];
        if (k >= 3)
          C[sym_j[k]][sym_i[k]] += 2.0 * E[k];
      }
    return C;
  }

  // x^e for a non-negative integer e by binary powering.
  inline double integer_power(double x, unsigned int e)
  {
    double result = 1.0;
    while (true)
      {
        if (e & 1u)
          result *= x;
        e >>= 1;
        if (e == 0)
          return result;
        x *= x;
      }
  }

  // x^e, by binary powering when e is a small non-negative integer (exact and cheaper than pow).
  inline double real_power(const double x, const double e)
  {
    if (e >= 0.0 && e <= 256.0 && e == std::floor(e))
      return integer_power(x, static_cast<unsigned int>(e));
    return std::pow(x, e);
  }
} // namespace indentsim::materials::crystal
