// Unit tests of the principal-space J2 update (J2Plasticity.cc, J2PrincipalReturn.h) against
// the AD update kept as the oracle (j2_reference_update.h: the 7-unknown return in the full
// tensor through the Pade log/exp, tangent by forward AD): the same P, tau, state and dP/dF to
// round-off at random plastic states for every hardening law and both yield measures, and at
// repeated and nearly repeated principal stretches; and the hand-derived Jacobian and
// sensitivity of the principal return against central finite differences. Units: GPa.
#include "materials/IsotropicHardening.h"
#include "materials/J2Plasticity.h"
#include "materials/J2PrincipalReturn.h"

#include "j2_reference_update.h"
#include "material_test_utilities.h"

#include <deal.II/base/tensor.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace
{
  using namespace indentsim::materials;
  using namespace indentsim::testing;
  using dealii::Tensor;

  // Table 1 elasticity; each law starts at the paper's sigma_y0 = 0.305 GPa.
  constexpr double young_modulus = 69.0;
  constexpr double poisson_ratio = 0.26;
  constexpr double yield_stress = 0.305;

  struct NamedLaw
  {
    std::string        name;
    IsotropicHardening law;
  };

  std::vector<NamedLaw> laws()
  {
    return {{"linear", IsotropicHardening::linear(yield_stress, 0.5)},
            {"perfectly plastic", IsotropicHardening::linear(yield_stress, 0.0)},
            {"power n = 0.2", IsotropicHardening::power(yield_stress, young_modulus, 0.2)},
            {"voce", IsotropicHardening::voce(yield_stress, 0.1, 30.0, 0.2)},
            {"table", IsotropicHardening::table({0.0, 0.002, 0.01, 0.03, 0.08},
                                                {0.305, 0.32, 0.34, 0.36, 0.365})}};
  }

  const char *name(const YieldStressMeasure measure)
  {
    return measure == YieldStressMeasure::cauchy ? "cauchy" : "kirchhoff";
  }

  std::vector<double> virgin_state(const J2Plasticity &model)
  {
    std::vector<double> state(model.n_state_variables());
    model.initial_state(state);
    return state;
  }

  // The largest relative differences between the fast update and the oracle at one point.
  struct Differences
  {
    double P = 0, tau = 0, state = 0, tangent = 0;
    void   take_max(const Differences &other)
    {
      P = std::max(P, other.P);
      tau = std::max(tau, other.tau);
      state = std::max(state, other.state);
      tangent = std::max(tangent, other.tangent);
    }
  };

  // Runs both updates from state_old; returns false (and compares nothing) if the oracle fails
  // or the step is elastic. P and tau relative to their norms; the state as the crystal test
  // does: C_p^-1 and gamma_p each relative to their change over the increment.
  bool compare_with_reference(const J2Plasticity &model, const Tensor<2, 3> &F,
                              const std::vector<double> &state_old, const bool tangent,
                              Differences &differences)
  {
    MaterialPointResponse fast, slow;
    std::vector<double>   state_fast(state_old.size()), state_slow(state_old.size());
    if (reference::update(model, F, state_old, slow, state_slow, tangent) != UpdateStatus::success)
      return false;
    EXPECT_EQ(model.update(F, state_old, fast, state_fast, tangent), UpdateStatus::success);
    const unsigned int gamma_p = J2Plasticity::gamma_p_index;
    if (!(state_slow[gamma_p] > state_old[gamma_p]))
      return false;
    differences.P = (fast.P - slow.P).norm() / slow.P.norm();
    differences.tau = (fast.tau - slow.tau).norm() / slow.tau.norm();
    double metric_difference = 0, metric_change = 0;
    for (unsigned int k = 0; k < gamma_p; ++k)
      {
        metric_difference += std::pow(state_fast[k] - state_slow[k], 2);
        metric_change += std::pow(state_slow[k] - state_old[k], 2);
      }
    differences.state = std::max(std::sqrt(metric_difference / metric_change),
                                 std::abs(state_fast[gamma_p] - state_slow[gamma_p]) /
                                     (state_slow[gamma_p] - state_old[gamma_p]));
    differences.tangent = tangent ? (fast.dP_dF - slow.dP_dF).norm() / slow.dP_dF.norm() : 0.0;
    return true;
  }

  void expect_round_off(const Differences &worst, const std::string &label)
  {
    report(label + ": largest relative difference in P", worst.P);
    report(label + ": largest relative difference in tau", worst.tau);
    report(label + ": largest relative difference in the state", worst.state);
    report(label + ": largest relative difference in the tangent", worst.tangent);
    EXPECT_LT(worst.P, 1e-10) << label;
    EXPECT_LT(worst.tau, 1e-10) << label;
    EXPECT_LT(worst.state, 1e-10) << label;
    EXPECT_LT(worst.tangent, 1e-8) << label;
  }

  // The principal-space update solves the same equations as the 7-unknown AD update
  // (j2_reference_update.h): P, tau, state and tangent agree to round-off at random plastic
  // states (first yield from the virgin state, and increments after a history of up to three
  // random plastic steps, from 0.5 % to 50 % strain) for every hardening law, the table across
  // its kinks, and both yield measures.
  TEST(J2FastUpdate, MatchesReferenceAdUpdate)
  {
    for (const auto &[law_name, law] : laws())
      for (const auto measure : {YieldStressMeasure::cauchy, YieldStressMeasure::kirchhoff})
        {
          const J2Plasticity model(young_modulus, poisson_ratio, law, measure);
          std::mt19937       generator(31);
          Differences        worst;
          unsigned int       n_plastic = 0;
          for (unsigned int sample = 0; sample < 40; ++sample)
            {
              std::vector<double> state = virgin_state(model);
              const Tensor<2, 3>  F_history = random_deformation(generator, 0.03);
              const unsigned int  n_history = sample % 4;
              for (unsigned int step = 1; step <= n_history; ++step)
                {
                  MaterialPointResponse response;
                  std::vector<double>   state_new(state.size());
                  ASSERT_EQ(model.update(identity() + (F_history - identity()) * (step / 4.0),
                                         state, response, state_new, false),
                            UpdateStatus::success);
                  state = state_new;
                }
              const double amplitude =
                  std::array<double, 5>{{0.005, 0.02, 0.08, 0.2, 0.5}}[sample % 5];
              const Tensor<2, 3> F = (n_history > 0 ? F_history : identity()) +
                                     (random_deformation(generator, amplitude) - identity());
              for (const bool tangent : {false, true})
                {
                  Differences differences;
                  if (compare_with_reference(model, F, state, tangent, differences))
                    {
                      worst.take_max(differences);
                      n_plastic += tangent;
                    }
                }
            }
          expect_round_off(worst, "J2 " + law_name + " (" + name(measure) + ")");
          EXPECT_GE(n_plastic, 30u) << law_name << ", " << name(measure);
        }
  }

  // Repeated principal stretches are the normal case of J2 indentation (virgin material, the
  // axis of an axisymmetric model, uniaxial states), where the eigenvector-rotation terms of the
  // tangent are limits of divided differences: the fast update must agree with the oracle to
  // round-off with two eigenvalues of b_e^tr exactly equal and equal to 1e-13, 1e-9 and 1e-5
  // relative, in tension and compression, in the coordinate axes (the axis of symmetry) and in
  // a rotated frame, from the virgin state and from a uniaxially pre-strained one.
  TEST(J2FastUpdate, MatchesReferenceAtRepeatedPrincipalStretches)
  {
    for (const auto &[law_name, law] : laws())
      for (const auto measure : {YieldStressMeasure::cauchy, YieldStressMeasure::kirchhoff})
        {
          const J2Plasticity model(young_modulus, poisson_ratio, law, measure);
          std::mt19937       generator(37);
          Differences        worst;
          unsigned int       n_compared = 0;
          for (const double gap : {0.0, 1e-13, 1e-9, 1e-5})
            for (const double axial : {1.03, 0.96, 1.2})
              for (const bool rotated : {false, true})
                {
                  // F = R diag(axial, lateral, lateral (1 + gap)) R^T, nearly isochoric.
                  const Tensor<2, 3> R = rotated ? random_rotation(generator) : identity();
                  const double       lateral = 1.0 / std::sqrt(axial) * (1.0 + 0.001);
                  const Tensor<2, 3> F =
                      R * diagonal(axial, lateral, lateral * (1.0 + gap)) * dealii::transpose(R);
                  std::vector<double> virgin = virgin_state(model);
                  for (const bool tangent : {false, true})
                    {
                      Differences differences;
                      ASSERT_TRUE(compare_with_reference(model, F, virgin, tangent, differences))
                          << "not plastic: gap " << gap << ", axial " << axial;
                      worst.take_max(differences);
                      n_compared += tangent;
                    }
                  // A further uniaxial step from the uniaxially pre-strained state (C_p^-1 with
                  // the same repeated pair), along the same axes.
                  MaterialPointResponse response;
                  std::vector<double>   prestrained(virgin.size());
                  const Tensor<2, 3>    F_0 = R *
                                           diagonal(1.0 + 0.6 * (axial - 1.0), lateral, lateral) *
                                           dealii::transpose(R);
                  ASSERT_EQ(model.update(F_0, virgin, response, prestrained, false),
                            UpdateStatus::success);
                  for (const bool tangent : {false, true})
                    {
                      Differences differences;
                      ASSERT_TRUE(
                          compare_with_reference(model, F, prestrained, tangent, differences))
                          << "not plastic after the pre-strain: gap " << gap;
                      worst.take_max(differences);
                      n_compared += tangent;
                    }
                }
          expect_round_off(worst,
                           "J2 " + law_name + " (" + name(measure) + "), repeated stretches");
          EXPECT_EQ(n_compared, 48u);
        }
  }

  // The hand-derived Jacobian dR/dx of the principal return (J2PrincipalReturn.h) must match
  // central differences of its residual, at random points with distinct and with repeated
  // principal strains, for a smooth and a piecewise-linear law and both measures.
  TEST(J2PrincipalReturn, JacobianMatchesFiniteDifferences)
  {
    std::mt19937                           generator(41);
    std::uniform_real_distribution<double> uniform(-1.0, 1.0);
    double                                 worst = 0;
    for (const auto &named : {laws()[0], laws()[3]})
      for (const bool cauchy : {true, false})
        for (unsigned int sample = 0; sample < 10; ++sample)
          {
            std::array<double, 3> t;
            for (double &t_a : t)
              t_a = 0.05 * uniform(generator);
            if (sample % 2 == 0)
              t[2] = t[1];
            J2PrincipalReturn principal(named.law, 27.4, 0.01, t, 1.0 + 0.02 * uniform(generator),
                                        cauchy);
            J2PrincipalReturn::Vector x;
            for (unsigned int a = 0; a < 3; ++a)
              x[a] = t[a] + 0.005 * uniform(generator);
            x[3] = 0.01 * (1.0 + uniform(generator));
            J2PrincipalReturn::Vector R;
            J2PrincipalReturn::Matrix K;
            principal.evaluate(x, R, &K);
            const double step = 1e-7;
            double       difference = 0, size = 0;
            for (unsigned int c = 0; c < 4; ++c)
              {
                J2PrincipalReturn::Vector x_plus = x, x_minus = x, R_plus, R_minus;
                x_plus[c] += step;
                x_minus[c] -= step;
                principal.evaluate(x_plus, R_plus, nullptr);
                principal.evaluate(x_minus, R_minus, nullptr);
                for (unsigned int a = 0; a < 4; ++a)
                  {
                    difference += std::pow((R_plus[a] - R_minus[a]) / (2 * step) - K[a][c], 2);
                    size += K[a][c] * K[a][c];
                  }
              }
            worst = std::max(worst, std::sqrt(difference / size));
          }
    report("principal return: largest relative Jacobian error vs FD", worst);
    EXPECT_LT(worst, 1e-7);
  }

  // The sensitivity de_a/d(t_c, J) of the principal return (the principal part of the
  // consistent tangent) must match central differences of the solved return with respect to
  // its parameters, for a smooth and a piecewise-linear law and both measures.
  TEST(J2PrincipalReturn, SensitivityMatchesFiniteDifferences)
  {
    std::mt19937                           generator(43);
    std::uniform_real_distribution<double> uniform(-1.0, 1.0);
    double                                 worst = 0;
    for (const auto &named : {laws()[0], laws()[3]})
      for (const bool cauchy : {true, false})
        for (unsigned int sample = 0; sample < 10; ++sample)
          {
            std::array<double, 3> t = {{0.03, -0.01, -0.015}};
            for (double &t_a : t)
              t_a += 0.02 * uniform(generator);
            const double J = 1.0 + 0.02 * uniform(generator);
            const auto   solved = [&](const std::array<double, 3> &t_p, const double J_p) {
              J2PrincipalReturn principal(named.law, 27.4, 0.01, t_p, J_p, cauchy);
              EXPECT_EQ(principal.solve(), J2PrincipalReturn::Outcome::plastic);
              return principal;
            };
            const J2PrincipalReturn                  principal = solved(t, J);
            std::array<J2PrincipalReturn::Vector, 3> de_dp;
            ASSERT_TRUE(principal.sensitivity(de_dp));
            const double step = 1e-6;
            double       difference = 0, size = 0;
            for (unsigned int c = 0; c < 4; ++c)
              {
                std::array<double, 3> t_plus = t, t_minus = t;
                double                J_plus = J, J_minus = J;
                (c < 3 ? t_plus[c] : J_plus) += step;
                (c < 3 ? t_minus[c] : J_minus) -= step;
                const J2PrincipalReturn plus = solved(t_plus, J_plus);
                const J2PrincipalReturn minus = solved(t_minus, J_minus);
                for (unsigned int a = 0; a < 3; ++a)
                  {
                    const double fd =
                        (plus.elastic_log_strain(a) - minus.elastic_log_strain(a)) / (2 * step);
                    difference += std::pow(fd - de_dp[a][c], 2);
                    size += de_dp[a][c] * de_dp[a][c];
                  }
              }
            worst = std::max(worst, std::sqrt(difference / size));
          }
    report("principal return: largest relative sensitivity error vs FD", worst);
    EXPECT_LT(worst, 1e-7);
  }
} // namespace
