// Depth-graded specimens (material.layers) against their homogeneous limits: a layer with the
// substrate's own parameters and a layer of zero thickness change nothing, a layer holding the
// whole plastic zone behaves as the uniformly hardened material, and a thin hard layer lies
// between the pristine and the hardened curves. J2 in axisymmetric mode on the automatic mesh.
// Units: um, mN, GPa.
#include "case/Case.h"
#include "indenter/IndenterFactory.h"
#include "mesh/MeshDesign.h"
#include "problems/IndentationProblem.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <map>
#include <string>
#include <vector>

using namespace indentsim;

namespace
{
  // The paper's J2 block (sigma_y0 = 0.305 GPa) under its rounded cone to 1 um in 64 geometric
  // steps, axisymmetric, on a coarse automatic mesh (6 elements per contact radius: 1 700 DOFs
  // without layers, a few seconds; the contact edge passing its nodes makes the force ripple by
  // about 1.5 %), designed with `layers` (from the surface down).
  io::Case layered_case(const std::vector<io::MaterialLayer> &layers, const double yield_stress)
  {
    io::Case c;
    c.material.model = "j2";
    c.material.yield_stress = yield_stress;
    c.material.layers = layers;
    c.indenter.a = 2.48;
    c.indenter.delta = 0.005;
    c.specimen.symmetry = "axisymmetric";
    c.specimen.contact_elements = io::automatic_contact_elements;
    c.specimen.elements_per_radius = 6;
    c.loading.max_depth = 1.0;
    c.loading.steps = 64;
    c.loading.spacing = "geometric";
    c.loading.unload = false;
    c.contact.penetration_tolerance = 1e-5;
    mesh::design_mesh(c, *indenter::create_indenter(c.indenter), /*size_given=*/false);
    return c;
  }

  struct Curve
  {
    std::vector<double>               depth, force;
    std::vector<problems::StepRecord> records;
  };

  Curve run(const io::Case &c)
  {
    problems::IndentationProblem<2> problem(c, MPI_COMM_WORLD, false);
    problem.setup();
    problem.run("");
    Curve curve;
    for (const auto &record : problem.records())
      {
        curve.depth.push_back(record.depth);
        curve.force.push_back(record.force);
      }
    curve.records = problem.records();
    return curve;
  }

  // The force of `curve` at the depth h, linear between its records.
  double force_at(const Curve &curve, const double h)
  {
    const auto upper = std::lower_bound(curve.depth.begin(), curve.depth.end(), h);
    if (upper == curve.depth.begin())
      return curve.force.front();
    if (upper == curve.depth.end())
      return curve.force.back();
    const std::size_t i = upper - curve.depth.begin();
    const double      t = (h - curve.depth[i - 1]) / (curve.depth[i] - curve.depth[i - 1]);
    return (1 - t) * curve.force[i - 1] + t * curve.force[i];
  }

  const io::MaterialLayer hard_layer(const double thickness)
  {
    return {thickness, "{yield_stress: 0.61}"};
  }

  // The homogeneous curves, run once for both tests.
  const Curve &homogeneous(const double yield_stress)
  {
    static std::map<double, Curve> curves;
    if (curves.count(yield_stress) == 0)
      curves[yield_stress] = run(layered_case({}, yield_stress));
    return curves.at(yield_stress);
  }
} // namespace

// The layer model may not change a homogeneous specimen: a layer that repeats the substrate's
// parameters gives the pristine curve on the same mesh (the automatic mesh refines across a
// layer, so the pristine run takes the layered case's design), and a hard layer of zero
// thickness (it holds no point, and the mesh ignores it) gives the pristine curve of the
// pristine design; both to round-off (the same increments, the same Newton iterations).
TEST(Layers, SubstrateParametersAndZeroThicknessGiveTheHomogeneousCurve)
{
  const io::Case same_case = layered_case({{0.5, "{yield_stress: 0.305}"}}, 0.305);
  io::Case       pristine_case = same_case;
  pristine_case.material.layers.clear();
  ASSERT_GT(pristine_case.specimen.grading.layer_element, 0.);
  const Curve  same = run(same_case);
  const Curve  pristine_on_layered_mesh = run(pristine_case);
  const Curve &pristine = homogeneous(0.305);
  const Curve  empty = run(layered_case({hard_layer(0)}, 0.305));
  const auto   expect_equal = [](const Curve &curve, const Curve &reference) {
    ASSERT_EQ(curve.depth.size(), reference.depth.size());
    for (std::size_t i = 0; i < reference.depth.size(); ++i)
      {
        EXPECT_EQ(curve.depth[i], reference.depth[i]);
        EXPECT_NEAR(curve.force[i], reference.force[i], 1e-10 * reference.force.back())
            << "h = " << reference.depth[i];
      }
  };
  expect_equal(same, pristine_on_layered_mesh);
  expect_equal(empty, pristine);
}

