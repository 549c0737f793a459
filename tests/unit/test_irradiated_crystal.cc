// The irradiation term of the crystal hardening (crystal/ExtendedVoceHardening.h):
//   tau_c = tau_c,Voce(Gamma) + tau_irr,0 exp(-Gamma/gamma_0),
// against its closed form, through the integrator (initial yield by the regularized Schmid law,
// the exact integration of a monotonic path, the critical shears after any path with q = 1) and
// the consistent tangent against finite differences while the defects are swept out. Units:
// GPa.
#include "materials/CrystalPlasticity.h"
#include "materials/crystal/Orientation.h"
#include "materials/crystal/SlipSystems.h"

#include "material_test_utilities.h"
#include "uniaxial_driver.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace
{
  using namespace indentsim::materials;
  using namespace indentsim::testing;
  using dealii::Tensor;

  // Table 2's aluminium with an irradiation term of 0.08 GPa swept out over gamma_0 = 0.02.
  ExtendedVoceHardening irradiated_law(const double q = 1.4)
  {
    ExtendedVoceHardening law;
    law.q = q;
    law.tau_irr = 0.08;
    law.softening_slip = 0.02;
    return law;
  }

  CrystalPlasticity irradiated_fcc(const double q, const double stiffness_factor = 1.0)
  {
    return CrystalPlasticity(fcc_slip_systems(),
                             LatticeElasticity::cubic(106.7 * stiffness_factor,
                                                      60.4 * stiffness_factor,
                                                      28.3 * stiffness_factor),
                             FamilyVoceHardening(irradiated_law(q)), 10.0);
  }

  // The law: tau_c(0) = tau0 + tau_irr, the rate against central differences (negative while
  // the defects dominate), and the exact increment against the difference of the closed form.
  TEST(IrradiatedCrystal, LawMatchesItsClosedForm)
  {
    const ExtendedVoceHardening law = irradiated_law();
    EXPECT_DOUBLE_EQ(law.critical_shear(0.0), law.tau0 + law.tau_irr);
    const double voce_only =
        law.tau0 + (law.tau1 + law.theta1 * 0.05) * (1 - std::exp(-law.theta0 * 0.05 / law.tau1));
    EXPECT_NEAR(law.critical_shear(0.05), voce_only + 0.08 * std::exp(-0.05 / 0.02), 1e-15);
    EXPECT_LT(law.hardening_rate(0.0), 0.0); // theta0 = 0.1 < tau_irr / gamma_0 = 4
    for (const double Gamma : {0.0, 0.003, 0.03, 0.3})
      {
        const double h = 1e-8, below = std::min(h, Gamma);
        EXPECT_NEAR((law.critical_shear(Gamma + h) - law.critical_shear(Gamma - below)) /
                        (h + below),
                    law.hardening_rate(Gamma), 2e-5)
            << "Gamma = " << Gamma;
        for (const double delta : {1e-4, 0.01, 0.2})
          {
            ExtendedVoceHardening defects_only = law;
            defects_only.theta0 = 0.0; // tau_c = tau0 + tau_irr(Gamma)
            const auto [value, rate] = law.irradiation_increment(Gamma, delta);
            EXPECT_NEAR(value,
                        defects_only.critical_shear(Gamma + delta) -
                            defects_only.critical_shear(Gamma),
                        1e-15);
            EXPECT_NEAR(rate, defects_only.hardening_rate(Gamma + delta), 1e-12);
          }
      }
  }

  // Initial yield along [001], [011], [111] in the small-strain limit (stiffness x 1000): the
  // regularized Schmid law's closed form with tau0 + tau_irr in place of tau0 (the ratios of
  // test_crystal.cc, n = 10), within 1e-5.
  TEST(IrradiatedCrystal, InitialYieldIsTheSchmidLawOfTheRaisedCriticalShear)
  {
    const CrystalPlasticity model = irradiated_fcc(1.4, 1000.0);
    const double            tau_c0 = 0.12 + 0.08;
    const std::array<std::pair<std::array<double, 3>, double>, 3> cases = {
        {{{{0, 0, 1}}, 2.20760}, {{{0, 1, 1}}, 2.28545}, {{{1, 1, 1}}, 3.35938}}};
    for (const auto &[axis, ratio] : cases)
      {
        const double sigma_y =
            initial_yield_stress(model, oriented_state(model, axis_along_z(axis)), 1.0 + 2e-5);
        EXPECT_NEAR(sigma_y / (tau_c0 * ratio), 1.0, 1e-5);
      }
  }

  // Tension along [001] past the softening: the integration of both terms is exact, so 1 and
  // 50 increments to 5 % strain give the same stress; with q = 1 every system's critical shear
  // is the closed form at the total slip after a random path; the stress falls below its first
  // yield value once the defects are swept out (tau_irr / gamma_0 > theta0).
  TEST(IrradiatedCrystal, IntegrationIsExactAndSoftens)
  {
    const CrystalPlasticity model = irradiated_fcc(1.0);
    const auto              stress_after = [&](const unsigned int n_steps, double &peak) {
      UniaxialDriver driver{model, oriented_state(model, identity())};
      double         sigma = 0;
      for (unsigned int step = 1; step <= n_steps; ++step)
        {
          sigma = driver.load_to(std::exp(0.05 * step / n_steps));
          peak = std::max(peak, sigma);
        }
      return sigma;
    };
    double       peak = 0;
    const double one_step = stress_after(1, peak), fifty_steps = stress_after(50, peak);
    report("irradiated [001]: peak stress on the way to 5 % strain [GPa]", peak);
    report("irradiated [001]: sigma at 5 % strain [GPa]", fifty_steps);
    EXPECT_NEAR(one_step / fifty_steps, 1.0, 1e-9);
    // The peak lies at the Schmid stress of tau0 + tau_irr, a little below it: the regularized
    // flow starts before it and sweeps defects out on the way.
    EXPECT_NEAR(peak / (2.20760 * (0.12 + 0.08)), 1.0, 0.02);
    EXPECT_LT(fifty_steps, 0.9 * peak); // then swept-out defects soften

    std::mt19937 generator(7);
    for (unsigned int sample = 0; sample < 3; ++sample)
      {
        std::vector<double> state = oriented_state(model, random_rotation(generator));
        load_towards(model, random_deformation(generator, 0.03), 5, state);
        const double Gamma = model.equivalent_plastic_strain(state);
        ASSERT_GT(Gamma, 0.0);
        for (unsigned int r = 0; r < 12; ++r)
          EXPECT_NEAR(model.critical_shear(state, r), irradiated_law(1.0).critical_shear(Gamma),
                      1e-12)
              << "sample " << sample << ", system " << r;
      }
  }

  // The consistent tangent against central differences while the defects soften the crystal:
  // FCC with q = 1.4, and BCC with two families of different irradiation terms and a latent
  // matrix between them.
  TEST(IrradiatedCrystal, TangentMatchesFiniteDifferencesWhileSoftening)
  {
    std::vector<CrystalPlasticity>     models = {irradiated_fcc(1.4)};
    const SlipSystems                  bcc = slip_systems("bcc", {"{110}<111>", "{112}<111>"});
    std::vector<ExtendedVoceHardening> laws = {irradiated_law(), irradiated_law()};
    laws[1].tau0 = 0.13;
    laws[1].tau_irr = 0.05;
    laws[1].softening_slip = 0.05;
    models.emplace_back(bcc, LatticeElasticity::cubic(231.4, 134.7, 116.4),
                        FamilyVoceHardening(laws, bcc.family, 1.4, {{1.0, 1.4}, {1.3, 1.0}}), 10.0);
    std::mt19937 generator(13);
    for (std::size_t m = 0; m < models.size(); ++m)
      for (unsigned int sample = 0; sample < 4; ++sample)
        {
          const CrystalPlasticity &model = models[m];
          std::vector<double>      state = oriented_state(model, random_rotation(generator));
          const Tensor<2, 3>       F_target = random_deformation(generator, 0.02);
          load_towards(model, F_target, 4, state);
          ASSERT_GT(model.equivalent_plastic_strain(state), 0.0);
          const double error = tangent_error(model, F_target, state, 1e-7);
          if (sample == 0)
            report(std::string(m == 0 ? "fcc" : "bcc, two families") +
                       ": irradiated plastic tangent FD error",
                   error);
          EXPECT_LT(error, 1e-5) << "model " << m << ", sample " << sample;
        }
  }
} // namespace
