#include "materials/crystal/MatrixExponential.h"

#include <cmath>

namespace indentsim::materials::crystal
{
  namespace
  {
    // Y = 2^-s X with |Y| <= 1/4 (Frobenius), so that the Taylor series of exp(Y) converges in a
    // few terms; exp(X) = exp(Y)^(2^s).
    Matrix scaled_for_series(const Matrix &X, double &norm, unsigned int &n_squarings)
    {
      double norm_squared = 0.0;
      for (const auto &row : X)
        for (const double a : row)
          norm_squared += a * a;
      norm = std::sqrt(norm_squared);
      n_squarings = 0;
      while (norm > 0.25 && n_squarings < 60)
        {
          norm *= 0.5;
          ++n_squarings;
        }
      const double scale = std::ldexp(1.0, -static_cast<int>(n_squarings));
      Matrix       Y = X;
      for (auto &row : Y)
        for (auto &a : row)
          a *= scale;
      return Y;
    }

    constexpr unsigned int max_series_terms = 30;
    using SeriesTerms = std::array<Matrix, max_series_terms + 1>;

    // The Taylor terms T_k = Y^k / k! of exp(Y) (|Y| = norm <= 1/4) until the next term is below
    // 1e-17, their sum in `sum`; returns the index K of the last term.
    unsigned int exp_series_terms(const Matrix &Y, const double norm, SeriesTerms &terms,
                                  Matrix &sum)
    {
      terms[0] = identity_matrix();
      sum = identity_matrix();
      terms[1] = Y;
      unsigned int n_terms = 1;
      double       bound = norm; // norm^k / k!, bounds |T_k|
      for (unsigned int k = 1; k <= max_series_terms; ++k)
        {
          if (k > 1)
            {
              terms[k] = multiply(terms[k - 1], Y);
              for (auto &row : terms[k])
                for (auto &a : row)
                  a /= double(k);
              bound *= norm / k;
            }
          for (unsigned int i = 0; i < 3; ++i)
            for (unsigned int j = 0; j < 3; ++j)
              sum[i][j] += terms[k][i][j];
          n_terms = k;
          if (bound * norm / (k + 1) < 1e-17 && k >= 2)
            break;
          if (norm == 0.0)
            break;
        }
      return n_terms;
    }
  } // namespace

  Matrix exp_matrix(const Matrix &X)
  {
    double       norm = 0;
    unsigned int n_squarings = 0;
    const Matrix Y = scaled_for_series(X, norm, n_squarings);
    SeriesTerms  terms;
    Matrix       result;
    exp_series_terms(Y, norm, terms, result);
    for (unsigned int s = 0; s < n_squarings; ++s)
      result = multiply(result, result);
    return result;
  }

  void exp_matrix_and_derivative(const Matrix &X, Matrix &A, std::array<Matrix, 9> &dA_dX)
  {
    double             norm = 0;
    unsigned int       n_squarings = 0;
    const Matrix       Y = scaled_for_series(X, norm, n_squarings);
    const double       scale = std::ldexp(1.0, -static_cast<int>(n_squarings)); // dY/dX
    SeriesTerms        terms;                                                   // T_0 .. T_K
    const unsigned int n_terms = exp_series_terms(Y, norm, terms, A);

    // beta(j, m) = j! m! / (j + m + 1)!
    std::array<Matrix, max_series_terms> G; // G_j, j = 0 .. K-1
    for (unsigned int j = 0; j < n_terms; ++j)
      {
        G[j] = Matrix{};
        double beta = 1.0 / (j + 1); // m = 0
        for (unsigned int m = 0; j + m + 1 <= n_terms; ++m)
          {
            for (unsigned int b = 0; b < 3; ++b)
              for (unsigned int l = 0; l < 3; ++l)
                G[j][b][l] += beta * terms[m][b][l];
            beta *= double(m + 1) / double(j + m + 2);
          }
      }
    for (unsigned int a = 0; a < 3; ++a)
      for (unsigned int b = 0; b < 3; ++b)
        {
          Matrix &dA = dA_dX[3 * a + b];
          for (unsigned int i = 0; i < 3; ++i)
            for (unsigned int l = 0; l < 3; ++l)
              {
                double sum = 0.0;
                for (unsigned int j = 0; j < n_terms; ++j)
                  sum += terms[j][i][a] * G[j][b][l];
                dA[i][l] = sum * scale;
              }
        }
    for (unsigned int s = 0; s < n_squarings; ++s)
      {
        for (auto &dA : dA_dX)
          {
            const Matrix left = multiply(dA, A), right = multiply(A, dA);
            for (unsigned int i = 0; i < 3; ++i)
              for (unsigned int j = 0; j < 3; ++j)
                dA[i][j] = left[i][j] + right[i][j];
          }
        A = multiply(A, A);
      }
  }
} // namespace indentsim::materials::crystal
