// Unit tests of the J2 hardening laws (materials/IsotropicHardening.h) at a single material
// point: the flow stress of each law against its closed form, the consistent tangent of the J2
// return with each law against central finite differences (on every segment of a table and
// beyond it), and homogeneous uniaxial tension against an independent solve written here (the
// closed-form uniaxial state of python/reference_j2_uniaxial.py with a bisection on the plastic
// strain, each law's sigma_y written out again). Units: GPa, dimensionless strains.
#include "materials/IsotropicHardening.h"
#include "materials/J2Plasticity.h"

#include "material_test_utilities.h"

#include <deal.II/base/tensor.h>

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace
{
  using namespace indentsim::materials;
  using namespace indentsim::testing;
  using dealii::Tensor;

  // Aluminium 6061 of the brief's table example: E 69 GPa, nu 0.33, sigma_y0 0.276 GPa.
  constexpr double young_modulus = 69.0;
  constexpr double poisson_ratio = 0.33;
  constexpr double yield_stress = 0.276;

  // The laws under test and their flow stresses written out independently of the class.
  struct LawCase
  {
    std::string                   name;
    IsotropicHardening            law;
    std::function<double(double)> sigma_y; // the closed form, for eps_p >= 0
  };

  const std::vector<double> table_strain = {0.0, 0.002, 0.01, 0.03, 0.08};
  const std::vector<double> table_stress = {0.276, 0.29, 0.31, 0.33, 0.335};

  double table_sigma_y(const double eps_p)
  {
    std::size_t i = 0;
    while (i + 2 < table_strain.size() && eps_p >= table_strain[i + 1])
      ++i;
    const double slope =
        (table_stress[i + 1] - table_stress[i]) / (table_strain[i + 1] - table_strain[i]);
    return table_stress[i] + slope * (eps_p - table_strain[i]);
  }

  std::vector<LawCase> law_cases()
  {
    return {
        {"linear", IsotropicHardening::linear(yield_stress, 0.5),
         [](double e) { return yield_stress + 0.5 * e; }},
        {"power n = 0.3", IsotropicHardening::power(yield_stress, young_modulus, 0.3),
         [](double e) {
           return yield_stress * std::pow(1 + young_modulus * e / yield_stress, 0.3);
         }},
        {"power n = 0.1", IsotropicHardening::power(yield_stress, young_modulus, 0.1),
         [](double e) {
           return yield_stress * std::pow(1 + young_modulus * e / yield_stress, 0.1);
         }},
        {"power n = 0", IsotropicHardening::power(yield_stress, young_modulus, 0.0),
         [](double) { return yield_stress; }},
        {"voce", IsotropicHardening::voce(yield_stress, 0.1, 30.0, 0.2),
         [](double e) { return yield_stress + 0.1 * (1 - std::exp(-30 * e)) + 0.2 * e; }},
        {"table", IsotropicHardening::table(table_strain, table_stress), &table_sigma_y},
    };
  }

  std::vector<double> virgin_state(const MaterialModel &model)
  {
    std::vector<double> state(model.n_state_variables());
    model.initial_state(state);
    return state;
  }

  // F = diag(e^s, e^-s/2, e^-s/2) plus a small shear (s > 0: tension along x).
  Tensor<2, 3> isochoric_stretch(const double s, const double shear = 0.0)
  {
    Tensor<2, 3> F = diagonal(std::exp(s), std::exp(-0.5 * s), std::exp(-0.5 * s));
    F[0][1] = shear;
    return F;
  }

  // The state after one step from the virgin state to isochoric_stretch(s), s found by
  // bisection so that gamma_p = target.
  std::vector<double> state_at_plastic_strain(const J2Plasticity &model, const double target)
  {
    const auto gamma_p_at = [&](const double s, std::vector<double> &state_new) {
      MaterialPointResponse response;
      EXPECT_EQ(model.update(isochoric_stretch(s), virgin_state(model), response, state_new, false),
                UpdateStatus::success);
      return model.equivalent_plastic_strain(state_new);
    };
    std::vector<double> state(model.n_state_variables());
    double              low = 0.0, high = target + 0.1;
    for (int i = 0; i < 100; ++i)
      {
        const double middle = 0.5 * (low + high);
        (gamma_p_at(middle, state) < target ? low : high) = middle;
      }
    gamma_p_at(0.5 * (low + high), state);
    EXPECT_NEAR(model.equivalent_plastic_strain(state), target, 1e-9);
    return state;
  }

  // ---------------------------------------------------------------------------------------
  // The flow stress functions

  // Each law's sigma_y must equal its closed form at eps_p >= 0, and its slope the central
  // difference of sigma_y (away from the table's points); below 0 every law continues as its
  // tangent line at 0.
  TEST(J2Hardening, FlowStressMatchesClosedForms)
  {
    for (const auto &[name, law, sigma_y] : law_cases())
      {
        SCOPED_TRACE(name);
        EXPECT_DOUBLE_EQ(law.initial_yield_stress(), yield_stress);
        for (const double e : {0.0, 1e-4, 0.001, 0.005, 0.02, 0.05, 0.1, 0.3, 1.0})
          EXPECT_NEAR(law.flow_stress(e), sigma_y(e), 1e-14) << "eps_p = " << e;
        for (const double e : {1e-3, 0.004, 0.02, 0.05, 0.1, 0.3})
          {
            const double step = 1e-7;
            const double difference = (sigma_y(e + step) - sigma_y(e - step)) / (2 * step);
            EXPECT_NEAR(law.slope(e), difference, 1e-6 * (1 + std::abs(difference)))
                << "eps_p = " << e;
          }
        const IsotropicHardening::FlowStress at_zero = law.evaluate(0.0);
        EXPECT_NEAR(law.flow_stress(-1e-3), at_zero.stress - 1e-3 * at_zero.slope, 1e-15);
        EXPECT_DOUBLE_EQ(law.slope(-1e-3), at_zero.slope);
      }
  }

  // Published forms at special points: power law sigma_y(0) = sigma_y0 with slope E n at 0
  // (Dao et al. 2001), Voce slope Q b + H at 0 and H at saturation, the table through its
  // points, its midpoints halfway between them and beyond the last point along the last
  // segment's slope.
  TEST(J2Hardening, SpecialValuesOfEachLaw)
  {
    const auto power = IsotropicHardening::power(0.2, 50.0, 0.3);
    EXPECT_DOUBLE_EQ(power.flow_stress(0.0), 0.2);
    EXPECT_NEAR(power.slope(0.0), 50.0 * 0.3, 1e-13);
    // At E eps_p = 7 sigma_y0: sigma_y0 8^n.
    EXPECT_NEAR(power.flow_stress(7 * 0.2 / 50.0), 0.2 * std::pow(8.0, 0.3), 1e-15);

    const auto voce = IsotropicHardening::voce(0.3, 0.15, 20.0, 0.1);
    EXPECT_NEAR(voce.slope(0.0), 0.15 * 20.0 + 0.1, 1e-13);
    EXPECT_NEAR(voce.slope(10.0), 0.1, 1e-13);
    EXPECT_NEAR(voce.flow_stress(10.0), 0.3 + 0.15 + 0.1 * 10.0, 1e-13);

    const auto table = IsotropicHardening::table({0, 0.05, 0.2}, {0.276, 0.31, 0.33});
    EXPECT_EQ(table.n_segments(), 2u);
    EXPECT_DOUBLE_EQ(table.flow_stress(0.05), 0.31);
    EXPECT_DOUBLE_EQ(table.flow_stress(0.2), 0.33);
    EXPECT_NEAR(table.flow_stress(0.025), 0.5 * (0.276 + 0.31), 1e-15);
    EXPECT_NEAR(table.flow_stress(0.125), 0.5 * (0.31 + 0.33), 1e-15);
    EXPECT_NEAR(table.slope(0.01), (0.31 - 0.276) / 0.05, 1e-12);
    EXPECT_NEAR(table.slope(0.05), (0.33 - 0.31) / 0.15, 1e-12); // right derivative at a point
    EXPECT_NEAR(table.flow_stress(0.5), 0.33 + (0.33 - 0.31) / 0.15 * 0.3, 1e-14);
    EXPECT_NEAR(table.slope(0.5), (0.33 - 0.31) / 0.15, 1e-12);
    EXPECT_EQ(table.segment(0.0), 0u);
    EXPECT_EQ(table.segment(0.05), 1u);
    EXPECT_EQ(table.segment(3.0), 1u);
  }

  // Invalid parameters must be refused with an exception naming the parameter.
  TEST(J2Hardening, InvalidParametersAreRejected)
  {
    const auto message = [](const std::function<void()> &build) {
      try
        {
          build();
        }
      catch (const std::invalid_argument &error)
        {
          return std::string(error.what());
        }
      return std::string("no exception");
    };
    const auto expect_message = [&](const std::function<void()> &build, const std::string &part) {
      const std::string text = message(build);
      EXPECT_NE(text.find(part), std::string::npos) << text;
    };
    expect_message([] { IsotropicHardening::power(0.2, 50, 1.0); }, "exponent = 1");
    expect_message([] { IsotropicHardening::power(0.2, 50, -0.1); }, "exponent = -0.1");
    expect_message([] { IsotropicHardening::linear(0.2, -1); }, "hardening_modulus = -1");
    expect_message([] { IsotropicHardening::linear(0.0, 1); }, "yield_stress = 0");
    expect_message([] { IsotropicHardening::voce(0.2, -0.1, 1); }, "saturation = -0.1");
    expect_message([] { IsotropicHardening::voce(0.2, 0.1, 0); }, "rate = 0");
    expect_message(
        [] {
          IsotropicHardening::table({0.01, 0.1}, {0.2, 0.3});
        },
        "plastic_strain[0] = 0.01");
    expect_message(
        [] {
          IsotropicHardening::table({0, 0.1, 0.1}, {0.2, 0.3, 0.4});
        },
        "plastic_strain[2] = 0.1");
    expect_message(
        [] {
          IsotropicHardening::table({0, 0.1, 0.2}, {0.2, 0.3, 0.25});
        },
        "stress[2] = 0.25");
    expect_message([] { IsotropicHardening::table({0, 0.1}, {0.2}); }, "one stress per");
    expect_message([] { IsotropicHardening::table({0}, {0.2}); }, "at least 2");
  }

  // ---------------------------------------------------------------------------------------
  // The J2 return with each law

  // The consistent tangent of a plastic step must match central differences of P to 1e-6
  // relative, for every law and both yield measures: random steps from the virgin state, and a
  // further step from states whose plastic strain lies inside each table segment and beyond
  // the table (away from the points, where the tangent jumps).
  TEST(J2Hardening, PlasticTangentMatchesFiniteDifferences)
  {
    for (const auto measure : {YieldStressMeasure::cauchy, YieldStressMeasure::kirchhoff})
      for (const auto &[name, law, sigma_y] : law_cases())
        {
          SCOPED_TRACE(name + (measure == YieldStressMeasure::cauchy ? ", cauchy" : ", kirchhoff"));
          const J2Plasticity model(young_modulus, poisson_ratio, law, measure);
          std::mt19937       generator(11);
          const auto         virgin = virgin_state(model);
          double             worst = 0.0;
          for (const double amplitude : {0.01, 0.05, 0.2})
            for (unsigned int sample = 0; sample < 3; ++sample)
              {
                const Tensor<2, 3>    F = random_deformation(generator, amplitude);
                MaterialPointResponse response;
                std::vector<double>   state_new(virgin.size());
                ASSERT_EQ(model.update(F, virgin, response, state_new), UpdateStatus::success);
                ASSERT_GT(model.equivalent_plastic_strain(state_new), 1e-5) << "not plastic";
                worst = std::max(worst, tangent_error(model, F, virgin));
              }

          // Inside each segment of the table (midpoints of its points) and beyond the last.
          for (const double target : {0.0008, 0.006, 0.02, 0.055, 0.15})
            {
              const auto state = state_at_plastic_strain(model, target);
              // A further stretch of 0.5e-3 with a small shear: plastic, gamma_p grows by about
              // 0.5e-3, staying on the segment.
              double s = 0.0;
              {
                MaterialPointResponse response;
                std::vector<double>   state_new(state.size());
                // The stretch of the state: the bisection's s is recovered from C_p^-1 and
                // gamma_p only approximately, so search the step from the elastic side.
                for (s = target; s < target + 0.05; s += 1e-4)
                  {
                    ASSERT_EQ(model.update(isochoric_stretch(s, 2e-4), state, response, state_new),
                              UpdateStatus::success);
                    if (model.equivalent_plastic_strain(state_new) > target + 5e-4)
                      break;
                  }
                const double gamma_p = model.equivalent_plastic_strain(state_new);
                ASSERT_GT(gamma_p, target + 5e-4);
                if (law.piecewise_linear() && law.n_segments() > 1)
                  {
                    // Well inside the segment of `target` (or beyond the table).
                    const unsigned int k = law.segment(target);
                    EXPECT_EQ(law.segment(gamma_p), k);
                    EXPECT_GT(
                        std::min(gamma_p - law.segment_start(k), law.segment_end(k) - gamma_p),
                        2e-4);
                  }
              }
              worst = std::max(worst, tangent_error(model, isochoric_stretch(s, 2e-4), state));
            }
          report("J2 " + name + " plastic tangent error", worst);
          EXPECT_LT(worst, 1e-6);
        }
  }

  // The independent uniaxial solution at log strain `log_strain`: the closed-form state of
  // python/reference_j2_uniaxial.py (plastic log strain alpha diag(1, -1/2, -1/2), elastic
  // stretches from the total and the lateral stretch, zero lateral stress from a quadratic) and
  // a bisection of the yield condition mu (b1 - b2) / J^m = sigma_y(alpha) in alpha.
  struct UniaxialState
  {
    double cauchy_stress, lateral_stretch, alpha;
  };

  UniaxialState uniaxial_reference(const double                         log_strain,
                                   const std::function<double(double)> &sigma_y, const bool cauchy)
  {
    const double mu = young_modulus / (2 * (1 + poisson_ratio));
    const double lame_lambda =
        young_modulus * poisson_ratio / ((1 + poisson_ratio) * (1 - 2 * poisson_ratio));
    const double lambda = std::exp(log_strain);
    struct Point
    {
      double lateral_stretch, J, tau_1, tau_2;
    };
    const auto point = [&](const double alpha) {
      const double a = 0.5 * lame_lambda * lambda * lambda, b = mu * std::exp(alpha),
                   c = mu + 0.5 * lame_lambda;
      const double s = 2 * c / (b + std::sqrt(b * b + 4 * a * c)); // lateral stretch squared
      const double J = lambda * s;
      const double pressure_term = 0.5 * lame_lambda * (J * J - 1);
      return Point{std::sqrt(s), J,
                   mu * (lambda * lambda * std::exp(-2 * alpha) - 1) + pressure_term,
                   mu * (s * std::exp(alpha) - 1) + pressure_term};
    };
    const auto f = [&](const double alpha) {
      const Point p = point(alpha);
      return std::abs(p.tau_1 - p.tau_2) / (cauchy ? p.J : 1.0) - sigma_y(alpha);
    };
    double alpha = 0.0;
    if (f(0.0) > 0.0)
      {
        double low = 0.0, high = log_strain;
        for (int i = 0; i < 200; ++i)
          {
            const double middle = 0.5 * (low + high);
            (f(middle) > 0.0 ? low : high) = middle;
          }
        alpha = 0.5 * (low + high);
      }
    const Point p = point(alpha);
    return {p.tau_1 / p.J, p.lateral_stretch, alpha};
  }

  // Drives F = diag(lambda, lambda_t, lambda_t) to log strain 0.2 in n_increments equal steps,
  // lambda_t from a secant iteration on P_22 = 0; returns the worst relative stress error and
  // the worst absolute errors of lambda_t and gamma_p against uniaxial_reference.
  std::array<double, 3> uniaxial_errors(const J2Plasticity                  &model,
                                        const std::function<double(double)> &sigma_y,
                                        const unsigned int                   n_increments)
  {
    const bool            cauchy = model.yield_stress_measure() == YieldStressMeasure::cauchy;
    std::vector<double>   state = virgin_state(model);
    double                lateral_stretch = 1.0, previous_log_strain = 0.0;
    std::array<double, 3> worst = {{0.0, 0.0, 0.0}};
    for (unsigned int increment = 1; increment <= n_increments; ++increment)
      {
        const double          log_strain = 0.2 * increment / n_increments;
        const double          lambda = std::exp(log_strain);
        std::vector<double>   state_new(state.size());
        MaterialPointResponse response;
        const auto            lateral_stress = [&](const double lambda_t) {
          EXPECT_EQ(
                         model.update(diagonal(lambda, lambda_t, lambda_t), state, response, state_new, false),
                         UpdateStatus::success);
          return response.P[1][1];
        };
        // The lateral stretch of vanishing lateral stress, from the isochoric guess.
        lateral_stretch = secant_root(
            lateral_stress, lateral_stretch * std::exp(-0.5 * (log_strain - previous_log_strain)));
        lateral_stress(lateral_stretch);
        const UniaxialState reference = uniaxial_reference(log_strain, sigma_y, cauchy);
        const double sigma = response.tau[0][0] / (lambda * lateral_stretch * lateral_stretch);
        worst[0] = std::max(worst[0], std::abs(sigma - reference.cauchy_stress) /
                                          std::abs(reference.cauchy_stress));
        worst[1] = std::max(worst[1], std::abs(lateral_stretch - reference.lateral_stretch));
        worst[2] = std::max(worst[2],
                            std::abs(model.equivalent_plastic_strain(state_new) - reference.alpha));
        state = state_new;
        previous_log_strain = log_strain;
      }
    return worst;
  }

  // Homogeneous uniaxial tension to log strain 0.2 under every law must reproduce the
  // independent solve to 1e-9 relative in the axial Cauchy stress and 1e-9 in the lateral
  // stretch and gamma_p, in 1, 7 and 50 increments alike (the flow direction is fixed, so the
  // exponential map is exact at any step size; one increment crosses every table point and
  // ends beyond the table), for both yield measures.
  TEST(J2Hardening, UniaxialTensionMatchesIndependentSolve)
  {
    for (const auto measure : {YieldStressMeasure::cauchy, YieldStressMeasure::kirchhoff})
      for (const auto &[name, law, sigma_y] : law_cases())
        {
          const J2Plasticity model(young_modulus, poisson_ratio, law, measure);
          for (const unsigned int n_increments : {1u, 7u, 50u})
            {
              const std::string label =
                  "J2 " + name +
                  (measure == YieldStressMeasure::cauchy ? " (cauchy)" : " (kirchhoff)") +
                  " uniaxial, " + std::to_string(n_increments) + " increments: ";
              SCOPED_TRACE(label);
              const auto errors = uniaxial_errors(model, sigma_y, n_increments);
              report(label + "max relative Cauchy stress error", errors[0]);
              EXPECT_LT(errors[0], 1e-9);
              EXPECT_LT(errors[1], 1e-9);
              EXPECT_LT(errors[2], 1e-9);
            }
        }
  }

  // A table with the points of a straight line is the linear law: the same state and stress
  // to round-off, also beyond the table.
  TEST(J2Hardening, StraightTableEqualsLinearLaw)
  {
    const J2Plasticity linear(young_modulus, poisson_ratio, yield_stress, 0.5);
    const J2Plasticity table(
        young_modulus, poisson_ratio,
        IsotropicHardening::table(
            {0, 0.01, 0.02, 0.05},
            {yield_stress, yield_stress + 0.005, yield_stress + 0.01, yield_stress + 0.025}));
    std::mt19937 generator(3);
    for (const double amplitude : {0.01, 0.05, 0.2})
      for (unsigned int sample = 0; sample < 4; ++sample)
        {
          const Tensor<2, 3>    F = random_deformation(generator, amplitude);
          MaterialPointResponse a, b;
          std::vector<double>   state_a(7), state_b(7);
          ASSERT_EQ(linear.update(F, virgin_state(linear), a, state_a), UpdateStatus::success);
          ASSERT_EQ(table.update(F, virgin_state(table), b, state_b), UpdateStatus::success);
          EXPECT_LT((a.P - b.P).norm(), 1e-12 * a.P.norm());
          EXPECT_LT((a.dP_dF - b.dP_dF).norm(), 1e-9 * a.dP_dF.norm());
          EXPECT_NEAR(state_a[6], state_b[6], 1e-13);
        }
  }
} // namespace
