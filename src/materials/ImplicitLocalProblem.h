// A small implicit local problem R(x; p) = 0 at one material point, solved by Newton's method
// with an exact Jacobian from forward automatic differentiation, and its sensitivity dx/dp by
// the implicit function theorem:
//   dR/dp = dR/dx dx/dp + dR/dp|_x = 0   =>   dx/dp = -(dR/dx)^-1 dR/dp|_x.
// A model writes its residual once, as a generic callable over the scalar type, and gets the
// local Newton, its Jacobian and the sensitivity needed for the consistent tangent from here
// (the DAMASK / MFEM-hooke idea: one integrator, the physics only supplies the residual). The
// tests' AD oracle of the J2 update (tests/unit/j2_reference_update.h) uses it. Where AD of the
// whole residual is too slow (the production J2 return in principal space, J2PrincipalReturn.h,
// and the crystal integrator with 19 unknowns), solve_with_jacobian runs the same Newton with a
// model-supplied Jacobian and, optionally, a model-supplied linear solve that exploits its
// structure.
//
// The residual is called as residual(x, p, R) with x, p and R std::arrays of one scalar type
// Number (double or Sacado::Fad::SFad<double, n>), and must be a template in Number, e.g. a
// generic lambda. SFad keeps all derivatives on the stack: no heap allocation anywhere.
//
// Failures (non-finite residual, singular Jacobian, no convergence within the iteration budget)
// are returned, never thrown: the caller reports UpdateStatus::local_newton_failed.
#pragma once