// A hard layer (sigma_y0 doubled) of 10 um holds the plastic zone of a 1 um indent (its depth is
// about 2.5 contact radii, 6 um): the curve is the uniformly hardened one within 1 %. And a
// layer of 0.3 um lies between the two homogeneous curves at every depth, with the hardened
// curve's force while the indent is shallow against the layer and moving toward the pristine one
// as the indent passes through it (the layer is meshed with four elements across it).
TEST(Layers, HardLayerLiesBetweenPristineAndUniformlyHardened)
{
  const Curve &pristine = homogeneous(0.305);
  const Curve &hardened = homogeneous(0.61);
  const Curve  thick = run(layered_case({hard_layer(10)}, 0.305));
  const Curve  thin = run(layered_case({hard_layer(0.3)}, 0.305));
  double       largest_thick_difference = 0;
  for (const double h : {0.05, 0.1, 0.2, 0.3, 0.5, 0.7, 1.0})
    {
      const double p = force_at(pristine, h), H = force_at(hardened, h);
      const double t = force_at(thin, h);
      std::cout << "[ layers ] h = " << h << " um: pristine " << p << " mN, 0.3 um layer " << t
                << " mN, 10 um layer " << force_at(thick, h) << " mN, hardened " << H << " mN"
                << std::endl;
      largest_thick_difference =
          std::max(largest_thick_difference, std::abs(force_at(thick, h) / H - 1));
      // To 0.5 %: deep in the indent the layer's share of the force (-0.5 % at 1 um) is below
      // the contact edge's ripple on these coarse meshes (about 1.5 %, layered_case), which
      // moves with the material too (on the thin layer's own mesh the pristine curve lies
      // 0.7-0.9 % above the layered one at 0.7-1 um).
      EXPECT_GT(t, p * (1 - 0.005)) << "h = " << h;
      EXPECT_LT(t, H * (1 + 0.005)) << "h = " << h;
    }
  EXPECT_LT(largest_thick_difference, 0.01);
  // Shallow: the contact and much of the plastic zone lie in the layer.
  EXPECT_NEAR(force_at(thin, 0.05) / force_at(hardened, 0.05), 1., 0.05);
  // Deep: the layer's share of the force falls as the indent passes through it.
  const double share_shallow = (force_at(thin, 0.1) - force_at(pristine, 0.1)) /
                               (force_at(hardened, 0.1) - force_at(pristine, 0.1));
  const double share_deep = (force_at(thin, 1.0) - force_at(pristine, 1.0)) /
                            (force_at(hardened, 1.0) - force_at(pristine, 1.0));
  std::cout << "[ layers ] the 0.3 um layer's share of the hardening: " << share_shallow
            << " at 0.1 um, " << share_deep << " at 1 um; 10 um layer within "
            << 100 * largest_thick_difference << " % of the hardened curve" << std::endl;
  EXPECT_LT(share_deep, share_shallow);

  // The plastic zone lies in the layer while it is shallower than the layer, and the layer's
  // part of its volume falls once the zone reaches the substrate.
  double reached = 0, last_fraction = 1;
  for (const problems::StepRecord &r : thin.records)
    {
      if (!(r.plastic_zone_volume > 0))
        continue;
      const double fraction = r.plastic_zone_layer_volume / r.plastic_zone_volume;
      if (r.plastic_zone_depth < 0.3)
        EXPECT_DOUBLE_EQ(fraction, 1.) << "h = " << r.depth;
      else if (reached == 0)
        reached = r.depth;
      last_fraction = fraction;
    }
  std::cout << "[ layers ] the plastic zone reaches the substrate at h = " << reached
            << " um; at 1 um " << 100 * last_fraction << " % of it lies in the 0.3 um layer"
            << std::endl;
  EXPECT_GT(reached, 0.);
  EXPECT_LT(reached, 0.3);
  EXPECT_LT(last_fraction, 0.2);
}

