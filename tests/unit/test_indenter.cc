// The rounded-cone indenter (eq. 16) against brute force, the Sneddon reference solution
// against its Hertz and cone limits, and the indenter library (sphere, cone, Vickers and
// Berkovich pyramids, flat punch, profile table) against brute force and area functions.
#include "indenter/Cone.h"
#include "indenter/FlatPunch.h"
#include "indenter/IndenterFactory.h"
#include "indenter/ProfileTable.h"
#include "indenter/Pyramid.h"
#include "indenter/RoundedCone.h"
#include "indenter/SneddonReference.h"
#include "indenter/Sphere.h"

#include "../test_files.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <numbers>
#include <random>
#include <string>
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

    double        best_r = 0., best_phi = 0., best = std::numeric_limits<double>::max();
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
    double    dr = r_max * (2. * std::max(i_best, 1) + 1.) / (double(n_r) * n_r);
    double    dphi = 2. * std::numbers::pi / n_phi;
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
    const double          R = g.a * g.a * g.delta;
    std::vector<Point<3>> points = {
        {0., 0., -0.3},          // on the axis, outside (below the apex)
        {0., 0., -5.},           // on the axis, far outside
        {0.01, 0.005, -0.002},   // near the apex, outside
        {-0.004, 0.003, 0.0005}, // near the apex, slightly above its level
        {0., 0., 0.3 * R},       // on the axis inside, below the centre of curvature
        {0., 0., 1.},            // on the axis inside, above it (closest points: a circle)
        {50., 30., 20.},         // far out on the cone flank, outside
        {-400., 250., 150.},     // very far out, outside
        {5., 3., 3.},            // inside, near the flank
        {1., 0., 5.},            // deep inside
        {-2., -1.5, 0.5},        // outside, above the apex level, other quadrant
        {3., -4., 1.},           // outside, above the apex level
        {0.02, -0.01, 0.0012},   // inside near the tip
        {1e-7, 0., -1e-3},       // almost on the axis
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
    const Point<3>          x(relative[0], relative[1], relative[2] - depth);
    const SurfaceProjection p = cone.project(x, depth);
    const BruteForceResult  bf = brute_force(x, depth, g.a, g.delta);
    const double            rho = std::hypot(x[0], x[1]);
    const bool              inside = relative[2] > eq16(rho, g.a, g.delta);
    const double            scale = 1. + relative.norm();
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
        const auto   surface = [&](const double r, const double ph) {
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
  const Geometry    g{2.48, 0.005};
  const RoundedCone cone(g.a, g.delta);
  for (const double depth : {0., 1.7})
    for (const auto &point : probe_points(g))
      check_projection(cone, g, point, depth);
}

// The projection is also exact for a blunt tip, where the rounding is large.
TEST(RoundedCone, ProjectionMatchesBruteForceBluntTip)
{
  const Geometry    g{1.2, 0.5};
  const RoundedCone cone(g.a, g.delta);
  for (const auto &point : probe_points(g))
    check_projection(cone, g, point, 0.4);
}

// delta = 0 (a sharp cone, allowed by the case file) is projected exactly, apex included.
TEST(RoundedCone, ProjectionMatchesBruteForceSharpCone)
{
  const Geometry    g{2.48, 0.};
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
  const auto                        indenter = create_indenter(parameters);
  ASSERT_NE(indenter, nullptr);
  EXPECT_EQ(indenter->name(), "rounded_cone");
  EXPECT_NEAR(indenter->profile(1., 0.), eq16(1., parameters.a, parameters.delta), 1e-15);
  parameters.shape = "knoop"; // not (yet) in the library
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
      EXPECT_NEAR(reference.stiffness_at_depth(h) / dP_dh, 1., 1e-7)
          << "h/delta = " << h_over_delta;
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

// ---------------------------------------------------------------------------------------------
// The indenter library. Every oracle below is written from the shape's definition (face angles,
// radii, the rounded solid = sharp solid + ball), independently of the projection code.

namespace
{
  using namespace indentsim::indenter;
  using dealii::Point;
  using dealii::Tensor;

  constexpr double pi = std::numbers::pi;
  constexpr double infinity = std::numeric_limits<double>::infinity();

  double radians(const double degrees)
  {
    return degrees * pi / 180.;
  }

  // A continuous map of [0, 1]^2 onto part of an indenter surface, in the indenter frame (apex
  // at the origin). The patches of a shape together cover its surface up to a given extent.
  using Patch = std::function<Point<3>(double, double)>;

  struct Nearest
  {
    double   distance;
    Point<3> point;
  };

  // Closest point by exhaustive search: an n x n grid on every patch, then successive zooming
  // from the best few grid-local minima of each patch. No projection formula is involved.
  Nearest brute_force(const std::vector<Patch> &patches, const Point<3> &q, const int n = 120)
  {
    double              best = infinity;
    Point<3>            best_point;
    std::vector<double> grid((n + 1) * (n + 1));
    for (const Patch &patch : patches)
      {
        for (int i = 0; i <= n; ++i)
          for (int j = 0; j <= n; ++j)
            grid[i * (n + 1) + j] = q.distance_square(patch(double(i) / n, double(j) / n));
        // Grid-local minima, best first.
        std::vector<std::pair<double, int>> minima;
        for (int i = 0; i <= n; ++i)
          for (int j = 0; j <= n; ++j)
            {
              const double value = grid[i * (n + 1) + j];
              bool         minimum = true;
              for (int di = -1; di <= 1 && minimum; ++di)
                for (int dj = -1; dj <= 1 && minimum; ++dj)
                  if (i + di >= 0 && i + di <= n && j + dj >= 0 && j + dj <= n)
                    minimum = grid[(i + di) * (n + 1) + j + dj] >= value;
              if (minimum)
                minima.emplace_back(value, i * (n + 1) + j);
            }
        std::sort(minima.begin(), minima.end());
        for (std::size_t m = 0; m < std::min<std::size_t>(minima.size(), 4); ++m)
          {
            double u = double(minima[m].second / (n + 1)) / n;
            double v = double(minima[m].second % (n + 1)) / n;
            double value = minima[m].first;
            double step = 1. / n;
            for (int level = 0; level < 32; ++level)
              {
                const double u0 = u, v0 = v;
                for (int i = -10; i <= 10; ++i)
                  for (int j = -10; j <= 10; ++j)
                    {
                      const double ui = std::clamp(u0 + 0.2 * i * step, 0., 1.);
                      const double vj = std::clamp(v0 + 0.2 * j * step, 0., 1.);
                      const double d = q.distance_square(patch(ui, vj));
                      if (d < value)
                        value = d, u = ui, v = vj;
                    }
                step *= 0.3;
              }
            if (value < best)
              best = value, best_point = patch(u, v);
          }
      }
    return {std::sqrt(best), best_point};
  }

  Point<3> on_circle(const double radius, const double azimuth, const double height)
  {
    return Point<3>(radius * std::cos(azimuth), radius * std::sin(azimuth), height);
  }

  // Sphere of radius R: lower hemisphere about the centre (0, 0, R), then the vertical shank.
  std::vector<Patch> sphere_patches(const double R, const double extent)
  {
    return {[=](double u, double v) {
              const double polar = u * pi / 2.;
              return on_circle(R * std::sin(polar), 2. * pi * v, R - R * std::cos(polar));
            },
            [=](double u, double v) { return on_circle(R, 2. * pi * v, R + u * extent); }};
  }

  // Cone of half-angle alpha with a spherical tip of radius R tangent to the flank.
  std::vector<Patch> cone_patches(const double alpha, const double R, const double extent)
  {
    return {[=](double u, double v) {
              const double polar = u * (pi / 2. - alpha);
              return on_circle(R * std::sin(polar), 2. * pi * v, R - R * std::cos(polar));
            },
            [=](double u, double v) {
              const double s = u * u * extent; // resolves the tip as well as the flank
              return on_circle(R * std::cos(alpha) + s * std::sin(alpha), 2. * pi * v,
                               R * (1. - std::sin(alpha)) + s * std::cos(alpha));
            }};
  }

  // A regular pyramid from its definition: face i has the outward normal
  // (cos theta cos phi_i, cos theta sin phi_i, -sin theta), phi_i = rotation + i 360/n; edges
  // are the intersections of neighbouring faces. Rounded by R: the faces moved by R along their
  // normals, cylinders of radius R around the edges, a sphere of radius R around the apex.
  struct PyramidGeometry
  {
    unsigned int              n;
    double                    theta, R, rotation_deg;
    std::vector<Tensor<1, 3>> normals, edges;

    PyramidGeometry(const unsigned int n_faces, const double theta_deg, const double tip_radius,
                    const double rotation)
      : n(n_faces)
      , theta(radians(theta_deg))
      , R(tip_radius)
      , rotation_deg(rotation)
    {
      for (unsigned int i = 0; i < n; ++i)
        {
          const double phi = radians(rotation + 360. * i / n);
          normals.push_back(Tensor<1, 3>({std::cos(theta) * std::cos(phi),
                                          std::cos(theta) * std::sin(phi), -std::sin(theta)}));
        }
      for (unsigned int k = 0; k < n; ++k)
        {
          Tensor<1, 3> e = dealii::cross_product_3d(normals[k], normals[(k + 1) % n]);
          e /= e.norm();
          edges.push_back(e[2] > 0. ? e : -e);
        }
    }

    std::vector<Patch> patches(const double extent) const
    {
      const Point<3>     apex(0., 0., R);
      std::vector<Patch> result;
      for (unsigned int i = 0; i < n; ++i)
        {
          const Tensor<1, 3> a = edges[(i + n - 1) % n], b = edges[i], normal = normals[i];
          result.push_back([=, this](double u, double v) {
            return apex + R * normal + extent * (u * a + v * b);
          });
        }
      for (unsigned int k = 0; k < n; ++k)
        {
          const Tensor<1, 3> e = edges[k], n0 = normals[k], n1 = normals[(k + 1) % n];
          const double       angle = std::acos(std::clamp(n0 * n1, -1., 1.));
          result.push_back([=, this](double u, double v) {
            const Tensor<1, 3> arc =
                (std::sin((1. - v) * angle) * n0 + std::sin(v * angle) * n1) / std::sin(angle);
            return apex + u * extent * e + R * arc;
          });
        }
      if (R > 0.)
        result.push_back([=, this](double u, double v) {
          Tensor<1, 3> w;
          if (n == 4)
            w = (1. - u) * (1. - v) * normals[0] + u * (1. - v) * normals[1] + u * v * normals[2] +
                (1. - u) * v * normals[3];
          else
            w = (1. - u) * normals[0] + u * ((1. - v) * normals[1] + v * normals[2]);
          return apex + R * w / w.norm();
        });
      return result;
    }
  };

  // Flat punch of radius a, rim rounded with e: flat end, quarter torus, wall.
  std::vector<Patch> flat_punch_patches(const double a, const double e, const double extent)
  {
    std::vector<Patch> result = {
        [=](double u, double v) { return on_circle(u * (a - e), 2. * pi * v, 0.); },
        [=](double u, double v) { return on_circle(a, 2. * pi * v, e + u * extent); }};
    if (e > 0.)
      result.push_back([=](double u, double v) {
        const double angle = u * pi / 2.;
        return on_circle(a - e + e * std::sin(angle), 2. * pi * v, e - e * std::cos(angle));
      });
    return result;
  }

  // A tabulated profile as a surface of revolution of the code's own z(r) (the interpolation
  // itself is checked against analytic shapes elsewhere).
  std::vector<Patch> table_patches(const ProfileTable &table, const double extent)
  {
    return {[&table, extent](double u, double v) {
      const double r = u * u * extent;
      return on_circle(r, 2. * pi * v, table.profile_at_radius(r));
    }};
  }

  // A shape under test with its independent oracle.
  struct ShapeCase
  {
    std::string                               label;
    const IndenterSurface                    *surface;
    std::function<std::vector<Patch>(double)> patches; // of the extent
    double                                    scale;   // size of the tip features [um]
    // Distance of a point from the surface, in the oracle's own terms where that is simple.
    std::function<double(const Point<3> &)> surface_residual;
  };

  // |z - profile(x, y)| where the surface is a graph, else the distance from a wall of radius
  // `wall` that starts at `wall_bottom`.
  std::function<double(const Point<3> &)> graph_residual(const IndenterSurface *surface,
                                                         const double           wall = infinity,
                                                         const double wall_bottom = infinity)
  {
    return [=](const Point<3> &c) {
      const double r = std::hypot(c[0], c[1]);
      double       residual = std::abs(c[2] - surface->profile(c[0], c[1]));
      if (c[2] >= wall_bottom - 1e-12 * (1. + wall_bottom))
        residual = std::min(residual, std::abs(r - wall));
      return residual;
    };
  }

  // Checks project() at the point q (indenter frame) with the apex at depth `depth`.
  void check_against_brute_force(const ShapeCase &shape, const Point<3> &q, const double depth,
                                 double &max_gap_error)
  {
    const double            size = q.norm() + 3. * shape.scale + 1e-3;
    const Point<3>          x(q[0], q[1], q[2] - depth); // specimen frame
    const SurfaceProjection p = shape.surface->project(x, depth);
    const Nearest           bf = brute_force(shape.patches(2. * size + 1.), q);
    const bool              inside = q[2] > shape.surface->profile(q[0], q[1]);
    const double            tolerance = 1e-9 * (1. + q.norm());
    SCOPED_TRACE(shape.label + ", point (" + std::to_string(q[0]) + ", " + std::to_string(q[1]) +
                 ", " + std::to_string(q[2]) + ") relative to the apex" +
                 (inside ? ", inside" : ", outside"));

    ASSERT_TRUE(p.converged);
    EXPECT_NEAR(p.gap, inside ? -bf.distance : bf.distance, tolerance);
    max_gap_error = std::max(max_gap_error, std::abs(p.gap - (inside ? -1. : 1.) * bf.distance));

    // The closest point lies on the surface, |gap| away from x: with the gap equal to the
    // brute-force distance it is a closest point (ties inside allow several).
    Point<3> c = p.closest_point;
    c[2] += depth;
    EXPECT_LT(shape.surface_residual(c), 1e-10 * (1. + q.norm()));
    EXPECT_NEAR(x.distance(p.closest_point), std::abs(p.gap), tolerance);
    // Outside a convex shape the closest point is unique.
    if (!inside && shape.label.find("table") == std::string::npos)
      {
        EXPECT_LT(c.distance(bf.point), 1e-6 * (1. + q.norm()));
      }

    // Unit normal, pointing into the specimen, along x - c.
    EXPECT_NEAR(p.normal.norm(), 1., 1e-12);
    EXPECT_LE(p.normal[2], 1e-15);
    if (std::abs(p.gap) > 1e-6 * (1. + q.norm()))
      {
        const Tensor<1, 3> along = (x - p.closest_point) / p.gap;
        EXPECT_LT((p.normal - along).norm(), 1e-8);
      }
    if (bf.distance > 1e-3 * size)
      {
        const Tensor<1, 3> expected = (q - bf.point) / (inside ? -bf.distance : bf.distance);
        if (!inside ||
            (p.closest_point + Tensor<1, 3>({0., 0., depth})).distance(bf.point) < 1e-6 * size)
          {
            EXPECT_LT((p.normal - expected).norm(), 1e-5);
          }
      }
  }

  // Points around the tip at several scales, plus points within 5 % of `scale` of the surface
  // on both sides (random surface points of the oracle's patches, moved randomly).
  std::vector<Point<3>> probe_points(const ShapeCase &shape, const unsigned int seed,
                                     const unsigned int n_random = 12,
                                     const unsigned int n_near = 16)
  {
    std::mt19937                           generator(seed);
    std::uniform_real_distribution<double> unit(-1., 1.), fraction(0., 1.);
    const double                           S = shape.scale;
    std::vector<Point<3>>                  points = {
                         {0., 0., -0.5 * S}, {0., 0., 0.2 * S}, {0., 0., 3. * S}, {0.3 * S, 0.1 * S, -0.01 * S}};
    for (unsigned int k = 0; k < n_random; ++k)
      {
        const double size = S * std::pow(10., 1.5 * fraction(generator) - 0.5);
        points.emplace_back(size * unit(generator), size * unit(generator),
                            size * (0.5 + unit(generator)));
      }
    const auto patches = shape.patches(3. * S);
    for (unsigned int k = 0; k < n_near; ++k)
      {
        const Patch   &patch = patches[generator() % patches.size()];
        const Point<3> on = patch(fraction(generator), fraction(generator));
        points.push_back(
            on + 0.05 * S * Tensor<1, 3>({unit(generator), unit(generator), unit(generator)}));
      }
    return points;
  }

  void check_shape(const ShapeCase &shape, const unsigned int seed)
  {
    double max_gap_error = 0.;
    for (const double depth : {0., 1.3})
      for (const Point<3> &q : probe_points(shape, seed))
        check_against_brute_force(shape, q, depth, max_gap_error);
    std::cout << "[ brute force ] " << shape.label
              << ": max |gap - brute force| = " << max_gap_error << " um\n";
  }

  // Area of {(x, y): profile(x, y) < h} by the polar integral of r(phi)^2 / 2, r(phi) found by
  // bisection on the profile, integrated by adaptive Simpson quadrature (which resolves the
  // small rounded corners by itself) on `n_sectors` equal sectors starting at `first_break`
  // (place the breaks on polygon corners).
  double polar_area(const IndenterSurface &surface, const double h, const unsigned int n_sectors,
                    const double first_break, const double relative_tolerance = 1e-12)
  {
    const auto integrand = [&](const double phi) {
      const double c = std::cos(phi), s = std::sin(phi);
      double       lo = 0., hi = 1e-3 + h;
      while (surface.profile(hi * c, hi * s) < h)
        hi *= 2.;
      for (int i = 0; i < 64; ++i)
        {
          const double mid = 0.5 * (lo + hi);
          (surface.profile(mid * c, mid * s) < h ? lo : hi) = mid;
        }
      const double r = 0.5 * (lo + hi);
      return 0.5 * r * r;
    };
    const double width = 2. * pi / n_sectors;
    const double tolerance = relative_tolerance * integrand(first_break) * width;
    const std::function<double(double, double, double, double, double, double, int)> adaptive =
        [&](const double a, const double b, const double fa, const double fm, const double fb,
            const double whole, const int depth) {
          const double m = 0.5 * (a + b);
          const double flm = integrand(0.5 * (a + m)), frm = integrand(0.5 * (m + b));
          const double left = (m - a) / 6. * (fa + 4. * flm + fm);
          const double right = (b - m) / 6. * (fm + 4. * frm + fb);
          if (depth >= 40 || std::abs(left + right - whole) <= 15. * tolerance * (b - a) / width)
            return left + right + (left + right - whole) / 15.;
          return adaptive(a, m, fa, flm, fm, left, depth + 1) +
                 adaptive(m, b, fm, frm, fb, right, depth + 1);
        };
    double area = 0.;
    for (unsigned int sector = 0; sector < n_sectors; ++sector)
      {
        // Start from 16 panels so that no feature hides between the first samples.
        for (int panel = 0; panel < 16; ++panel)
          {
            const double a = first_break + sector * width + panel * width / 16.;
            const double b = a + width / 16.;
            const double fa = integrand(a), fm = integrand(0.5 * (a + b)), fb = integrand(b);
            area += adaptive(a, b, fa, fm, fb, (b - a) / 6. * (fa + 4. * fm + fb), 0);
          }
      }
    return area;
  }
} // namespace

// Sphere: gap, closest point and normal agree with brute force on the cap and the shank.
TEST(IndenterSphere, ProjectionMatchesBruteForce)
{
  const double R = 2.;
  const Sphere sphere(R);
  check_shape({"sphere R = 2", &sphere, [=](double extent) { return sphere_patches(R, extent); }, R,
               graph_residual(&sphere, R, R)},
              1);
}

// Cone: exact for the sharp cone (apex included) and the spherical tip.
TEST(IndenterCone, ProjectionMatchesBruteForce)
{
  for (const double R : {0., 0.3})
    {
      const double alpha = radians(70.3);
      const Cone   cone(70.3, R);
      check_shape({"cone alpha = 70.3 deg, R = " + std::to_string(R), &cone,
                   [=](double extent) { return cone_patches(alpha, R, extent); }, std::max(R, 0.2),
                   graph_residual(&cone)},
                  2);
    }
}

// Pyramids: exact flat faces, edges and apex, sharp and rounded, rotated, both kinds.
TEST(IndenterPyramid, ProjectionMatchesBruteForce)
{
  struct Variant
  {
    unsigned int n;
    double       theta, R, rotation;
  };
  for (const Variant &v :
       {Variant{4, 68., 0., 0.}, Variant{4, 68., 0.2, 0.}, Variant{4, 68., 0.2, 30.},
        Variant{3, 65.27, 0., 0.}, Variant{3, 65.27, 0.2, -17.}})
    {
      const Pyramid pyramid(v.n == 4 ? "vickers" : "berkovich", v.n, v.theta, v.R, v.rotation);
      const PyramidGeometry geometry(v.n, v.theta, v.R, v.rotation);
      check_shape({pyramid.name() + " R = " + std::to_string(v.R) + ", rotation " +
                       std::to_string(v.rotation) + " deg",
                   &pyramid, [geometry](double extent) { return geometry.patches(extent); },
                   std::max(v.R, 0.2), graph_residual(&pyramid)},
                  3 + v.n);
    }
}

// Flat punch: flat end, sharp or rounded rim, wall.
TEST(IndenterFlatPunch, ProjectionMatchesBruteForce)
{
  for (const double e : {0., 0.25})
    {
      const double    a = 1.;
      const FlatPunch punch(a, e);
      check_shape({"flat punch a = 1, e = " + std::to_string(e), &punch,
                   [=](double extent) { return flat_punch_patches(a, e, extent); }, a,
                   graph_residual(&punch, a, e)},
                  7);
    }
}

// The pyramid's closed-form profile (sharp) and Newton profile (rounded) lie on the surface.
TEST(IndenterPyramid, ProfileLiesOnTheSurface)
{
  for (const double R : {0., 0.2})
    {
      const PyramidGeometry                  geometry(4, 68., R, 30.);
      const Pyramid                          pyramid("vickers", 4, 68., R, 30.);
      std::mt19937                           generator(11);
      std::uniform_real_distribution<double> unit(-1., 1.);
      for (int k = 0; k < 20; ++k)
        {
          const double   x = 2. * unit(generator), y = 2. * unit(generator);
          const Point<3> on(x, y, pyramid.profile(x, y));
          EXPECT_LT(brute_force(geometry.patches(10.), on).distance, 1e-10)
              << "R = " << R << " at (" << x << ", " << y << ")";
        }
    }
}

// Vickers: A = 4 tan^2(68 deg) h^2 = 24.504 h^2, and the area of {profile < h} agrees.
TEST(IndenterPyramid, VickersAreaFunction)
{
  const Pyramid vickers = Pyramid::vickers(0., 0.);
  const double  coefficient = 4. * std::pow(std::tan(radians(68.)), 2);
  for (const double h : {1e-3, 0.5, 6.})
    {
      EXPECT_NEAR(vickers.projected_area(h) / (h * h), coefficient, 1e-12);
      EXPECT_NEAR(vickers.projected_area(h) / (h * h), 24.504, 5e-4);
      const double polar = polar_area(vickers, h, 4, radians(45.));
      EXPECT_NEAR(polar / vickers.projected_area(h), 1., 1e-12) << "h = " << h;
      std::cout << "[ area ] Vickers h = " << h
                << ": A / h^2 = " << vickers.projected_area(h) / (h * h)
                << ", A / 24.504 h^2 - 1 = " << vickers.projected_area(h) / (24.504 * h * h) - 1.
                << ", area of {profile < h} / A - 1 = " << polar / vickers.projected_area(h) - 1.
                << "\n";
    }
  EXPECT_EQ(vickers.projected_area(0.), 0.);
  EXPECT_EQ(vickers.projected_area(-1.), 0.);
  // A rotation does not change the area.
  EXPECT_NEAR(Pyramid::vickers(0., 30.).projected_area(2.), vickers.projected_area(2.), 1e-12);
  EXPECT_NEAR(polar_area(Pyramid::vickers(0., 30.), 2., 4, radians(75.)),
              vickers.projected_area(2.), 1e-10 * vickers.projected_area(2.));
}

// Berkovich: A = 3 sqrt(3) tan^2(65.27 deg) h^2 = 24.494 h^2 exactly for the flat faces.
TEST(IndenterPyramid, BerkovichAreaFunction)
{
  const Pyramid berkovich = Pyramid::berkovich(0., 0.);
  const double  coefficient = 3. * std::sqrt(3.) * std::pow(std::tan(radians(65.27)), 2);
  for (const double h : {1e-3, 0.5, 6.})
    {
      EXPECT_NEAR(berkovich.projected_area(h) / (h * h), coefficient, 1e-12);
      const double polar = polar_area(berkovich, h, 3, radians(60.));
      EXPECT_NEAR(polar / berkovich.projected_area(h), 1., 1e-12) << "h = " << h;
      std::cout << "[ area ] Berkovich h = " << h
                << ": A / h^2 = " << berkovich.projected_area(h) / (h * h)
                << ", A / 24.56 h^2 - 1 = " << berkovich.projected_area(h) / (24.56 * h * h) - 1.
                << ", area of {profile < h} / A - 1 = " << polar / berkovich.projected_area(h) - 1.
                << "\n";
    }
  // The handbook's 24.56 h^2 is 3 sqrt(3) tan^2(65.3 deg), the rounded angle of the original
  // design; 65.27 deg was chosen later so that the Berkovich area function equals the Vickers
  // one (24.50 h^2). The exact faces at 65.27 deg give 24.494 h^2, 0.27 % below 24.56.
  const double ratio = berkovich.projected_area(1.) / 24.56;
  EXPECT_LT(std::abs(ratio - 1.), 3e-3);
  EXPECT_GT(std::abs(ratio - 1.), 2e-3) << "the faces are not at 65.3 deg";
  EXPECT_NEAR(3. * std::sqrt(3.) * std::pow(std::tan(radians(65.3)), 2) / 24.56, 1., 1e-4);
}

// Cone pi tan^2(alpha) h^2, sphere pi (2 R h - h^2), flat punch pi a^2.
TEST(IndenterLibrary, AxisymmetricAreaFunctions)
{
  const double    alpha = radians(70.3);
  const Cone      cone(70.3, 0.);
  const Sphere    sphere(3.);
  const FlatPunch punch(2., 0.);
  for (const double h : {1e-4, 0.2, 2.9})
    {
      EXPECT_NEAR(cone.projected_area(h) / (pi * std::pow(std::tan(alpha) * h, 2)), 1., 1e-13);
      EXPECT_NEAR(sphere.projected_area(h) / (pi * (2. * 3. * h - h * h)), 1., 1e-13);
      EXPECT_DOUBLE_EQ(punch.projected_area(h), pi * 4.);
      EXPECT_NEAR(polar_area(sphere, h, 1, 0.) / sphere.projected_area(h), 1., 1e-10);
      EXPECT_NEAR(polar_area(cone, h, 1, 0.) / cone.projected_area(h), 1., 1e-10);
    }
  EXPECT_DOUBLE_EQ(sphere.projected_area(5.), pi * 9.) << "beyond the equator: the shank";
  for (const IndenterSurface *surface :
       {static_cast<const IndenterSurface *>(&cone), static_cast<const IndenterSurface *>(&sphere),
        static_cast<const IndenterSurface *>(&punch)})
    EXPECT_EQ(surface->projected_area(0.), 0.) << surface->name();
}

// Rounded shapes: the offset faces lie Delta = R (1/sin(theta) - 1) below the sharp ones, so
// beyond the tip A(h) = A_sharp(h + Delta) (cone) and A_sharp(h + Delta) - n D (pyramids, D the
// corner area cut off by each rounded edge). Checked against the area of {profile < h}, and
// the relative excess over the sharp area is 2 Delta / h to first order.
TEST(IndenterLibrary, RoundedShapesApproachTheSharpAreaFunction)
{
  const double R = 0.1;
  {
    const Cone   rounded(70.3, R), sharp(70.3, 0.);
    const double alpha = radians(70.3), Delta = R * (1. / std::sin(alpha) - 1.);
    EXPECT_NEAR(rounded.blunting_offset(), Delta, 1e-15);
    for (const double h : {0.5 * R * (1. - std::sin(alpha)), 0.05, 0.3, 2.})
      EXPECT_NEAR(polar_area(rounded, h, 1, 0.) / rounded.projected_area(h), 1., 1e-10)
          << "h = " << h;
    for (const double h : {1., 10., 100.})
      EXPECT_NEAR(rounded.projected_area(h) / sharp.projected_area(h + Delta), 1., 1e-13);
    const double h = 100. * R;
    EXPECT_NEAR(rounded.projected_area(h) / sharp.projected_area(h) - 1., 2. * Delta / h,
                2. * std::pow(Delta / h, 2));
  }
  for (const unsigned int n : {4u, 3u})
    {
      const double  theta_deg = n == 4 ? 68. : 65.27, theta = radians(theta_deg);
      const Pyramid rounded("p", n, theta_deg, R, 0.), sharp("p", n, theta_deg, 0., 0.);
      const double  Delta = R * (1. / std::sin(theta) - 1.);
      EXPECT_NEAR(rounded.blunting_offset(), Delta, 1e-15);
      // Heights on the tip sphere, among the elliptic edge arcs, and on the faces.
      const double beta = std::atan(std::tan(theta) / std::cos(pi / n));
      double       largest = 0.;
      for (const double h :
           {0.5 * R * (1. - std::sin(beta)), R * (1. - 0.5 * (std::sin(beta) + std::sin(theta))),
            R * (1. - std::sin(theta)), 0.05, 0.3, 2.})
        {
          const double ratio = polar_area(rounded, h, n, pi / n) / rounded.projected_area(h);
          EXPECT_NEAR(ratio, 1., 1e-11) << "n = " << n << ", h = " << h;
          largest = std::max(largest, std::abs(ratio - 1.));
        }
      std::cout << "[ area ] rounded " << (n == 4 ? "Vickers" : "Berkovich")
                << " (R = 0.1): max relative difference from the area of {profile < h}: " << largest
                << "\n";
      // The two closed forms meet where the faces begin.
      const double h_faces = R * (1. - std::sin(theta));
      EXPECT_NEAR(rounded.projected_area(h_faces * (1. - 1e-12)) / rounded.projected_area(h_faces),
                  1., 1e-9);
      // Far from the tip: the sharp area at h + Delta less the n corner deficits.
      const double D = rounded.corner_deficit();
      EXPECT_GT(D, 0.);
      EXPECT_LT(D, 0.1 * R * R);
      for (const double h : {1., 10.})
        EXPECT_NEAR(rounded.projected_area(h), sharp.projected_area(h + Delta) - n * D,
                    1e-12 * sharp.projected_area(h));
      const double h = 100. * R;
      EXPECT_NEAR(rounded.projected_area(h) / sharp.projected_area(h) - 1., 2. * Delta / h,
                  2. * std::pow(Delta / h, 2));
    }
  {
    // Flat punch with a rounded rim: the rim's torus until h = e, then pi a^2.
    const double    a = 2., e = 0.2;
    const FlatPunch punch(a, e);
    for (const double h : {0.01, 0.1, 0.19})
      {
        const double r = a - e + std::sqrt(e * e - (e - h) * (e - h));
        EXPECT_NEAR(punch.projected_area(h) / (pi * r * r), 1., 1e-13);
        EXPECT_NEAR(polar_area(punch, h, 1, 0.) / punch.projected_area(h), 1., 1e-10);
      }
    EXPECT_DOUBLE_EQ(punch.projected_area(0.3), pi * a * a);
  }
}

namespace
{
  // Walks along `path` (indenter frame) and checks that the gap is 1-Lipschitz and the normal
  // Lipschitz with constant 1 / (R + gap) (the normal of a convex solid rounded by R, at the
  // distance R + gap from the sharp solid); returns the normals at both ends.
  std::pair<Tensor<1, 3>, Tensor<1, 3>>
  check_continuity_along(const IndenterSurface &surface, const double R,
                         const std::function<Point<3>(double)> &path, const unsigned int n_steps)
  {
    SurfaceProjection  previous = surface.project(path(0.), 0.);
    const Tensor<1, 3> first = previous.normal;
    double             largest_normal_jump = 0.;
    for (unsigned int i = 1; i <= n_steps; ++i)
      {
        const double            s0 = double(i - 1) / n_steps, s1 = double(i) / n_steps;
        const SurfaceProjection current = surface.project(path(s1), 0.);
        const double            step = path(s1).distance(path(s0));
        EXPECT_LE(std::abs(current.gap - previous.gap), step * (1. + 1e-9) + 1e-15)
            << surface.name() << " at s = " << s1;
        const double bound = step / (R + std::min(current.gap, previous.gap));
        const double jump = (current.normal - previous.normal).norm();
        EXPECT_LE(jump, bound * (1. + 1e-6) + 1e-12) << surface.name() << " at s = " << s1;
        largest_normal_jump = std::max(largest_normal_jump, jump);
        previous = current;
      }
    EXPECT_LT(largest_normal_jump, 0.05) << "the path is too coarse to show continuity";
    return {first, previous.normal};
  }
} // namespace

// Rounded pyramids: gap and normal continuous across faces, edges and the tip, outside and
// inside (within R); the paths do cross an edge (the normal turns from one face to the next).
TEST(IndenterPyramid, RoundedEdgesAreContinuous)
{
  const double R = 0.2;
  for (const unsigned int n : {4u, 3u})
    {
      const Pyramid         pyramid("p", n, n == 4 ? 68. : 65.27, R, 10.);
      const PyramidGeometry geometry(n, n == 4 ? 68. : 65.27, R, 10.);
      const double          phi0 = radians(10.), phi1 = radians(10. + 360. / n);
      const double          height = 1.;
      // At `height` the offset faces' traces are lines at the distance (height + Delta)
      // tan(theta) from the axis. The path runs parallel to them, `offset` outside (> 0) or
      // inside (< 0; still outside the sharp solid, which lies R / cos(theta) further in), from
      // the middle of face 0 around edge 0 to the middle of face 1.
      for (const double offset : {0.3 * R, 0.01 * R, -0.5 * R})
        {
          const double inradius =
              (height + pyramid.blunting_offset()) * std::tan(pyramid.face_angle());
          const auto arc = [&](const double s) {
            const double phi = phi0 + s * (phi1 - phi0);
            const double from_face = std::min(phi - phi0, phi1 - phi); // to the nearer face
            return on_circle((inradius + offset) / std::cos(from_face), phi, height);
          };
          const auto [start, end] = check_continuity_along(pyramid, R, arc, 4000);
          EXPECT_LT((start - geometry.normals[0]).norm(), 1e-12) << "offset " << offset;
          EXPECT_LT((end - geometry.normals[1]).norm(), 1e-12) << "offset " << offset;
        }
      // Up the edge's meridian from below the apex: tip sphere, then the edge cylinder.
      const double psi = phi0 + pi / n;
      const auto   meridian = [&](const double s) {
        return Point<3>(0., 0., -0.3 * R) +
               s * Tensor<1, 3>({2. * R * std::cos(psi), 2. * R * std::sin(psi), 0.9 * R});
      };
      const auto [bottom, top] = check_continuity_along(pyramid, R, meridian, 4000);
      EXPECT_NEAR(bottom[2], -1., 1e-12);
      EXPECT_NEAR(top * geometry.edges[0], 0., 1e-9) << "ends on the edge cylinder";
    }
}

// The other rounded shapes are continuous across their seams as well (cone: cap to flank;
// flat punch: end face to rim to wall; sphere: cap to shank). The paths keep away from the sharp
// solids, where the normal of any rounded solid turns abruptly.
TEST(IndenterLibrary, RoundedSeamsAreContinuous)
{
  const Cone cone(70.3, 0.2);
  check_continuity_along(
      cone, 0.2, [](double s) { return Point<3>(2. * s, 0.3 * s, -0.05); }, 4000);
  const FlatPunch punch(1., 0.2);
  check_continuity_along(
      punch, 0.2, [](double s) { return Point<3>(1.3 * s, 0.1, -0.1 + 0.45 * s); }, 4000);
  const Sphere sphere(1.);
  check_continuity_along(
      sphere, 1., [](double s) { return Point<3>(1.2, 0.2 * s, -0.2 + 2. * s); }, 4000);
}

// Rotation convention: at rotation 0 face 0 faces +x; a positive rotation turns the pyramid
// counterclockwise seen from above; a Berkovich pyramid then has an edge along -x.
TEST(IndenterPyramid, RotationConvention)
{
  const double theta = radians(68.);
  for (const double rotation : {0., 30.})
    {
      const Pyramid           vickers = Pyramid::vickers(0., rotation);
      const double            phi = radians(rotation);
      const SurfaceProjection p = vickers.project(on_circle(10., phi, 1.), 0.);
      EXPECT_NEAR(p.normal[0], std::cos(theta) * std::cos(phi), 1e-14);
      EXPECT_NEAR(p.normal[1], std::cos(theta) * std::sin(phi), 1e-14);
      EXPECT_NEAR(p.normal[2], -std::sin(theta), 1e-14);
      // Along a face normal's azimuth the profile rises at cot(theta), along an edge slower.
      EXPECT_NEAR(vickers.profile(std::cos(phi), std::sin(phi)), 1. / std::tan(theta), 1e-14);
      EXPECT_NEAR(vickers.profile(std::cos(phi + pi / 4.), std::sin(phi + pi / 4.)),
                  std::cos(pi / 4.) / std::tan(theta), 1e-14);
    }
  const Pyramid     berkovich = Pyramid::berkovich(0., 0.);
  const double      theta_b = radians(65.27);
  SurfaceProjection p = berkovich.project(Point<3>(10., 0., 1.), 0.);
  EXPECT_NEAR(p.normal[0], std::cos(theta_b), 1e-14);
  EXPECT_NEAR(p.normal[1], 0., 1e-14);
  p = berkovich.project(Point<3>(-10., 0., 1.), 0.); // nearest: the edge along -x
  EXPECT_NEAR(p.closest_point[1], 0., 1e-12);
  EXPECT_LT(p.closest_point[0], 0.);
  EXPECT_NEAR(berkovich.edge_direction(0)[1] / berkovich.edge_direction(0)[0], std::sqrt(3.), 1e-12)
      << "edge 0 at 60 deg";
  EXPECT_NEAR(berkovich.edge_direction(1)[1], 0., 1e-15);
  EXPECT_LT(berkovich.edge_direction(1)[0], 0.) << "edge 1 along -x";
}

// faces_along_axes() counts the faces whose trace on the surface runs along x or y, i.e. whose
// normal has no horizontal component along one of the two axes (to 0.5 deg): counted here from
// the face normals themselves.
TEST(IndenterPyramid, FacesAlongTheAxesAreCounted)
{
  const auto count_from_normals = [](const Pyramid &pyramid) {
    unsigned int n = 0;
    for (unsigned int i = 0; i < pyramid.n_faces(); ++i)
      {
        const Tensor<1, 3> &normal = pyramid.face_normal(i);
        const double        horizontal = std::hypot(normal[0], normal[1]);
        if (std::min(std::abs(normal[0]), std::abs(normal[1])) <=
            std::sin(radians(0.5)) * horizontal + 1e-12)
          ++n;
      }
    return n;
  };
  const std::vector<std::pair<Pyramid, unsigned int>> cases = {
      {Pyramid::vickers(0.05, 0.), 4},    {Pyramid::vickers(0.05, 90.), 4},
      {Pyramid::vickers(0.05, -0.4), 4},  {Pyramid::vickers(0.05, 22.5), 0},
      {Pyramid::vickers(0.05, 45.), 0},   {Pyramid::vickers(0.05, 1.), 0},
      {Pyramid::berkovich(0.05, 0.), 1},  {Pyramid::berkovich(0.05, 30.), 1},
      {Pyramid::berkovich(0.05, 15.), 0},
  };
  for (const auto &[pyramid, expected] : cases)
    {
      EXPECT_EQ(pyramid.faces_along_axes(), expected)
          << pyramid.name() << " at " << pyramid.rotation_deg() << " deg";
      EXPECT_EQ(count_from_normals(pyramid), expected)
          << pyramid.name() << " at " << pyramid.rotation_deg() << " deg";
    }
}

// mirror_symmetric_about_xz_and_yz() tells the truth: where it says yes, gap and normal are
// mirrored exactly; where it says no, some point shows the asymmetry.
TEST(IndenterLibrary, MirrorSymmetryClaimsHold)
{
  const Sphere                                          sphere(1.);
  const Cone                                            cone(70.3, 0.1);
  const FlatPunch                                       punch(1., 0.1);
  const RoundedCone                                     rounded(2.48, 0.005);
  const ProfileTable                                    table({0., 1., 2.}, {0., 0.3, 1.2});
  std::vector<std::pair<const IndenterSurface *, bool>> cases = {
      {&sphere, true}, {&cone, true}, {&punch, true}, {&rounded, true}, {&table, true}};
  std::vector<Pyramid> pyramids;
  for (const double rotation : {0., 45., 90., -45., 135., 30., 10.})
    pyramids.push_back(Pyramid::vickers(0.1, rotation));
  for (const double rotation : {0., 30., 90.})
    pyramids.push_back(Pyramid::berkovich(0.1, rotation));
  for (const Pyramid &pyramid : pyramids)
    cases.emplace_back(&pyramid, pyramid.name() == "vickers" &&
                                     std::fmod(std::abs(pyramid.rotation_deg()), 45.) == 0.);

  std::mt19937                           generator(5);
  std::uniform_real_distribution<double> unit(-1., 1.);
  std::vector<Point<3>>                  points;
  for (int k = 0; k < 200; ++k)
    points.emplace_back(2. * unit(generator), 2. * unit(generator), unit(generator));
  for (const auto &[surface, symmetric] : cases)
    {
      EXPECT_EQ(surface->mirror_symmetric_about_xz_and_yz(), symmetric) << surface->name();
      double largest_asymmetry = 0.;
      for (const Point<3> &x : points)
        {
          const SurfaceProjection p = surface->project(x, 0.5);
          for (const unsigned int axis : {0u, 1u})
            {
              Point<3> mirrored = x;
              mirrored[axis] = -mirrored[axis];
              const SurfaceProjection m = surface->project(mirrored, 0.5);
              largest_asymmetry = std::max(largest_asymmetry, std::abs(m.gap - p.gap));
              if (symmetric)
                {
                  EXPECT_NEAR(m.gap, p.gap, 1e-13) << surface->name();
                  EXPECT_NEAR(m.normal[axis], -p.normal[axis], 1e-13) << surface->name();
                }
            }
        }
      if (!symmetric)
        {
          EXPECT_GT(largest_asymmetry, 1e-2) << surface->name();
        }
    }
}

// No NaN for any finite input, converged = false only for non-finite input.
TEST(IndenterLibrary, ProjectionIsRobust)
{
  const Sphere       sphere(1.);
  const Cone         sharp_cone(70.3, 0.), cone(70.3, 0.1);
  const Pyramid      vickers = Pyramid::vickers(0., 0.), rounded = Pyramid::berkovich(0.1, 7.);
  const FlatPunch    punch(1., 0.), rounded_punch(1., 0.1);
  const ProfileTable table({0., 1., 2.}, {0., 0.3, 1.2});
  const std::vector<const IndenterSurface *> surfaces = {
      &sphere, &sharp_cone, &cone, &vickers, &rounded, &punch, &rounded_punch, &table};
  const std::vector<std::pair<Point<3>, double>> inputs = {
      {Point<3>(0., 0., 0.), 0.},          // the apex itself
      {Point<3>(0., 0., 5.), 0.},          // on the axis, deep inside
      {Point<3>(0., 0., 0.1), 0.},         // on the axis at a tip centre
      {Point<3>(1e-300, -1e-300, 0.), 0.}, // tiny
      {Point<3>(0.5, 0.5, 0.), -1e30},     // the solver's "indenter far away"
      {Point<3>(1e150, -2e150, 3e150), 1e150},
      {Point<3>(-1e200, 1e200, -1e200), 0.},
      {Point<3>(1., 0., 1e-17), 0.}, // on a face/edge within round-off
  };
  for (const IndenterSurface *surface : surfaces)
    {
      for (const auto &[x, depth] : inputs)
        {
          const SurfaceProjection p = surface->project(x, depth);
          EXPECT_TRUE(p.converged) << surface->name();
          EXPECT_FALSE(std::isnan(p.gap)) << surface->name();
          EXPECT_NEAR(p.normal.norm(), 1., 1e-12) << surface->name() << " at " << x;
          EXPECT_LE(p.normal[2], 1e-15) << surface->name();
        }
      const double nan = std::numeric_limits<double>::quiet_NaN();
      EXPECT_FALSE(surface->project(Point<3>(nan, 0., 0.), 0.).converged) << surface->name();
      EXPECT_FALSE(surface->project(Point<3>(0., 0., 0.), infinity).converged);
      EXPECT_FALSE(surface->project(Point<3>(0., infinity, 0.), 0.).converged);
    }
}

// Invalid geometry is rejected by the constructors.
TEST(IndenterLibrary, InvalidParametersThrow)
{
  EXPECT_THROW(Sphere(0.), std::invalid_argument);
  EXPECT_THROW(Cone(90., 0.), std::invalid_argument);
  EXPECT_THROW(Cone(0., 0.), std::invalid_argument);
  EXPECT_THROW(Cone(70., -0.1), std::invalid_argument);
  EXPECT_THROW(Pyramid("p", 2, 60., 0., 0.), std::invalid_argument);
  EXPECT_THROW(Pyramid::vickers(-1., 0.), std::invalid_argument);
  EXPECT_THROW(Pyramid::berkovich(0., infinity), std::invalid_argument);
  EXPECT_THROW(FlatPunch(0., 0.), std::invalid_argument);
  EXPECT_THROW(FlatPunch(1., 1.5), std::invalid_argument);
  EXPECT_NO_THROW(FlatPunch(1., 1.)) << "e = a: a hemispherical end";
}

namespace
{
  namespace fs = std::filesystem;

  fs::path write_table(const std::string &test_name, const std::string &file_name,
                       const std::string &text)
  {
    const fs::path dir = indentsim::test_files::scratch_directory("indenter", test_name);
    const fs::path path = dir / file_name;
    std::ofstream(path) << text;
    return path;
  }

  // The error message of reading `path`, or "" if it was accepted.
  std::string table_error(const fs::path &path)
  {
    try
      {
        ProfileTable::read(path.string());
      }
    catch (const ProfileTableError &error)
      {
        return error.what();
      }
    return "";
  }
} // namespace

// A profile sampled from a sphere reproduces the sphere's gap, normal and closest point to
// interpolation accuracy (PCHIP with 361 rows: gap error below 1e-7 R; the normal, i.e. the
// slope, is only second-order accurate, O(h^2 f''^2 / f'), about 4e-5 here).
TEST(IndenterProfileTable, SampledSphereReproducesTheSphere)
{
  const double        R = 5.;
  const unsigned int  n_rows = 361;
  std::vector<double> r, z;
  for (unsigned int i = 0; i < n_rows; ++i)
    {
      r.push_back(0.9 * R * i / (n_rows - 1));
      z.push_back(R - std::sqrt(R * R - r.back() * r.back()));
    }
  const ProfileTable                     table(r, z, "sphere table");
  const Sphere                           sphere(R);
  std::mt19937                           generator(3);
  std::uniform_real_distribution<double> unit(-1., 1.);
  double                                 largest_gap_error = 0., largest_normal_error = 0.;
  unsigned int                           n_checked = 0;
  for (int k = 0; k < 400; ++k)
    {
      const Point<3> x(4. * unit(generator), 4. * unit(generator), 1.5 * unit(generator) + 0.5);
      const SurfaceProjection exact = sphere.project(x, 0.);
      if (std::hypot(exact.closest_point[0], exact.closest_point[1]) > 0.8 * R)
        continue; // the table ends at 0.9 R
      const SurfaceProjection p = table.project(x, 0.);
      ASSERT_TRUE(p.converged);
      largest_gap_error = std::max(largest_gap_error, std::abs(p.gap - exact.gap));
      largest_normal_error = std::max(largest_normal_error, (p.normal - exact.normal).norm());
      EXPECT_LT(p.closest_point.distance(exact.closest_point), 1e-4);
      ++n_checked;
    }
  std::cout << "[ profile table ] sphere R = 5 from " << n_rows << " rows: max gap error "
            << largest_gap_error << " um, max normal error " << largest_normal_error << " ("
            << n_checked << " points)\n";
  EXPECT_GT(n_checked, 100u);
  EXPECT_LT(largest_gap_error, 1e-7 * R);
  EXPECT_LT(largest_normal_error, 1e-4);
  // The projected area follows the sphere's pi (2 R h - h^2).
  for (const double h : {0.1, 1., 2.})
    EXPECT_NEAR(table.projected_area(h) / sphere.projected_area(h), 1., 1e-6);
  // The slope at the apex is exactly zero for a sphere sampled uniformly (the three-point
  // estimate is exact for a parabola, and the sphere is one to O(r^4)).
  EXPECT_LT(std::abs(table.slopes()[0]), 1e-6);
}

// An area function A(h) = pi tan^2(alpha) h^2 read from a file is exactly the cone, also beyond
// the table (straight continuation), and its projected area reproduces the tabulated areas.
TEST(IndenterProfileTable, AreaFunctionOfAConeIsTheCone)
{
  const double alpha_deg = 70.3, k = pi * std::pow(std::tan(radians(alpha_deg)), 2);
  std::string  text = "# area function of a sharp cone, alpha = 70.3 deg\ndepth_um,area_um2\r\n";
  std::vector<double> depths = {0., 0.05, 0.2, 0.25, 0.7, 1.3, 2., 3.5, 5.};
  for (const double h : depths)
    {
      std::array<char, 64> buffer{};
      const auto           end = std::to_chars(buffer.data(), buffer.data() + 64, k * h * h).ptr;
      text += std::to_string(h) + " , " + std::string(buffer.data(), end) + "\r\n";
    }
  const fs::path     path = write_table("area_cone", "cone_area.csv", text + "\n# end\n");
  const ProfileTable table = ProfileTable::read(path.string());
  EXPECT_EQ(table.kind(), ProfileTable::Kind::area_function);
  const Cone                             cone(alpha_deg, 0.);
  std::mt19937                           generator(4);
  std::uniform_real_distribution<double> unit(-1., 1.);
  double                                 largest = 0.;
  for (int i = 0; i < 300; ++i)
    {
      const double            size = std::pow(10., 1.5 * unit(generator));
      const Point<3>          x(size * unit(generator), size * unit(generator),
                                size * unit(generator) - 0.3);
      const SurfaceProjection p = table.project(x, 0.3), q = cone.project(x, 0.3);
      ASSERT_TRUE(p.converged);
      EXPECT_NEAR(p.gap, q.gap, 1e-12 * (1. + size)) << x;
      EXPECT_LT((p.normal - q.normal).norm(), 1e-12) << x;
      largest = std::max(largest, std::abs(p.gap - q.gap));
    }
  std::cout << "[ profile table ] cone from its area function: max gap error " << largest
            << " um\n";
  for (const double h : depths)
    if (h > 0.)
      {
        EXPECT_NEAR(table.projected_area(h) / (k * h * h), 1., 1e-12) << h;
      }
  EXPECT_NEAR(table.projected_area(12.) / (k * 144.), 1., 1e-12) << "beyond the table";
}

// The interpolant passes through the rows, is C1 (continuous normal), never decreases, and
// continues beyond the last row with the last secant slope.
TEST(IndenterProfileTable, InterpolationIsMonotoneAndC1)
{
  const std::vector<double> r = {0., 0.5, 1., 2., 3., 4.};
  const std::vector<double> z = {0., 0.5, 0.7, 0.7, 1.5, 3.};
  const ProfileTable        table(r, z);
  for (std::size_t i = 0; i < r.size(); ++i)
    EXPECT_DOUBLE_EQ(table.profile_at_radius(r[i]), z[i]);
  for (std::size_t i = 1; i + 1 < r.size(); ++i)
    {
      const double d = 1e-7;
      const double left = (table.profile_at_radius(r[i]) - table.profile_at_radius(r[i] - d)) / d;
      const double right = (table.profile_at_radius(r[i] + d) - table.profile_at_radius(r[i])) / d;
      EXPECT_NEAR(left, right, 1e-5) << "row " << i;
    }
  double previous = 0.;
  for (int i = 0; i <= 4000; ++i)
    {
      const double value = table.profile_at_radius(5. * i / 4000.);
      EXPECT_GE(value, previous);
      previous = value;
    }
  EXPECT_DOUBLE_EQ(table.profile_at_radius(1.5), 0.7) << "a flat part stays flat";
  EXPECT_NEAR(table.profile_at_radius(6.) - table.profile_at_radius(5.), 1.5, 1e-12);
  EXPECT_NEAR(table.slope_at_radius(4.), 1.5, 1e-15);
  EXPECT_NEAR(table.slope_at_radius(4. - 1e-12), 1.5, 1e-9);
}

// The projection onto tabulated, non-convex profiles (a conical apex, a plateau, concave and
// convex stretches) agrees with brute force, inside and outside.
TEST(IndenterProfileTable, ProjectionMatchesBruteForce)
{
  std::vector<double> r, z;
  for (int i = 0; i <= 24; ++i)
    {
      r.push_back(0.25 * i);
      z.push_back(0.1 * r.back() * r.back() + 0.15 * (1. - std::cos(2. * r.back())));
    }
  const ProfileTable wavy(r, z, "wavy");
  const ProfileTable plateau({0., 0.5, 1., 2., 3., 4.}, {0., 0.5, 0.7, 0.7, 1.5, 3.}, "plateau");
  for (const ProfileTable *table : {&wavy, &plateau})
    check_shape({"profile table " + table->source(), table,
                 [table](double extent) { return table_patches(*table, extent); }, 1.,
                 graph_residual(table)},
                9);
}

// On long, strongly curved cubic pieces one piece can hold several stationary points of the
// distance (minimum, maximum, minimum); the projection must find the global minimum among them.
// Oracle: the distance minimized over the meridian curve by dense sampling and zooming (the
// closest point of a surface of revolution lies in the point's meridian half-plane).
TEST(IndenterProfileTable, ProjectionFindsTheGlobalMinimumOnLongPieces)
{
  const ProfileTable table({0., 3., 6., 9.}, {0., 0.4, 4., 4.5}, "long pieces");
  const auto         meridian_distance = [&](const double rho, const double zeta) {
    const auto distance = [&](const double r) {
      return std::hypot(r - rho, table.profile_at_radius(r) - zeta);
    };
    constexpr int n = 20000;
    double        best_r = 0., best = distance(0.), step = 30. / n;
    for (int i = 1; i <= n; ++i)
      if (distance(i * step) < best)
        best = distance(i * step), best_r = i * step;
    for (int level = 0; level < 40; ++level)
      {
        const double r0 = best_r;
        for (int i = -10; i <= 10; ++i)
          {
            const double r = std::max(0., r0 + 0.2 * i * step);
            if (distance(r) < best)
              best = distance(r), best_r = r;
          }
        step *= 0.3;
      }
    return best;
  };
  std::mt19937                           generator(21);
  std::uniform_real_distribution<double> radius(0., 10.), height(-2., 7.);
  double                                 largest = 0.;
  for (int k = 0; k < 1500; ++k)
    {
      const double            rho = radius(generator), zeta = height(generator);
      const SurfaceProjection p = table.project(Point<3>(rho, 0., zeta), 0.);
      const double            expected = meridian_distance(rho, zeta);
      ASSERT_TRUE(p.converged);
      EXPECT_NEAR(std::abs(p.gap), expected, 1e-9) << "rho = " << rho << ", zeta = " << zeta;
      largest = std::max(largest, std::abs(std::abs(p.gap) - expected));
    }
  std::cout << "[ profile table ] long pieces, 1500 points: max |gap| error " << largest << " um\n";
}

// Bad table files are rejected with the file, the line and what is allowed.
TEST(IndenterProfileTable, BadFilesAreRejected)
{
  struct BadFile
  {
    std::string              text;
    std::vector<std::string> parts;
  };
  const std::vector<BadFile> bad = {
      {"r,z\n0,0\n1,1\n", {":1:", "header 'r,z'", "r_um,z_um", "depth_um,area_um2"}},
      {"", {"empty", "r_um,z_um"}},
      {"r_um,z_um\n0,0\n", {"1 data row", "at least 2"}},
      {"r_um,z_um\n", {"0 data rows", "at least 2"}},
      {"r_um,z_um\n0,0\n1,abc\n", {":3:", "'abc' is not a number", "r_um,z_um"}},
      {"r_um,z_um\n0,0\n1\n", {":3:", "expected 2", "got 1"}},
      {"r_um,z_um\n0,0\n1,2,3\n", {":3:", "got 3"}},
      {"r_um,z_um\n0.1,0\n1,1\n", {":2:", "first row must be the apex 0,0"}},
      {"r_um,z_um\n0,0\n1,1\n1,2\n", {":4:", "r_um = 1 does not increase", "strictly increasing"}},
      {"r_um,z_um\n0,0\n1,1\n2,0.5\n3,2\n", {":4:", "z_um = 0.5", "non-decreasing"}},
      {"r_um,z_um\n0,0\n1,1\n2,1\n", {":4:", "same z_um", "last slope"}},
      {"r_um,z_um\n0,0\n1,inf\n", {":3:", "'inf' is not a number"}},
      {"depth_um,area_um2\n0,0\n1,24.5\n1,30\n", {":4:", "depth_um = 1", "strictly increasing"}},
      {"depth_um,area_um2\n0,0\n1,24.5\n2,24.5\n", {":4:", "area_um2 = 24.5", "vertical wall"}},
      {"depth_um,area_um2\n0,1\n1,24.5\n", {":2:", "depth_um = 0, area_um2 = 0"}},
  };
  for (std::size_t i = 0; i < bad.size(); ++i)
    {
      const fs::path path =
          write_table("bad_tables", "bad_" + std::to_string(i) + ".csv", bad[i].text);
      const std::string message = table_error(path);
      SCOPED_TRACE("table:\n" + bad[i].text + "message: " + message);
      ASSERT_FALSE(message.empty()) << "accepted";
      EXPECT_EQ(message.rfind(path.string(), 0), 0u) << "does not start with the file";
      for (const std::string &part : bad[i].parts)
        EXPECT_NE(message.find(part), std::string::npos) << "missing '" << part << "'";
    }
  const std::string missing =
      table_error(indentsim::test_files::scratch_directory("indenter", "missing") / "none.csv");
  EXPECT_NE(missing.find("none.csv"), std::string::npos) << missing;
  EXPECT_NE(missing.find("does not exist"), std::string::npos) << missing;
  // Comments, blank lines, spaces and CRLF are fine.
  EXPECT_EQ(table_error(write_table("bad_tables", "good.csv",
                                    "# tip\r\n\r\n r_um , z_um \r\n0,0\r\n+1.5, 2e-1\r\n")),
            "");
  EXPECT_THROW(ProfileTable({0., 1.}, {0., 0.}), ProfileTableError);
}

// The factory builds every shape of the library from the case parameters.
TEST(IndenterFactory, CreatesEveryShape)
{
  indentsim::io::IndenterParameters parameters;
  parameters.file = write_table("factory", "tip.csv", "r_um,z_um\n0,0\n1,0.2\n2,1\n").string();
  for (const std::string shape :
       {"rounded_cone", "sphere", "cone", "vickers", "berkovich", "flat_punch", "profile_table"})
    {
      parameters.shape = shape;
      const auto indenter = create_indenter(parameters);
      ASSERT_NE(indenter, nullptr);
      EXPECT_EQ(indenter->name(), shape);
    }
  parameters.shape = "vickers";
  parameters.tip_radius = 0.1;
  parameters.rotation_deg = 30.;
  const auto vickers = create_indenter(parameters);
  EXPECT_FALSE(vickers->mirror_symmetric_about_xz_and_yz()) << "the rotation reached the shape";
  EXPECT_NEAR(vickers->profile(0., 0.), 0., 1e-15);
  parameters.shape = "sphere";
  parameters.radius = 4.;
  EXPECT_NEAR(create_indenter(parameters)->projected_area(10.), pi * 16., 1e-12);
  parameters.shape = "profile_table";
  parameters.file = "/no/such/table.csv";
  EXPECT_THROW(create_indenter(parameters), ProfileTableError);
}
