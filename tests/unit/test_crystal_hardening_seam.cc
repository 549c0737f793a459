// A second hardening law, defined only here, through the same crystal-plasticity integrator
// (CrystalPlasticityModel): linear hardening with latent hardening,
//   tau_c_dot^r = h sum_s h_rs |gamma_dot^s|,  h_rs = q + (1 - q) delta_rs,
// so Delta tau_c^r = h (q Delta Gamma + (1 - q) |Delta gamma^r|) exactly over any increment. The
// integrator, its Jacobian and its consistent tangent are not touched: the law supplies its
// increment and derivatives through the interface of crystal/ExtendedVoceHardening.h.
#include "materials/crystal/CrystalPlasticityModel.templates.h"
#include "materials/crystal/LatticeElasticity.h"
#include "materials/crystal/RegularizedSchmidFlow.h"
#include "materials/crystal/SlipSystems.h"

#include "material_test_utilities.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <vector>

namespace
{
  using namespace indentsim::materials;
  using namespace indentsim::testing;
  using dealii::Tensor;

  struct LinearHardening
  {
    double tau0 = 0.12; // initial critical shear [GPa]
    double h = 0.08;    // hardening modulus [GPa]
    double q = 1.4;     // latent hardening ratio [-]

    double initial_critical_shear(unsigned int /*r*/) const { return tau0; }
    double stress_scale() const { return tau0; }

    template <int n_slip>
    void increment(double /*Gamma_n*/, const std::array<double, n_slip> &abs_delta_gamma,
                   const double delta_Gamma, HardeningIncrement<n_slip> &out) const
    {
      for (int r = 0; r < n_slip; ++r)
        {
          out.value[r] = h * (q * delta_Gamma + (1.0 - q) * abs_delta_gamma[r]);
          out.total_rate[r] = h * q;
          out.own_rate[r] = h * (1.0 - q);
        }
    }

    const char *parameter_error() const
    {
      return (tau0 > 0 && h >= 0 && q >= 0) ? nullptr
                                            : "tau0 must be positive, h and q non-negative";
    }
  };

  using LinearHardeningCrystal =
      CrystalPlasticityModel<LatticeElasticity, RegularizedSchmidFlow, LinearHardening>;

  LinearHardeningCrystal linear_model(const double q)
  {
    LinearHardening hardening;
    hardening.q = q;
    return LinearHardeningCrystal(fcc_slip_systems(), LatticeElasticity(),
                                  RegularizedSchmidFlow{10.0}, hardening);
  }

  // A plastic state of a random orientation, 4 increments towards a random deformation of a few
  // per cent (F_target).
  std::vector<double> random_plastic_state(const MaterialModel &model, std::mt19937 &generator,
                                           Tensor<2, 3> &F_target)
  {
    const Tensor<2, 3> rotation = random_rotation(generator);
    F_target = random_deformation(generator, 0.03);
    return plastic_state(model, rotation, F_target);
  }

  // The consistent tangent of the generic integrator with the linear law equals central finite
  // differences of P(F), at elastic and plastic states, with and without latent hardening.
  TEST(CrystalHardeningSeam, LinearHardeningTangentMatchesFiniteDifferences)
  {
    std::mt19937 generator(5);
    for (const double q : {1.0, 1.4})
      {
        const LinearHardeningCrystal model = linear_model(q);
        for (unsigned int sample = 0; sample < 4; ++sample)
          {
            std::vector<double> virgin(model.n_state_variables());
            model.oriented_initial_state(virgin, random_rotation(generator));
            const double error_elastic =
                tangent_error(model, random_deformation(generator, 5e-4), virgin, 1e-7);
            EXPECT_LT(error_elastic, 1e-6) << "q = " << q << ", elastic sample " << sample;

            Tensor<2, 3> F_target;
            const auto   state = random_plastic_state(model, generator, F_target);
            ASSERT_GT(model.equivalent_plastic_strain(state), 0.0);
            const double error_plastic = tangent_error(model, F_target, state, 1e-7);
            if (sample == 0)
              report("linear hardening, q = " + std::to_string(q) + ": plastic tangent FD error",
                     error_plastic);
            EXPECT_LT(error_plastic, 1e-5) << "q = " << q << ", plastic sample " << sample;
          }
      }
  }

  // The law is the one integrated: summed over the systems, Delta tau_c^r = h (q n Delta Gamma +
  // (1 - q) Delta Gamma), so sum_r (tau_c^r - tau0) = h Gamma (q n + 1 - q) after any history;
  // and the returned state lies on the yield surface.
  TEST(CrystalHardeningSeam, LinearHardeningIsTheLawIntegrated)
  {
    std::mt19937 generator(11);
    for (const double q : {1.0, 1.4})
      {
        const LinearHardeningCrystal model = linear_model(q);
        const LinearHardening       &law = model.hardening_law();
        const unsigned int           n = model.n_slip_systems();
        for (unsigned int sample = 0; sample < 4; ++sample)
          {
            Tensor<2, 3> F_target;
            const auto   state = random_plastic_state(model, generator, F_target);
            const double Gamma = model.equivalent_plastic_strain(state);
            ASSERT_GT(Gamma, 0.0);
            double hardening_sum = 0.0;
            for (unsigned int r = 0; r < n; ++r)
              hardening_sum += model.critical_shear(state, r) - law.tau0;
            const double expected = law.h * Gamma * (q * n + 1.0 - q);
            EXPECT_NEAR(hardening_sum / expected, 1.0, 1e-8)
                << "q = " << q << ", sample " << sample;

            MaterialPointResponse response;
            std::vector<double>   state_new(state.size());
            const Tensor<2, 3>    F = F_target + (random_deformation(generator, 0.01) - identity());
            ASSERT_EQ(model.update(F, state, response, state_new, true), UpdateStatus::success);
            if (model.equivalent_plastic_strain(state_new) > Gamma)
              {
                std::vector<double> tau_c(n);
                for (unsigned int r = 0; r < n; ++r)
                  tau_c[r] = model.critical_shear(state_new, r);
                EXPECT_NEAR(
                    model.yield_function_value(model.resolved_shear_stresses(F, state_new), tau_c),
                    1.0, 1e-10);
              }
          }
      }
  }
} // namespace
