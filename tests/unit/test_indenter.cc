// The rounded-cone indenter (eq. 16) against brute force, and the Sneddon reference solution
// against its Hertz and cone limits.
#include <indenter/IndenterFactory.h>
#include <indenter/RoundedCone.h>
#include <indenter/SneddonReference.h>

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

namespace
{
  using namespace indentsim::indenter;
  using dealii::Point;
  using dealii::Tensor;

  // Eq. 16 written out independently of the code under test.
  double eq16(const double r, const double a, const double delta)
  {
    return std::sqrt(r * r / (a * a) + delta * delta) - delta;
  }

  struct BruteForceResult
  {
    double   distance;
    Point<3> closest_point;
  };

  // Closest point by exhaustive search over the surface parametrized by (r, phi) in the specimen
  // frame, followed by successive zooming of the grid: no axisymmetric reduction, no Newton.
  BruteForceResult brute_force(const Point<3> &x, const double depth, const double a,
                               const double delta)
  {
    const auto surface = [&](const double r, const double phi) {
      return Point<3>(r * std::cos(phi), r * std::sin(phi), eq16(r, a, delta) - depth);
    };
    const double scale = std::hypot(x[0], x[1]) + std::abs(x[2] + depth) + 10. * a * a * delta;
    const double r_max = 2. * scale;

    double best_r = 0., best_phi = 0., best = std::numeric_limits<double>::max();
    constexpr int n_r = 2000, n_phi = 360;
    // Quadratic spacing in r resolves the tip as well as the flank.
    for (int i = 0; i <= n_r; ++i)
      {
        const double r = r_max * (double(i) / n_r) * (double(i) / n_r);
        for (int j = 0; j < n_phi; ++j)
          {
            const double phi = 2. * std::numbers::pi * j / n_phi - std::numbers::pi;
            const double d = x.distance_square(surface(r, phi));
            if (d < best)
              best = d, best_r = r, best_phi = phi;
          }
      }
    const int i_best = int(std::round(n_r * std::sqrt(best_r / r_max)));
    double dr = r_max * (2. * std::max(i_best, 1) + 1.) / (double(n_r) * n_r);
    double dphi = 2. * std::numbers::pi / n_phi;
    for (int level = 0; level < 14; ++level)
      {
        const double r0 = best_r, phi0 = best_phi;
        for (int i = -20; i <= 20; ++i)
          for (int j = -20; j <= 20; ++j)
            {
              const double r = std::max(0., r0 + 0.1 * i * dr);
              const double phi = phi0 + 0.1 * j * dphi;
              const double d = x.distance_square(surface(r, phi));
              if (d < best)
                best = d, best_r = r, best_phi = phi;
            }
        dr *= 0.2;
        dphi *= 0.2;
      }
    return {std::sqrt(best), surface(best_r, best_phi)};
  }

  struct Geometry
  {
    double a, delta;
  };

  // Test points relative to the apex (specimen frame with the apex at (0, 0, -depth)).
  std::vector<Point<3>> probe_points(const Geometry &g)
  {
    const double R = g.a * g.a * g.delta;
    std::vector<Point<3>> points = {
      {0., 0., -0.3},                 // on the axis, outside (below the apex)
      {0., 0., -5.},                  // on the axis, far outside
      {0.01, 0.005, -0.002},          // near the apex, outside
      {-0.004, 0.003, 0.0005},        // near the apex, slightly above its level
      {0., 0., 0.3 * R},              // on the axis inside, below the centre of curvature
      {0., 0., 1.},                   // on the axis inside, above it (closest points: a circle)
      {50., 30., 20.},                // far out on the cone flank, outside
      {-400., 250., 150.},            // very far out, outside
      {5., 3., 3.},                   // inside, near the flank
      {1., 0., 5.},                   // deep inside
      {-2., -1.5, 0.5},               // outside, above the apex level, other quadrant
      {3., -4., 1.},                  // outside, above the apex level
      {0.02, -0.01, 0.0012},          // inside near the tip
      {1e-7, 0., -1e-3},              // almost on the axis
    };
    // Random points at several scales around the apex.
    std::mt19937                           generator(42);
    std::uniform_real_distribution<double> unit(-1., 1.);
    for (const double scale : {0.01, 0.2, 5.})
      for (int k = 0; k < 8; ++k)
        points.emplace_back(scale * unit(generator), scale * unit(generator),
                            scale * unit(generator));
    return points;
  }

