// Unit tests of the BCC and HCP lattices of the crystal model: the slip families (counts, unit
// and orthogonal vectors, closure under the point group), their Schmid factors and the initial
// yield of the regularized Schmid law against an independent script
// (tests/data/schmid_yield.py, which derives the systems from crystallography alone), the
// hexagonal elasticity against the closed form for transversely isotropic media, and the
// consistent tangent with several families active. Units: GPa.
#include "materials/CrystalPlasticity.h"
#include "materials/MaterialFactory.h"
#include "materials/crystal/Orientation.h"
#include "materials/crystal/SlipSystems.h"

#include "material_test_utilities.h"
#include "uniaxial_driver.h"

#include <gtest/gtest.h>

#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace
{
  using namespace indentsim::materials;
  using namespace indentsim::testing;
  using dealii::Tensor;

  constexpr double zirconium_c_over_a = 1.593;

  std::vector<std::string> split(const std::string &text, const char separator)
  {
    std::vector<std::string> parts;
    std::stringstream        stream(text);
    for (std::string part; std::getline(stream, part, separator);)
      parts.push_back(part);
    return parts;
  }

  // The rows of a CSV file in tests/data (header dropped), each split at commas.
  std::vector<std::vector<std::string>> read_rows(const std::string &name)
  {
    std::ifstream in(std::string(INDENTSIM_TEST_DATA_DIR) + "/data/" + name);
    EXPECT_TRUE(in.good()) << name;
    std::vector<std::vector<std::string>> rows;
    std::string                           line;
    std::getline(in, line);
    while (std::getline(in, line))
      if (!line.empty())
        rows.push_back(split(line, ','));
    return rows;
  }

  std::array<double, 3> direction_of(const std::string &text)
  {
    const auto parts = split(text, ' ');
    return {{std::stod(parts[0]), std::stod(parts[1]), std::stod(parts[2])}};
  }

  std::string lower(std::string text)
  {
    for (char &c : text)
      c = static_cast<char>(std::tolower(c));
    return text;
  }

  // Schmid factors S_r = (d . m_r)(d . n_r) of unit d.
  std::vector<double> schmid_factors(const SlipSystems &systems, std::array<double, 3> d)
  {
    const double        length = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    Tensor<1, 3>        axis({d[0] / length, d[1] / length, d[2] / length});
    std::vector<double> S;
    for (unsigned int r = 0; r < systems.size(); ++r)
      S.push_back((axis * systems.direction[r]) * (axis * systems.normal[r]));
    return S;
  }

  TEST(CrystalLattices, FamiliesHaveTheirCountsAndOrthonormalSystems)
  {
    const std::vector<std::pair<std::string, std::vector<unsigned int>>> lattices = {
        {"fcc", {12}}, {"bcc", {12, 12, 24}}, {"hcp", {3, 3, 6, 12, 6}}};
    for (const auto &[lattice, counts] : lattices)
      {
        const auto families = known_slip_families(lattice);
        ASSERT_EQ(families.size(), counts.size()) << lattice;
        const SlipSystems systems = slip_systems(lattice, families, zirconium_c_over_a);
        unsigned int      total = 0;
        for (unsigned int f = 0; f < counts.size(); ++f)
          {
            EXPECT_EQ(family_size(lattice, families[f]), counts[f]) << families[f];
            total += counts[f];
          }
        ASSERT_EQ(systems.size(), total) << lattice;
        for (unsigned int r = 0; r < systems.size(); ++r)
          {
            EXPECT_NEAR(systems.direction[r].norm(), 1.0, 1e-14);
            EXPECT_NEAR(systems.normal[r].norm(), 1.0, 1e-14);
            EXPECT_NEAR(systems.direction[r] * systems.normal[r], 0.0, 1e-14);
            for (unsigned int s = 0; s < r; ++s)
              {
                const Tensor<2, 3> P = systems.schmid_tensor(r), Q = systems.schmid_tensor(s);
                EXPECT_GT(std::min((P - Q).norm(), (P + Q).norm()), 1e-3) << r << " " << s;
              }
          }
      }
    EXPECT_THROW(slip_systems("bcc", {"{111}<110>"}), std::invalid_argument);
    EXPECT_THROW(slip_systems("hcp", {"basal"}, 0.0), std::invalid_argument);
    EXPECT_THROW(slip_systems("bcc", {"{110}<111>", "{110}<111>"}), std::invalid_argument);
  }

  // Every operation of the point group maps each family onto itself (m (x) n onto +- the Schmid
  // tensor of a system of the same family); for FCC this checks the Schmid & Boas table, which
  // is not generated from the group.
  TEST(CrystalLattices, PointGroupMapsEachFamilyOntoItself)
  {
    for (const std::string lattice : {"fcc", "bcc", "hcp"})
      {
        const auto group = point_group(lattice);
        EXPECT_EQ(group.size(), lattice == "hcp" ? 24u : 48u);
        const SlipSystems systems =
            slip_systems(lattice, known_slip_families(lattice), zirconium_c_over_a);
        for (const Tensor<2, 3> &g : group)
          {
            EXPECT_NEAR((g * dealii::transpose(g) - identity()).norm(), 0.0, 1e-14);
            for (unsigned int r = 0; r < systems.size(); ++r)
              {
                const Tensor<2, 3> image =
                    dealii::outer_product(g * systems.direction[r], g * systems.normal[r]);
                unsigned int matches = 0;
                for (unsigned int s = 0; s < systems.size(); ++s)
                  if (systems.family[s] == systems.family[r] &&
                      std::min((image - systems.schmid_tensor(s)).norm(),
                               (image + systems.schmid_tensor(s)).norm()) < 1e-12)
                    ++matches;
                EXPECT_EQ(matches, 1u) << lattice << " system " << r;
              }
          }
      }
  }

  // The quarter model's mirror planes x = 0 and y = 0 (the reflection in the point group): a
  // basal (0001) surface with a1 along x has both (planes containing c every 30 degrees), and
  // loses them when turned 15 degrees about c; BCC (001) and (011) have them, (111) not.
  TEST(CrystalLattices, MirrorPlanesOfTheQuarterModel)
  {
    const Tensor<1, 3> e_x({1., 0., 0.}), e_y({0., 1., 0.});
    const Tensor<2, 3> basal = rotation_from_surface_normal({{0, 0, 1}}, {{1, 0, 0}});
    EXPECT_TRUE(is_mirror_plane("hcp", basal, e_x) && is_mirror_plane("hcp", basal, e_y));
    const Tensor<2, 3> turned = bunge_rotation({{15., 0., 0.}});
    EXPECT_FALSE(is_mirror_plane("hcp", turned, e_x) || is_mirror_plane("hcp", turned, e_y));
    EXPECT_TRUE(is_mirror_plane("hcp", bunge_rotation({{30., 0., 0.}}), e_x));
    for (const std::array<double, 3> &normal : {std::array<double, 3>{{0, 0, 1}}, {{0, 1, 1}}})
      {
        const Tensor<2, 3> g = rotation_from_surface_normal(normal, {{1, 0, 0}});
        EXPECT_TRUE(is_mirror_plane("bcc", g, e_x) && is_mirror_plane("bcc", g, e_y));
      }
    const Tensor<2, 3> g111 = rotation_from_surface_normal({{1, 1, 1}}, {{1, -1, 0}});
    EXPECT_FALSE(is_mirror_plane("bcc", g111, e_x) && is_mirror_plane("bcc", g111, e_y));
  }

  // hcp orientations from Miller-Bravais indices: the indented plane (hkil) contains every
  // direction [uvtw] of its zone (u h + v k + t i + w l = 0), so the sample z axis is
  // perpendicular to them; (0001) with [2 -1 -1 0] is the crystal frame itself; three-index
  // (hkl) and [UVW] = [u - t, v - t, w] name the same orientation.
  TEST(CrystalLattices, MillerBravaisOrientationsFollowTheZoneLaw)
  {
    indentsim::io::MaterialParameters m;
    m.lattice = indentsim::io::Lattice::hcp;
    m.c_over_a = 1.587;
    m.orientation.kind = indentsim::io::OrientationKind::surface_normal;
    const auto orientation = [&](const std::vector<double> &plane,
                                 const std::vector<double> &direction) {
      m.orientation.surface_normal = plane;
      m.orientation.reference_direction = direction;
      return create_orientation(m);
    };
    EXPECT_LT((orientation({0, 0, 0, 1}, {2, -1, -1, 0}) - identity()).norm(), 1e-12);
    struct Case
    {
      std::vector<double>   plane, direction, plane3, direction3;
      std::array<double, 4> zone; // a second direction in the plane
    };
    for (const Case &c :
         {Case{{1, 0, -1, 0}, {-1, 2, -1, 0}, {1, 0, 0}, {0, 3, 0}, {0, 0, 0, 1}},
          Case{{1, 0, -1, 1}, {-1, 2, -1, 0}, {1, 0, 1}, {0, 3, 0}, {-2, 1, 1, 3}},
          Case{{1, 1, -2, 2}, {1, -1, 0, 0}, {1, 1, 2}, {2, -2, 0}, {-1, -1, 2, 3}}})
      {
        const Tensor<2, 3> g = orientation(c.plane, c.direction);
        const Tensor<1, 3> z = g * Tensor<1, 3>({0., 0., 1.}); // sample z in the crystal frame
        const Tensor<1, 3> x = g * Tensor<1, 3>({1., 0., 0.});
        const std::array<double, 4> direction{
            {c.direction[0], c.direction[1], c.direction[2], c.direction[3]}};
        const Tensor<1, 3> d = miller_bravais_direction(direction, m.c_over_a);
        const Tensor<1, 3> zone = miller_bravais_direction(c.zone, m.c_over_a);
        EXPECT_NEAR(z * zone / zone.norm(), 0.0, 1e-12) << c.plane[0] << c.plane[1] << c.plane[3];
        EXPECT_NEAR(z * d / d.norm(), 0.0, 1e-12);
        EXPECT_NEAR(x * d / d.norm(), 1.0, 1e-12); // the reference direction along sample x
        EXPECT_LT((orientation(c.plane3, c.direction3) - g).norm(), 1e-12);
      }
  }

  // The largest Schmid factor and the sum of |S|^20 of each family along the script's loading
  // directions: invariants of the family, whatever the numbering and signs.
  TEST(CrystalLattices, SchmidFactorsMatchTheIndependentScript)
  {
    const auto rows = read_rows("schmid_factors.csv");
    ASSERT_GE(rows.size(), 29u);
    for (const auto &row : rows)
      {
        const std::string lattice = lower(row[0]);
        const double      c_over_a = row[2].empty() ? 0.0 : std::stod(row[2]);
        const auto        S =
            schmid_factors(slip_systems(lattice, {row[1]}, c_over_a), direction_of(row[3]));
        double largest = 0, sum = 0;
        for (const double s : S)
          {
            largest = std::max(largest, std::abs(s));
            sum += std::pow(std::abs(s), 20);
          }
        const double expected_largest = std::stod(row[4]), expected_sum = std::stod(row[5]);
        EXPECT_NEAR(largest, expected_largest, 1e-9) << row[0] << " " << row[1] << " " << row[3];
        EXPECT_NEAR(sum, expected_sum, 1e-8 * expected_sum + 1e-300)
            << row[0] << " " << row[1] << " " << row[3];
      }
  }

  // A model of the script's case: the families with their own tau0, n = 10, and a
  // stiffness 1000 times a metal's so that the elastic strain at yield (~1e-6) leaves the
  // small-strain closed form exact to ~1e-5.
  CrystalPlasticity stiff_model(const std::string              &lattice,
                                const std::vector<std::string> &families,
                                const std::vector<double> &tau0, const double c_over_a)
  {
    const SlipSystems                  systems = slip_systems(lattice, families, c_over_a);
    std::vector<ExtendedVoceHardening> laws;
    for (const double t : tau0) // hardening as stiff as the elasticity keeps the driver regular
      laws.push_back({t, t, 1000 * t, 0.0, 1.0});
    const LatticeElasticity elasticity =
        lattice == "hcp" ? LatticeElasticity::hexagonal(143.5e3, 72.5e3, 65.4e3, 164.9e3, 32.1e3)
                         : LatticeElasticity::cubic(522.4e3, 204.4e3, 160.6e3);
    return CrystalPlasticity(systems, elasticity, FamilyVoceHardening(laws, systems.family, 1.0),
                             10.0);
  }

  // The Cauchy stress at which slip starts in tension along `axis`: the strain is doubled from
  // 1e-7 until slip starts (yield strains are 2e-6 to 7e-6; the first plastic point is at most
  // twice the yield strain, where the uniaxial driver's Newton still converges), then bisected.
  double initial_yield_stress(const CrystalPlasticity &model, const std::array<double, 3> &axis)
  {
    std::vector<double> state0(model.n_state_variables());
    model.oriented_initial_state(state0, axis_along_z(axis));
    const auto slips = [&](const double stretch) {
      UniaxialDriver driver{model, state0};
      EXPECT_TRUE(std::isfinite(driver.load_to(stretch))) << "stretch - 1 = " << stretch - 1;
      return model.equivalent_plastic_strain(driver.state) > 0;
    };
    double elastic = 1.0, plastic = 1.0 + 1e-7;
    while (!slips(plastic) && plastic < 1.001)
      elastic = plastic, plastic = 1.0 + 2 * (plastic - 1.0);
    for (unsigned int k = 0; k < 30; ++k)
      {
        const double middle = 0.5 * (elastic + plastic);
        (slips(middle) ? plastic : elastic) = middle;
      }
    UniaxialDriver driver{model, state0};
    return driver.load_to(elastic);
  }

  // The regularized Schmid law's sigma_y = (sum_r |S_r / tau0_r|^2n)^(-1/2n) of the script, for
  // BCC with one, two and three families and HCP with three and five, along the script's axes
  // (the issue asks for 0.1 %; the small-strain limit allows 1e-4).
  TEST(CrystalLattices, InitialYieldMatchesRegularizedSchmidLaw)
  {
    const auto rows = read_rows("schmid_yield.csv");
    ASSERT_GE(rows.size(), 20u);
    double largest_deviation = 0;
    for (const auto &row : rows)
      {
        std::vector<double> tau0;
        for (const std::string &t : split(row[2], '+'))
          tau0.push_back(std::stod(t));
        const CrystalPlasticity model = stiff_model(lower(row[0]), split(row[1], '+'), tau0,
                                                    row[3].empty() ? 0.0 : std::stod(row[3]));
        const double            sigma_y = initial_yield_stress(model, direction_of(row[4]));
        const double            deviation = sigma_y / std::stod(row[5]) - 1.0;
        largest_deviation = std::max(largest_deviation, std::abs(deviation));
        EXPECT_LT(std::abs(deviation), 1e-4) << row[0] << " " << row[1] << " " << row[4];
      }
    report("largest relative deviation of sigma_y from the script", largest_deviation);
  }

  // Young's modulus of the hexagonal lattice along a direction at angle theta from the c axis,
  // 1/E = s11 sin^4 + s33 cos^4 + (2 s13 + s44) sin^2 cos^2 (transversely isotropic media), with
  // the compliances in closed form from C11, C12, C13, C33, C44 (zirconium, Fisher & Renken 1964).
  TEST(CrystalLattices, HexagonalYoungsModulusMatchesTransverselyIsotropicClosedForm)
  {
    const double            C11 = 143.5, C12 = 72.5, C13 = 65.4, C33 = 164.9, C44 = 32.1;
    const double            D = C33 * (C11 + C12) - 2 * C13 * C13;
    const double            s11 = (C11 * C33 - C13 * C13) / ((C11 - C12) * D), s13 = -C13 / D;
    const double            s33 = (C11 + C12) / D, s44 = 1 / C44;
    const CrystalPlasticity model(slip_systems("hcp", {}, zirconium_c_over_a),
                                  LatticeElasticity::hexagonal(C11, C12, C13, C33, C44),
                                  ExtendedVoceHardening{10.0, 0.0, 0.0, 0.0, 1.0}, 10.0);
    for (const double degrees : {0.0, 30.0, 45.0, 60.0, 90.0})
      for (const double azimuth : {0.0, 17.0}) // transverse isotropy: no dependence on it
        {
          const double theta = degrees * M_PI / 180, phi = azimuth * M_PI / 180;
          const double s = std::sin(theta), c = std::cos(theta);
          const double expected =
              1 / (s11 * s * s * s * s + s33 * c * c * c * c + (2 * s13 + s44) * s * s * c * c);
          std::vector<double> state(model.n_state_variables());
          model.oriented_initial_state(state,
                                       axis_along_z({{s * std::cos(phi), s * std::sin(phi), c}}));
          UniaxialDriver driver{model, state};
          const double   strain = 1e-7;
          const double   modulus = driver.load_to(1.0 + strain) / std::log(1.0 + strain);
          if (azimuth == 0.0)
            report("hcp E at " + std::to_string(int(degrees)) + " deg from c [GPa]", modulus);
          EXPECT_NEAR(modulus / expected, 1.0, 1e-5) << degrees << " " << azimuth;
        }
  }

  // Monotonic tension along [001] of BCC {110}<111> (8 equally stressed systems, no lattice
  // rotation) with latent hardening: the exponential map and the secant Voce update are exact,
  // so 1 and 50 increments to 5 % strain give the same stress, as for FCC.
  TEST(CrystalLattices, BccMonotonicPathIsStepSizeIndependent)
  {
    const CrystalPlasticity model(slip_systems("bcc"),
                                  LatticeElasticity::cubic(232.1, 135.9, 117.0),
                                  ExtendedVoceHardening{0.061, 0.216, 0.593, 0.0, 1.4}, 10.0);
    const auto              stress_after = [&](const unsigned int n_steps) {
      std::vector<double> state(model.n_state_variables());
      model.oriented_initial_state(state, identity());
      UniaxialDriver driver{model, state};
      double         sigma = 0;
      for (unsigned int step = 1; step <= n_steps; ++step)
        sigma = driver.load_to(std::exp(0.05 * step / n_steps));
      return sigma;
    };
    const double one_step = stress_after(1), fifty_steps = stress_after(50);
    report("bcc [001] sigma at 5 % strain, 1 step [GPa]", one_step);
    EXPECT_NEAR(one_step / fifty_steps, 1.0, 1e-9);
    EXPECT_GT(one_step, 0.061 * std::sqrt(6.0) * 1.5); // hardened well beyond first yield
  }

  // Every family of the lattice (BCC: 48 systems, HCP: 30), each with its own hardening law (so
  // the families' critical shears differ), optionally with a latent matrix between the families
  // (not symmetric), where each family's slip enters the hardening rows on its own.
  CrystalPlasticity several_family_model(const std::string &lattice, const bool latent_matrix)
  {
    const auto                         families = known_slip_families(lattice);
    const SlipSystems                  systems = slip_systems(lattice, families, 1.587);
    std::vector<ExtendedVoceHardening> laws;
    for (unsigned int f = 0; f < families.size(); ++f)
      laws.push_back({0.10 + 0.02 * f, 0.05 + 0.01 * f, 1.0 + 0.2 * f, 0.01, 1.4});
    std::vector<std::vector<double>> latent;
    if (latent_matrix)
      for (unsigned int f = 0; f < families.size(); ++f)
        {
          latent.emplace_back();
          for (unsigned int g = 0; g < families.size(); ++g)
            latent.back().push_back(f == g ? 1.0 + 0.1 * f : 1.2 + 0.1 * f + 0.05 * g);
        }
    const LatticeElasticity elasticity =
        lattice == "hcp" ? LatticeElasticity::hexagonal(162.4, 92.0, 69.0, 180.7, 46.7)
                         : LatticeElasticity::cubic(231.4, 134.7, 116.4);
    return CrystalPlasticity(systems, elasticity,
                             FamilyVoceHardening(laws, systems.family, 1.4, latent), 10.0);
  }

  // The consistent tangent against central differences with every BCC and every HCP family, at
  // plastic states of random orientations and deformations, with and without a latent matrix.
  TEST(CrystalLattices, TangentMatchesFiniteDifferencesWithSeveralFamilies)
  {
    for (const std::string lattice : {"bcc", "hcp"})
      for (const bool matrix : {false, true})
        {
          const CrystalPlasticity model = several_family_model(lattice, matrix);
          const std::string       variant = lattice + (matrix ? " with latent matrix" : "");
          std::mt19937            generator(5);
          for (unsigned int sample = 0; sample < 4; ++sample)
            {
              const Tensor<2, 3>        rotation = random_rotation(generator);
              const Tensor<2, 3>        F_target = random_deformation(generator, 0.02);
              const std::vector<double> state = plastic_state(model, rotation, F_target);
              ASSERT_GT(model.equivalent_plastic_strain(state), 0.0);
              const double error = tangent_error(model, F_target, state, 1e-7);
              if (sample == 0)
                report(variant + " plastic tangent FD error", error);
              EXPECT_LT(error, 1e-5) << variant << " sample " << sample;
            }
        }
  }

  // Objectivity with every BCC and HCP family, as for FCC: a superposed rigid rotation Q F of a
  // plastic increment rotates P (Q P) and the Kirchhoff stress (Q tau Q^T) and leaves the
  // internal state unchanged.
  TEST(CrystalLattices, SuperposedRotationChangesNothingElse)
  {
    for (const std::string lattice : {"bcc", "hcp"})
      {
        const CrystalPlasticity model = several_family_model(lattice, true);
        std::mt19937            generator(11);
        for (unsigned int sample = 0; sample < 3; ++sample)
          {
            const Tensor<2, 3>    rotation = random_rotation(generator);
            const Tensor<2, 3>    F = random_deformation(generator, 0.02);
            const auto            state = plastic_state(model, rotation, F); // at 4/5 of F
            const Tensor<2, 3>    Q = random_rotation(generator);
            MaterialPointResponse plain, rotated;
            std::vector<double>   state_plain(state.size()), state_rotated(state.size());
            ASSERT_EQ(model.update(F, state, plain, state_plain), UpdateStatus::success);
            ASSERT_EQ(model.update(Q * F, state, rotated, state_rotated), UpdateStatus::success);
            EXPECT_GT(model.equivalent_plastic_strain(state_plain),
                      model.equivalent_plastic_strain(state))
                << lattice << ": the increment must slip";
            EXPECT_LT((rotated.P - Q * plain.P).norm(), 1e-12 * plain.P.norm()) << lattice;
            EXPECT_LT((rotated.tau - Q * plain.tau * dealii::transpose(Q)).norm(),
                      1e-12 * plain.tau.norm())
                << lattice;
            for (unsigned int k = 0; k < state.size(); ++k)
              EXPECT_NEAR(state_rotated[k], state_plain[k], 1e-12 * (1 + std::abs(state_plain[k])))
                  << lattice << " state " << k;
          }
      }
  }

  // The latent matrix's meaning, in closed form. BCC tension along [001]: the 8 {110}<111>
  // systems with Schmid factor 0.41 slip; {112}<111> (tau0 = 10 GPa) never does. All slip is
  // family A's, so the secants of family B's law over the increments add up to its Voce law,
  //   tau_c^r = tau0_B + q_BA (tau_c,B(Gamma) - tau0_B)   (row B = {112}, column A = {110}),
  // and the {110} systems without slip harden by q_AA (tau_c,A(Gamma) - tau0_A). A matrix whose
  // entries all equal q gives the scalar q's state to round-off.
  TEST(CrystalLattices, LatentMatrixRowsHardenTheirFamily)
  {
    const SlipSystems systems = slip_systems("bcc", {"{110}<111>", "{112}<111>"});
    const std::vector<ExtendedVoceHardening> laws = {{0.06, 0.1, 0.5, 0.02, 1.0},
                                                     {10.0, 0.2, 1.0, 0.05, 1.0}};
    const auto voce = [](const ExtendedVoceHardening &law, const double Gamma) {
      return law.tau0 +
             (law.tau1 + law.theta1 * Gamma) * (1 - std::exp(-law.theta0 * Gamma / law.tau1));
    };
    const double q_AA = 1.1, q_AB = 1.2, q_BA = 1.7, q_BB = 1.3;
    const auto   strained = [&](const FamilyVoceHardening &hardening) {
      const CrystalPlasticity model(systems, LatticeElasticity::cubic(232.1, 135.9, 117.0),
                                      hardening, 10.0);
      std::vector<double>     state(model.n_state_variables());
      model.oriented_initial_state(state, identity());
      UniaxialDriver driver{model, state};
      for (unsigned int step = 1; step <= 10; ++step)
        driver.load_to(std::exp(0.002 * step));
      return driver.state;
    };
    const std::vector<double> state =
        strained(FamilyVoceHardening(laws, systems.family, 1.4, {{q_AA, q_AB}, {q_BA, q_BB}}));
    const unsigned int n = systems.size();
    const double       Gamma = state[9 + n];
    ASSERT_GT(Gamma, 0.01);
    unsigned int idle_A = 0;
    for (unsigned int r = 0; r < n; ++r)
      {
        const double tau_c = state[9 + r];
        if (systems.family[r] == 1)
          EXPECT_NEAR(tau_c, 10.0 + q_BA * (voce(laws[1], Gamma) - 10.0), 1e-10) << "system " << r;
        else if (std::abs(tau_c - (0.06 + q_AA * (voce(laws[0], Gamma) - 0.06))) < 1e-10)
          ++idle_A; // the 4 {110} systems with Schmid factor 0
      }
    EXPECT_EQ(idle_A, 4u);
    report("bcc [001] Gamma at 2 % strain", Gamma);

    const std::vector<double> scalar = strained(FamilyVoceHardening(laws, systems.family, 1.4));
    const std::vector<double> uniform =
        strained(FamilyVoceHardening(laws, systems.family, 1.4, {{1.4, 1.4}, {1.4, 1.4}}));
    for (std::size_t i = 0; i < scalar.size(); ++i)
      EXPECT_NEAR(uniform[i], scalar[i], 1e-12 * (1 + std::abs(scalar[i]))) << "state " << i;
  }
} // namespace
