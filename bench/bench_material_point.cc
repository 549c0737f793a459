// Cost of one material-point update [us], elastic and plastic, with and without the tangent,
// for the J2 model of Table 1, the crystal model of Table 2 (FCC, 12 systems) and BCC with all 48
// systems (bcc48). Run on demand: build/bench_material_point. Not a test: timings are machine facts.
// `build/bench_material_point crystal plastic yes 100` runs one row only, 100 times: the form to
// count instructions with valgrind --tool=callgrind (repeatable, unlike times on a shared machine).
// Each repetition updates from the same old state into the same state_new, so the crystal's local
// Newton starts from the previous repetition's result from the second repetition on.
#include "materials/CrystalPlasticity.h"
#include "materials/J2Plasticity.h"
#include "materials/crystal/Orientation.h"

#include <deal.II/base/tensor.h>

#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

using namespace indentsim::materials;

namespace
{
  double time_update(const MaterialModel &model, const dealii::Tensor<2, 3> &F,
                     const std::vector<double> &state, const bool tangent, const unsigned int n,
                     double &plastic_strain)
  {
    MaterialPointResponse response;
    std::vector<double>   state_new(state.size());
    const auto            start = std::chrono::steady_clock::now();
    for (unsigned int k = 0; k < n; ++k)
      model.update(F, state, response, state_new, tangent);
    const auto stop = std::chrono::steady_clock::now();
    plastic_strain = model.equivalent_plastic_strain(state_new);
    return std::chrono::duration<double, std::micro>(stop - start).count() / n;
  }
} // namespace

int main(int argc, char **argv)
{
  // Optional filter: model regime tangent [repetitions].
  const auto selected = [&](const char *model, const char *regime, const char *tangent) {
    return argc < 4 || (std::string(argv[1]) == model && std::string(argv[2]) == regime &&
                        std::string(argv[3]) == tangent);
  };
  const unsigned int      n_repetitions = argc >= 5 ? std::stoul(argv[4]) : 2000;
  const J2Plasticity      j2(69.0, 0.26, 0.305, 0.5);
  const CrystalPlasticity crystal(fcc_slip_systems(), LatticeElasticity(), ExtendedVoceHardening(),
                                  10.0);
  // BCC with all 48 systems ({110}, {112}, {123}<111>), Table 2's hardening on each family: the
  // cost per system against FCC's 12.
  const CrystalPlasticity bcc48(
      slip_systems("bcc", known_slip_families("bcc")), LatticeElasticity(),
      FamilyVoceHardening(std::vector<ExtendedVoceHardening>(3),
                          slip_systems("bcc", known_slip_families("bcc")).family, 1.4),
      10.0);
  std::printf("model    regime   tangent  time_us  plastic_strain\n");
  for (const MaterialModel *model :
       {static_cast<const MaterialModel *>(&j2), static_cast<const MaterialModel *>(&crystal),
        static_cast<const MaterialModel *>(&bcc48)})
    {
      std::vector<double> state(model->n_state_variables());
      model->oriented_initial_state(state, bunge_rotation({{20., 35., 10.}}));
      for (const double strain : {1e-3, 2e-2})
        {
          dealii::Tensor<2, 3> F;
          F[0][0] = F[1][1] = 1.0 - 0.5 * strain;
          F[2][2] = 1.0 + strain;
          F[0][2] = 0.3 * strain;
          for (const bool tangent : {false, true})
            {
              const char *model_name = model == &j2        ? "j2"
                                       : model == &crystal ? "crystal"
                                                           : "bcc48";
              const char *regime = strain < 1e-2 ? "elastic" : "plastic";
              if (!selected(model_name, regime, tangent ? "yes" : "no"))
                continue;
              double     plastic_strain = 0;
              const auto time =
                  time_update(*model, F, state, tangent, n_repetitions, plastic_strain);
              std::printf("%-8s %-8s %-8s %8.2f  %.3g\n", model_name, regime,
                          tangent ? "yes" : "no", time, plastic_strain);
            }
        }
    }
}