  // Checks one projection against brute force; `depth` shifts the apex to (0, 0, -depth).
  void check_projection(const RoundedCone &cone, const Geometry &g, const Point<3> &relative,
                        const double depth)
  {
    const Point<3> x(relative[0], relative[1], relative[2] - depth);
    const SurfaceProjection p = cone.project(x, depth);
    const BruteForceResult  bf = brute_force(x, depth, g.a, g.delta);
    const double rho = std::hypot(x[0], x[1]);
    const bool   inside = relative[2] > eq16(rho, g.a, g.delta);
    const double scale = 1. + relative.norm();
    SCOPED_TRACE("a = " + std::to_string(g.a) + ", delta = " + std::to_string(g.delta) +
                 ", point relative to apex (" + std::to_string(relative[0]) + ", " +
                 std::to_string(relative[1]) + ", " + std::to_string(relative[2]) + ")");

    ASSERT_TRUE(p.converged);
    EXPECT_NEAR(p.gap, inside ? -bf.distance : bf.distance, 1e-9 * scale);

    // The closest point lies on the surface, at distance |gap| from x.
    const Point<3> &c = p.closest_point;
    EXPECT_NEAR(c[2] + depth, eq16(std::hypot(c[0], c[1]), g.a, g.delta), 1e-12 * scale);
    EXPECT_NEAR(x.distance(c), std::abs(p.gap), 1e-9 * scale);

    // Off the axis-inside medial line the closest point is unique and must match.
    const bool unique = !(rho == 0. && inside);
    if (unique)
      {
        EXPECT_LT(c.distance(bf.closest_point), 1e-6 * scale);
      }
    else
      EXPECT_NEAR(std::hypot(c[0], c[1]), std::hypot(bf.closest_point[0], bf.closest_point[1]),
                  1e-6 * scale);

    // Unit normal pointing into the specimen, along x - c when there is a gap.
    EXPECT_NEAR(p.normal.norm(), 1., 1e-12);
    EXPECT_LE(p.normal[2], 1e-15);
    // (Very near the axis the brute-force azimuth is ill-determined, so skip it there.)
    if (std::abs(bf.distance) > 1e-6 && unique && (rho == 0. || rho > 1e-4 * scale))
      {
        const Tensor<1, 3> expected =
          (x - bf.closest_point) / (inside ? -bf.distance : bf.distance);
        EXPECT_LT((p.normal - expected).norm(), 1e-5);
      }
    // Perpendicular to the surface tangents at c (where the surface is smooth).
    const double r_c = std::hypot(c[0], c[1]);
    if (g.delta > 0. || r_c > 1e-9)
      {
        const double phi = r_c > 0. ? std::atan2(c[1], c[0]) : 0.;
        const double h = 1e-6 * (r_c + g.a * g.delta + 1e-3);
        const auto surface = [&](const double r, const double ph) {
          return Point<3>(r * std::cos(ph), r * std::sin(ph), eq16(r, g.a, g.delta) - depth);
        };
        const Tensor<1, 3> t_r = (surface(r_c + h, phi) - surface(std::max(r_c - h, 0.), phi)) /
                                 (r_c + h - std::max(r_c - h, 0.));
        const Tensor<1, 3> t_phi({-std::sin(phi), std::cos(phi), 0.});
        if (r_c > h)
          {
            EXPECT_NEAR(p.normal * t_r / t_r.norm(), 0., 1e-6);
          }
        else // at the rounded apex the tangent plane is horizontal
          EXPECT_NEAR(p.normal[2], -1., 1e-6);
        EXPECT_NEAR(p.normal * t_phi, 0., 1e-9);
      }
  }
} // namespace

// Gap, closest point and normal of the paper's rounded cone agree with brute force everywhere.
TEST(RoundedCone, ProjectionMatchesBruteForce)
{
  const Geometry   g{2.48, 0.005};
  const RoundedCone cone(g.a, g.delta);
  for (const double depth : {0., 1.7})
    for (const auto &point : probe_points(g))
      check_projection(cone, g, point, depth);
}

// The projection is also exact for a blunt tip, where the rounding is large.
TEST(RoundedCone, ProjectionMatchesBruteForceBluntTip)
{
  const Geometry   g{1.2, 0.5};
  const RoundedCone cone(g.a, g.delta);
  for (const auto &point : probe_points(g))
    check_projection(cone, g, point, 0.4);
}