#include <Sacado.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace indentsim::materials
{
  struct LocalNewtonSettings
  {
    unsigned int max_iterations = 25;
    double       tolerance = 1e-14; // on the max-norm of the residual
    // When round-off stops any descent (the line search finds no decrease), a residual below
    // this looser bound is still accepted as converged.
    double       stagnation_tolerance = 1e-11;
    unsigned int max_line_search_steps = 10; // step halvings when the residual norm grows
  };

  struct LocalNewtonResult
  {
    bool         converged = false;
    unsigned int n_iterations = 0;
    double       residual_norm = 0.0; // max-norm at exit
    // solve_with_jacobian only: the Jacobian it returns was evaluated at the returned x.
    bool jacobian_at_solution = false;
  };

  namespace internal
  {
    // Solves A X = B in place (B becomes X) for n_rhs right-hand sides by Gaussian elimination
    // with partial pivoting. Returns false if A is singular to working precision.
    template <int n, int n_rhs>
    bool solve_dense(std::array<std::array<double, n>, n>     &A,
                     std::array<std::array<double, n_rhs>, n> &B)
    {
      double scale = 0.0;
      for (const auto &row : A)
        for (const double a : row)
          scale = std::max(scale, std::abs(a));
      if (!(scale > 0.0) || !std::isfinite(scale))
        return false;

      for (int k = 0; k < n; ++k)
        {
          int pivot = k;
          for (int i = k + 1; i < n; ++i)
            if (std::abs(A[i][k]) > std::abs(A[pivot][k]))
              pivot = i;
          if (std::abs(A[pivot][k]) <= 1e-14 * scale)
            return false;
          std::swap(A[k], A[pivot]);
          std::swap(B[k], B[pivot]);
          for (int i = k + 1; i < n; ++i)
            {
              const double factor = A[i][k] / A[k][k];
              for (int j = k; j < n; ++j)
                A[i][j] -= factor * A[k][j];
              for (int j = 0; j < n_rhs; ++j)
                B[i][j] -= factor * B[k][j];
            }
        }
      for (int k = n - 1; k >= 0; --k)
        for (int j = 0; j < n_rhs; ++j)
          {
            double sum = B[k][j];
            for (int m = k + 1; m < n; ++m)
              sum -= A[k][m] * B[m][j];
            B[k][j] = sum / A[k][k];
          }
      return true;
    }

    template <int n>
    double max_norm(const std::array<double, n> &v)
    {
      double norm = 0.0;
      for (const double a : v)
        {
          if (!std::isfinite(a))
            return std::numeric_limits<double>::infinity();
          norm = std::max(norm, std::abs(a));
        }
      return norm;
    }
  } // namespace internal

  template <int n_unknowns, int n_parameters>
  class ImplicitLocalProblem
  {
  public:
    using Unknowns = std::array<double, n_unknowns>;
    using Parameters = std::array<double, n_parameters>;
    // dx/dp, row i = unknown, column a = parameter
    using Sensitivity = std::array<std::array<double, n_parameters>, n_unknowns>;

    // Newton's method for R(x; p) = 0 from the initial guess in `x`, with backtracking on the
    // Euclidean residual norm (the full step is taken whenever it reduces the residual, so
    // convergence stays quadratic near the solution).
    template <typename ResidualFunction>
    static LocalNewtonResult solve(const ResidualFunction &residual, const Parameters &p,
                                   Unknowns                  &x,
                                   const LocalNewtonSettings &settings = LocalNewtonSettings())
    {
      // The residual in plain doubles, and with dR/dx by forward AD when asked for.
      using ADNumber = Sacado::Fad::SFad<double, n_unknowns>;
      std::array<ADNumber, n_parameters> p_ad;
      for (int a = 0; a < n_parameters; ++a)
        p_ad[a] = ADNumber(p[a]);
      const auto evaluate = [&](const Unknowns &x_trial, Unknowns &R,
                                std::array<std::array<double, n_unknowns>, n_unknowns> *dR_dx) {
        if (!dR_dx)
          {
            residual(x_trial, p, R);
            return;
          }
        std::array<ADNumber, n_unknowns> x_ad, R_ad;
        for (int i = 0; i < n_unknowns; ++i)
          x_ad[i] = ADNumber(n_unknowns, i, x_trial[i]);
        residual(x_ad, p_ad, R_ad);
        for (int i = 0; i < n_unknowns; ++i)
          {
            R[i] = R_ad[i].val();
            for (int j = 0; j < n_unknowns; ++j)
              (*dR_dx)[i][j] = R_ad[i].dx(j);
          }
      };
      std::array<std::array<double, n_unknowns>, n_unknowns> jacobian;
      return solve_with_jacobian(evaluate, x, jacobian, settings);
    }

    // Newton's method as solve(), for a model that supplies its own Jacobian (hand-derived, or
    // AD of a part only): evaluate(x, R, dR_dx) fills R, and dR/dx too unless dR_dx is null.
    // A model that knows the structure of its Jacobian may provide
    // evaluate.solve_linearized<n_rhs>(dR_dx, B) (B := dR_dx^-1 B, false if singular), used
    // instead of the dense LU. Line-search trials ask for R alone, and dR/dx is evaluated once
    // a trial is accepted and not yet converged, so no Jacobian is spent on a rejected step or
    // on the converged point. On return, `jacobian` holds dR/dx at the last point where it was
    // evaluated, which is x only when result.jacobian_at_solution; the last call of evaluate is
    // always at the returned x.
    template <typename Evaluate>
    static LocalNewtonResult
    solve_with_jacobian(Evaluate &evaluate, Unknowns &x,
                        std::array<std::array<double, n_unknowns>, n_unknowns> &jacobian,
                        const LocalNewtonSettings &settings = LocalNewtonSettings())
    {
      const auto euclidean_norm = [](const Unknowns &v) {
        double sum = 0.0;
        for (const double a : v)
          sum += a * a;
        return std::isfinite(sum) ? std::sqrt(sum) : std::numeric_limits<double>::infinity();
      };

      LocalNewtonResult result;
      Unknowns          R;
      evaluate(x, R, &jacobian);
      result.jacobian_at_solution = true;
      result.residual_norm = internal::max_norm<n_unknowns>(R);
      for (; result.n_iterations < settings.max_iterations; ++result.n_iterations)
        {
          if (!std::isfinite(result.residual_norm))
            return result;
          if (result.residual_norm <= settings.tolerance)
            {
              result.converged = true;
              return result;
            }

          std::array<std::array<double, 1>, n_unknowns> step;
          for (int i = 0; i < n_unknowns; ++i)
            step[i][0] = -R[i];
          if constexpr (requires { evaluate.template solve_linearized<1>(jacobian, step); })
            {
              if (!evaluate.template solve_linearized<1>(jacobian, step))
                return result;
            }
          else
            {
              auto factorised = jacobian;
              if (!internal::solve_dense<n_unknowns, 1>(factorised, step))
                return result;
            }

          const double   old_norm = euclidean_norm(R);
          const Unknowns x_old = x;
          double         alpha = 1.0;
          bool           accepted = false;
          result.jacobian_at_solution = false;
          for (unsigned int ls = 0; ls <= settings.max_line_search_steps; ++ls, alpha *= 0.5)
            {
              for (int i = 0; i < n_unknowns; ++i)
                x[i] = x_old[i] + alpha * step[i][0];
              evaluate(x, R, nullptr);
              if (euclidean_norm(R) <= (1.0 - 1e-4 * alpha) * old_norm)
                {
                  accepted = true;
                  break;
                }
            }
          result.residual_norm = internal::max_norm<n_unknowns>(R);
          if (!accepted)
            {
              result.n_iterations += 1;
              result.converged = result.residual_norm <= settings.stagnation_tolerance;
              return result;
            }
          if (std::isfinite(result.residual_norm) && result.residual_norm > settings.tolerance)
            {
              evaluate(x, R, &jacobian);
              result.jacobian_at_solution = true;
            }
        }
      result.converged = result.residual_norm <= settings.tolerance;
      return result;
    }

    // dx/dp at a solution x of R(x; p) = 0 (one residual evaluation with derivatives with
    // respect to x and p together, then one LU solve with n_parameters right-hand sides).
    // Returns false if dR/dx is singular.
    template <typename ResidualFunction>
    static bool sensitivity(const ResidualFunction &residual, const Parameters &p,
                            const Unknowns &x, Sensitivity &dx_dp)
    {
      constexpr int n_total = n_unknowns + n_parameters;
      using ADNumber = Sacado::Fad::SFad<double, n_total>;
      std::array<ADNumber, n_unknowns>   x_ad, R_ad;
      std::array<ADNumber, n_parameters> p_ad;
      for (int i = 0; i < n_unknowns; ++i)
        x_ad[i] = ADNumber(n_total, i, x[i]);
      for (int a = 0; a < n_parameters; ++a)
        p_ad[a] = ADNumber(n_total, n_unknowns + a, p[a]);
      residual(x_ad, p_ad, R_ad);

      std::array<std::array<double, n_unknowns>, n_unknowns> dR_dx;
      for (int i = 0; i < n_unknowns; ++i)
        {
          for (int j = 0; j < n_unknowns; ++j)
            dR_dx[i][j] = R_ad[i].dx(j);
          for (int a = 0; a < n_parameters; ++a)
            dx_dp[i][a] = -R_ad[i].dx(n_unknowns + a);
        }
      return internal::solve_dense<n_unknowns, n_parameters>(dR_dx, dx_dp);
    }

    // The solution linearised about p, x(p) ~ x + dx/dp (p_ad - p), evaluated with AD
    // parameters p_ad: the returned numbers carry dx/d(whatever p_ad is differentiated by),
    // i.e. the chain rule through the implicit function, without differentiating the Newton
    // iterations.
    template <typename ADNumber>
    static std::array<ADNumber, n_unknowns>
    linearized_solution(const Unknowns &x, const Sensitivity &dx_dp,
                        const std::array<ADNumber, n_parameters> &p_ad)
    {
      std::array<ADNumber, n_unknowns> x_ad;
      for (int i = 0; i < n_unknowns; ++i)
        {
          ADNumber value = x[i];
          for (int a = 0; a < n_parameters; ++a)
            value += dx_dp[i][a] * (p_ad[a] - p_ad[a].val());
          x_ad[i] = value;
        }
      return x_ad;
    }
  };
} // namespace indentsim::materials
