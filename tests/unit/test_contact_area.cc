// The contact-area interpolation (contact/ContactArea.h) against closed-form areas of linear
// indicator fields. Units: um.
#include "contact/ContactArea.h"

#include <gtest/gtest.h>

#include <cmath>

using dealii::Point;
using indentsim::contact::quad_contact_patch;
using indentsim::contact::triangle_contact_patch;

// Requirement: on a triangle, the area of {phi > 0} of a linear phi is exact, including the
// all-positive and all-negative cases.
TEST(ContactArea, TriangleClipIsExactForLinearIndicator)
{
  const std::array<Point<2>, 3> t = {{Point<2>(0, 0), Point<2>(1, 0), Point<2>(0, 1)}};
  // phi = x - 0.5: the part x > 0.5 is the triangle (0.5,0), (1,0), (0.5,0.5), area 1/8.
  auto p = triangle_contact_patch(t, {{-0.5, 0.5, -0.5}});
  EXPECT_NEAR(p.area, 0.125, 1e-15);
  EXPECT_NEAR(p.max_radius, 1.0, 1e-15);
  // phi = 0.25 - x - y: the corner triangle x + y < 0.25, area 1/32, farthest point on an axis.
  p = triangle_contact_patch(t, {{0.25, -0.75, -0.75}});
  EXPECT_NEAR(p.area, 1. / 32, 1e-15);
  EXPECT_NEAR(p.max_radius, 0.25, 1e-15);
  EXPECT_NEAR(triangle_contact_patch(t, {{1, 2, 3}}).area, 0.5, 1e-15);
  EXPECT_EQ(triangle_contact_patch(t, {{-1, -2, 0}}).area, 0.0);
}

// Requirement: on a quadrilateral the four-triangle split reproduces a linear phi exactly and
// moves the perimeter continuously (not node by node) as phi changes.
TEST(ContactArea, QuadPerimeterMovesContinuously)
{
  // A rotated, stretched parallelogram: phi linear in x, so the contact part is exact.
  const std::array<Point<2>, 4> q = {
      {Point<2>(1, 1), Point<2>(3, 1.5), Point<2>(3.5, 3.5), Point<2>(1.5, 3)}};
  const auto phi_at = [](const Point<2> &x, const double level) { return level - x[0]; };
  double     previous = -1;
  for (double level = 1.0; level <= 3.5; level += 0.25)
    {
      std::array<double, 4> phi;
      for (unsigned int i = 0; i < 4; ++i)
        phi[i] = phi_at(q[i], level);
      const double area = quad_contact_patch(q, phi).area;
      // Closed form: area of the parallelogram left of x = level, by a fine strip sum of the
      // chord length (independent of the clipping code).
      double    reference = 0;
      const int n = 20000;
      for (int k = 0; k < n; ++k)
        {
          const double y = 1 + 2.5 * (k + 0.5) / n;
          // Left and right edges of the parallelogram at height y.
          double x_min = 1e9, x_max = -1e9;
          for (unsigned int e = 0; e < 4; ++e)
            {
              const Point<2> a = q[e], b = q[(e + 1) % 4];
              if ((a[1] - y) * (b[1] - y) <= 0 && a[1] != b[1])
                {
                  const double x = a[0] + (y - a[1]) / (b[1] - a[1]) * (b[0] - a[0]);
                  x_min = std::min(x_min, x), x_max = std::max(x_max, x);
                }
            }
          if (x_max > x_min)
            reference += std::max(0.0, std::min(x_max, level) - x_min) * 2.5 / n;
        }
      EXPECT_NEAR(area, reference, 1e-6) << "level " << level;
      EXPECT_GE(area, previous);
      previous = area;
    }
  // The full parallelogram: |(2, 0.5) x (0.5, 2)| = 3.75.
  EXPECT_NEAR(previous, 3.75, 1e-12);
}