// delta = 0 (a sharp cone, allowed by the case file) is projected exactly, apex included.
TEST(RoundedCone, ProjectionMatchesBruteForceSharpCone)
{
  const Geometry   g{2.48, 0.};
  const RoundedCone cone(g.a, g.delta);
  for (const auto &point : probe_points(Geometry{2.48, 0.005}))
    check_projection(cone, g, point, 0.3);
}

// The apex and the axis are handled exactly: apex foot below the tip and up to the curvature centre.
TEST(RoundedCone, AxisPointsAreExact)
{
  const double      a = 2.48, delta = 0.005, depth = 2.;
  const RoundedCone cone(a, delta);
  // Below the apex: closest point is the apex, gap the distance, normal straight down.
  auto p = cone.project(Point<3>(0., 0., -depth - 0.25), depth);
  EXPECT_TRUE(p.converged);
  EXPECT_DOUBLE_EQ(p.gap, 0.25);
  EXPECT_EQ(p.closest_point, Point<3>(0., 0., -depth));
  EXPECT_DOUBLE_EQ(p.normal[2], -1.);
  // Inside on the axis but below the centre of curvature (R = a^2 delta): still the apex.
  const double R = a * a * delta;
  p = cone.project(Point<3>(0., 0., -depth + 0.9 * R), depth);
  EXPECT_NEAR(p.gap, -0.9 * R, 1e-15 * depth);
  EXPECT_EQ(p.closest_point, Point<3>(0., 0., -depth));
  // Exactly on the surface: zero gap, the point itself.
  const Point<3> on_surface(0.6, -0.8, eq16(1., a, delta) - depth);
  p = cone.project(on_surface, depth);
  EXPECT_NEAR(p.gap, 0., 1e-14);
  EXPECT_LT(p.closest_point.distance(on_surface), 1e-13);
}

// profile() is eq. 16, accurate even where the naive formula cancels.
TEST(RoundedCone, ProfileIsEq16)
{
  const double      a = 2.48, delta = 0.005;
  const RoundedCone cone(a, delta);
  for (const double r : {0., 0.001, 0.1, 1., 37.})
    EXPECT_NEAR(cone.profile(r * 0.6, r * 0.8), eq16(r, a, delta), 1e-14 * (1. + r));
  // For r << a delta: f = r^2 / (2 a^2 delta) (1 - r^2/(4 a^2 delta^2) + ...).
  const double r = 1e-7;
  const double series = r * r / (2. * a * a * delta) * (1. - r * r / (4. * a * a * delta * delta));
  EXPECT_NEAR(cone.profile(r, 0.) / series, 1., 1e-12);
  EXPECT_DOUBLE_EQ(cone.tip_radius(), a * a * delta);
  EXPECT_DOUBLE_EQ(cone.half_angle(), std::atan(a));
}

// projected_area(h) is pi r(h)^2 with r(h) the radius where the profile reaches h.
TEST(RoundedCone, ProjectedAreaIsPiRSquared)
{
  const double      a = 2.48, delta = 0.005;
  const RoundedCone cone(a, delta);
  for (const double h : {1e-6, 1e-3, 0.005, 0.1, 6.})
    {
      // Bisection on the independent eq16 for r(h).
      double lo = 0., hi = 10. * a * (h + delta) + 1.;
      for (int i = 0; i < 200; ++i)
        {
          const double mid = 0.5 * (lo + hi);
          (eq16(mid, a, delta) < h ? lo : hi) = mid;
        }
      const double r = 0.5 * (lo + hi);
      EXPECT_NEAR(cone.projected_area(h) / (std::numbers::pi * r * r), 1., 1e-10) << "h = " << h;
    }
  EXPECT_EQ(cone.projected_area(0.), 0.);
  EXPECT_EQ(cone.projected_area(-1.), 0.);
  // Far from the tip it approaches the cone's pi tan^2(alpha) (h + delta)^2.
  EXPECT_NEAR(cone.projected_area(100.) / (std::numbers::pi * a * a * 100.005 * 100.005), 1., 1e-8);
}

