#include "contact/ContactArea.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace indentsim::contact
{
  using dealii::Point;

  namespace
  {
    double polygon_area(const std::vector<Point<2>> &polygon)
    {
      double twice_area = 0;
      for (std::size_t i = 0; i < polygon.size(); ++i)
        {
          const Point<2> &a = polygon[i], &b = polygon[(i + 1) % polygon.size()];
          twice_area += a[0] * b[1] - a[1] * b[0];
        }
      return std::abs(twice_area) / 2;
    }
  } // namespace

  ContactPatch triangle_contact_patch(const std::array<Point<2>, 3> &xy,
                                      const std::array<double, 3>   &phi)
  {
    // Clip the triangle at phi = 0 (Sutherland-Hodgman against one linear half-plane): the
    // part with phi > 0 is a polygon of the positive corners and the edge crossings.
    std::vector<Point<2>> clipped;
    for (unsigned int i = 0; i < 3; ++i)
      {
        const unsigned int j = (i + 1) % 3;
        if (phi[i] > 0)
          clipped.push_back(xy[i]);
        if ((phi[i] > 0) != (phi[j] > 0))
          {
            const double t = phi[i] / (phi[i] - phi[j]);
            clipped.push_back(xy[i] + t * (xy[j] - xy[i]));
          }
      }
    ContactPatch patch;
    if (clipped.size() < 3)
      return patch;
    patch.area = polygon_area(clipped);
    // The distance from the axis is convex, so its maximum over the polygon is at a corner.
    for (const Point<2> &p : clipped)
      {
        patch.max_radius = std::max(patch.max_radius, p.norm());
        patch.max_abs_x = std::max(patch.max_abs_x, std::abs(p[0]));
        patch.max_abs_y = std::max(patch.max_abs_y, std::abs(p[1]));
      }
    return patch;
  }

  ContactPatch segment_contact_patch(const std::array<double, 2> &r,
                                     const std::array<double, 2> &phi)
  {
    ContactPatch patch;
    if (phi[0] <= 0 && phi[1] <= 0)
      return patch;
    // The zero crossing of phi, where phi changes sign along the edge.
    const auto crossing = [&]() { return r[0] + (r[1] - r[0]) * phi[0] / (phi[0] - phi[1]); };
    double     r1 = r[0], r2 = r[1];
    if (phi[0] <= 0)
      r1 = crossing();
    else if (phi[1] <= 0)
      r2 = crossing();
    patch.area = std::numbers::pi * std::abs(r2 * r2 - r1 * r1);
    patch.max_radius = std::max(std::abs(r1), std::abs(r2));
    patch.max_abs_x = patch.max_abs_y = patch.max_radius;
    return patch;
  }

  ContactPatch quad_contact_patch(const std::array<Point<2>, 4> &xy,
                                  const std::array<double, 4>   &phi)
  {
    const Point<2> centre = 0.25 * (xy[0] + xy[1] + xy[2] + xy[3]);
    const double   phi_centre = 0.25 * (phi[0] + phi[1] + phi[2] + phi[3]);
    ContactPatch   patch;
    for (unsigned int i = 0; i < 4; ++i)
      {
        const unsigned int j = (i + 1) % 4;
        const ContactPatch part =
            triangle_contact_patch({{xy[i], xy[j], centre}}, {{phi[i], phi[j], phi_centre}});
        patch.area += part.area;
        patch.max_radius = std::max(patch.max_radius, part.max_radius);
        patch.max_abs_x = std::max(patch.max_abs_x, part.max_abs_x);
        patch.max_abs_y = std::max(patch.max_abs_y, part.max_abs_y);
      }
    return patch;
  }
} // namespace indentsim::contact