// Johnson's expanding cavity (K.L. Johnson, J. Mech. Phys. Solids 18, 1970; Contact Mechanics,
// 1985, sec. 6.3): under a cone of face angle beta the plastic zone is a hemisphere of radius c
// about the contact of radius a, (c/a)^3 = E tan(beta) / (6 sigma_y (1 - nu)) + 2 (1 - 2 nu) /
// (3 (1 - nu)). Below the tip, on the axis, the zone's depth is c within 15 % at every depth from
// 0.3 um to 1 um, for the paper's sigma_y0 and twice it (c/a = 2.76 and 2.22); at the surface the
// free surface and the pile-up pull the zone's boundary in (its radius is about 0.8 c there).
TEST(PlasticZone, DepthFollowsJohnsonsExpandingCavity)
{
  for (const double yield_stress : {0.305, 0.61})
    {
      const io::Case c = layered_case({}, yield_stress);
      const double   nu = c.material.poisson_ratio, tan_beta = 1 / c.indenter.a;
      const double   johnson =
          std::cbrt(c.material.young_modulus * tan_beta / (6 * yield_stress * (1 - nu)) +
                    2 * (1 - 2 * nu) / (3 * (1 - nu)));
      const Curve &curve = homogeneous(yield_stress);
      double       lowest = 1e9, highest = 0, radius = 0;
      for (const problems::StepRecord &r : curve.records)
        {
          if (r.depth < 0.3)
            continue;
          const double ratio = r.plastic_zone_depth / r.contact_radius;
          lowest = std::min(lowest, ratio);
          highest = std::max(highest, ratio);
          radius = r.plastic_zone_radius / r.contact_radius;
          EXPECT_NEAR(ratio / johnson, 1., 0.15) << "h = " << r.depth;
        }
      std::cout << "[ plastic zone ] sigma_y0 " << yield_stress << " GPa: depth / a " << lowest
                << " ... " << highest << ", Johnson c/a " << johnson << "; radius / a at 1 um "
                << radius << std::endl;
    }
}

// A damage profile (case/DamageProfile.h) of the kind an ion beam leaves: the dose rises from 0
// at the surface to 1 dpa at 0.2 um, stays to 0.3 um and falls to 0 at 0.35 um; with
// Delta sigma_sat = sigma_y0 and d0 = 0.1 dpa the yield stress lies between the pristine
// sigma_y0 and the saturated 2 sigma_y0 everywhere. On one mesh (the profile's design, four
// elements across the damage peak's 0.225 um width at half maximum) the curve lies between the
// two homogeneous curves at every depth to 0.6 um (above the pristine one by more than the
// discretisation's noise while the indent is shallower than the profile, and within 0.2 % of it
// deeper), and the profile's share of the hardening falls as the indent goes deeper (to within
// 0.005, the curves' discretisation noise: deeper than the profile, d - p is 1.5 % of p and
// H - p 60 %, so a ripple of 0.1 % of p moves the share by 0.002). (It need not
// lie below the uniformly hard 0.35 um layer: the softer surface piles up more and widens the
// contact.)
TEST(Layers, DamageProfileLiesBetweenItsBounds)
{
  io::Case profile_case = layered_case({}, 0.305);
  profile_case.loading.max_depth = 0.6;
  profile_case.loading.steps = 40;
  io::DamageProfileParameters &profile = profile_case.material.damage_profile;
  profile.depth = {0, 0.2, 0.3, 0.35};
  profile.dpa = {0, 1, 1, 0};
  profile.law = io::DamageLaw::saturation;
  profile.saturation_increment = 0.305;
  profile.saturation_dose = 0.1;
  mesh::design_mesh(profile_case, *indenter::create_indenter(profile_case.indenter), false);
  ASSERT_NEAR(profile_case.specimen.grading.layer_element, 0.225 / 4, 1e-12); // FWHM / 4
  io::Case pristine_case = profile_case, hardened_case = profile_case;
  pristine_case.material.damage_profile = {};
  hardened_case.material.damage_profile = {};
  hardened_case.material.yield_stress = 0.61;
  const Curve damaged = run(profile_case), pristine = run(pristine_case),
              hardened = run(hardened_case);
  double previous_share = 1;
  for (const double h : {0.05, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6})
    {
      const double d = force_at(damaged, h), p = force_at(pristine, h), H = force_at(hardened, h);
      const double share = (d - p) / (H - p);
      std::cout << "[ layers ] h = " << h << " um: pristine " << p << " mN, damage profile " << d
                << " mN, hardened " << H << " mN; the profile's share of the hardening " << share
                << std::endl;
      EXPECT_GT(d, h <= 0.4 ? 1.01 * p : 0.998 * p) << "h = " << h;
      EXPECT_LT(d, H) << "h = " << h;
      EXPECT_LT(share, previous_share + 0.005) << "h = " << h;
      previous_share = share;
    }
}