// The factory builds the shape named in the case and rejects unknown shapes.
TEST(IndenterFactory, CreatesRoundedCone)
{
  indentsim::io::IndenterParameters parameters;
  const auto indenter = create_indenter(parameters);
  ASSERT_NE(indenter, nullptr);
  EXPECT_EQ(indenter->name(), "rounded_cone");
  EXPECT_NEAR(indenter->profile(1., 0.), eq16(1., parameters.a, parameters.delta), 1e-15);
  parameters.shape = "vickers";
  EXPECT_THROW(create_indenter(parameters), std::invalid_argument);
  EXPECT_THROW(RoundedCone(0., 0.005), std::invalid_argument);
  EXPECT_THROW(RoundedCone(2.48, -0.1), std::invalid_argument);
}

// For h << delta the Sneddon solution is Hertz's sphere with R = A^2 delta.
TEST(SneddonReference, HertzLimit)
{
  const double           E_star = SneddonReference::reduced_modulus(69., 0.26);
  const double           A = 2.48, delta = 0.005, R = A * A * delta;
  const SneddonReference reference(E_star, A, delta);
  const double           h = 1e-4 * delta;
  const double           hertz = 4. / 3. * E_star * std::sqrt(R) * std::pow(h, 1.5);
  EXPECT_NEAR(reference.force_at_depth(h) / hertz, 1., 1e-3);
  EXPECT_NEAR(reference.contact_radius_at_depth(h) / std::sqrt(R * h), 1., 1e-3);
  // ... and the approach to Hertz is from above, at rate O(h/delta).
  const double deviation = reference.force_at_depth(h) / hertz - 1.;
  EXPECT_GT(deviation, 0.);
  EXPECT_LT(deviation, 1e-3);
}

// For delta -> 0 it is Sneddon's cone, P = (2/pi) E* tan(alpha) h^2; delta = 0 exactly too.
TEST(SneddonReference, ConeLimit)
{
  const double E_star = 74.;
  const double A = 2.48;
  for (const double delta : {1e-9, 0.})
    {
      const SneddonReference reference(E_star, A, delta);
      for (const double h : {0.5, 6.})
        {
          const double cone = 2. / std::numbers::pi * E_star * A * h * h;
          EXPECT_NEAR(reference.force_at_depth(h) / cone, 1., 1e-6) << delta << " " << h;
          EXPECT_NEAR(reference.contact_radius_at_depth(h) / (2. * A * h / std::numbers::pi), 1.,
                      1e-6);
        }
    }
}

// The stiffness 2 E* a_c is the derivative of the force with respect to depth.
TEST(SneddonReference, StiffnessIsDerivativeOfForce)
{
  const double           E_star = 74., A = 2.48, delta = 0.005;
  const SneddonReference reference(E_star, A, delta);
  for (const double h_over_delta : {0.01, 0.1, 1., 10., 1000.})
    {
      const double h = h_over_delta * delta;
      const double dh = 1e-5 * h;
      const double dP_dh =
        (reference.force_at_depth(h + dh) - reference.force_at_depth(h - dh)) / (2. * dh);
      EXPECT_NEAR(reference.stiffness_at_depth(h) / dP_dh, 1., 1e-7) << "h/delta = " << h_over_delta;
    }
}

// The contact radius inverts h(a_c), and the force is continuous where its series takes over.
TEST(SneddonReference, InversionAndContinuity)
{
  const double           E_star = 74., A = 2.48, delta = 0.005, c = A * delta;
  const SneddonReference reference(E_star, A, delta);
  for (const double h : {1e-9, 1e-5, 0.003, 0.2, 6., 500.})
    {
      const double a_c = reference.contact_radius_at_depth(h);
      EXPECT_NEAR(a_c / A * std::atan(a_c / c) / h, 1., 1e-13) << h;
    }
  // The closed form (x^2 - 1) atan x + x and its small-x series meet at x = 0.1.
  const double below = reference.force_at_contact_radius(0.1 * c * (1. - 1e-12));
  const double above = reference.force_at_contact_radius(0.1 * c * (1. + 1e-12));
  EXPECT_NEAR(above / below, 1., 1e-9);
  // A direct evaluation at moderate x, where the closed form does not cancel.
  const double x = 2.;
  EXPECT_NEAR(reference.force_at_contact_radius(x * c),
              E_star / A * ((x * x - 1.) * c * c * std::atan(x) + x * c * c), 1e-12);
  EXPECT_EQ(reference.force_at_depth(0.), 0.);
}
