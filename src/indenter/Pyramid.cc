// Regular pyramids (Vickers, Berkovich), sharp or rounded (MinkowskiRounding.h). Units: um.
#include "indenter/Pyramid.h"
#include "indenter/MinkowskiRounding.h"

#include <deal.II/base/quadrature_lib.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

namespace indentsim::indenter
{
  Pyramid::Pyramid(std::string name, const unsigned int n_faces, const double face_angle_deg,
                   const double tip_radius, const double rotation_deg)
    : shape_name(std::move(name))
    , theta(face_angle_deg * std::numbers::pi / 180.)
    , R(tip_radius)
    , rotation(rotation_deg)
  {
    if (n_faces < 3 || n_faces > max_faces)
      throw std::invalid_argument("Pyramid: the number of faces must be between 3 and " +
                                  std::to_string(max_faces) + ", got " + std::to_string(n_faces));
    if (!(face_angle_deg > 0. && face_angle_deg < 90.))
      throw std::invalid_argument(
          "Pyramid: the face-to-axis angle must satisfy 0 < theta < 90 deg, got " +
          std::to_string(face_angle_deg));
    if (!(tip_radius >= 0.) || !std::isfinite(tip_radius))
      throw std::invalid_argument("Pyramid: the tip radius must be >= 0 um, got " +
                                  std::to_string(tip_radius));
    if (!std::isfinite(rotation_deg))
      throw std::invalid_argument("Pyramid: the rotation must be a finite angle in degrees");

    sin_theta = std::sin(theta);
    const double cos_theta = std::cos(theta);
    for (unsigned int i = 0; i < n_faces; ++i)
      {
        double cos_phi = 0., sin_phi = 0.;
        cos_sin_deg(rotation_deg + 360. * i / n_faces, cos_phi, sin_phi);
        face_normals.emplace_back(
            Tensor<1, 3>({cos_theta * cos_phi, cos_theta * sin_phi, -sin_theta}));
      }
    // Edge k is the intersection line of faces k and k+1, pointing upwards.
    for (unsigned int k = 0; k < n_faces; ++k)
      {
        Tensor<1, 3> edge =
            dealii::cross_product_3d(face_normals[k], face_normals[(k + 1) % n_faces]);
        edge /= edge.norm();
        if (edge[2] < 0.)
          edge = -edge;
        edge_directions.push_back(edge);
      }
    edge_angle = std::atan(std::tan(theta) / std::cos(std::numbers::pi / n_faces));
  }

  Pyramid Pyramid::vickers(const double tip_radius, const double rotation_deg)
  {
    return Pyramid("vickers", 4, vickers_face_angle_deg, tip_radius, rotation_deg);
  }

  Pyramid Pyramid::berkovich(const double tip_radius, const double rotation_deg)
  {
    return Pyramid("berkovich", 3, berkovich_face_angle_deg, tip_radius, rotation_deg);
  }

  double Pyramid::sharp_area_coefficient() const
  {
    const double n = n_faces();
    const double tan_theta = std::tan(theta);
    return n * std::tan(std::numbers::pi / n) * tan_theta * tan_theta;
  }

  double Pyramid::blunting_offset() const
  {
    return R * (1. / sin_theta - 1.);
  }

  double Pyramid::corner_deficit() const
  {
    const double gamma = std::numbers::pi / 2. - std::numbers::pi / n_faces();
    const double cos_beta = std::cos(edge_angle);
    const double opened = std::atan(std::tan(gamma) / cos_beta);
    return R * R * (1. / std::tan(opened) - (std::numbers::pi / 2. - opened)) / cos_beta;
  }

  bool Pyramid::mirror_symmetric_about_xz_and_yz() const
  {
    // The mirror planes contain the axis and a face normal or an edge: azimuths rotation +
    // k 180/n. x = 0 is the plane at 90 deg, y = 0 the plane at 0 deg.
    const double spacing = 180. / n_faces();
    const auto   is_mirror_plane = [&](const double azimuth_deg) {
      return std::abs(std::remainder(azimuth_deg - rotation, spacing)) <= 1e-9;
    };
    return is_mirror_plane(0.) && is_mirror_plane(90.);
  }

  unsigned int Pyramid::faces_along_axes() const
  {
    unsigned int n = 0;
    for (unsigned int i = 0; i < n_faces(); ++i)
      if (std::abs(std::remainder(rotation + i * 360. / n_faces(), 90.)) <= 0.5)
        ++n;
    return n;
  }

  // The face plane n_i . (x, y, z) = 0 has the height (n_ix x + n_iy y) / sin(theta).
  double Pyramid::sharp_profile(const double x, const double y) const
  {
    double height = 0.;
    for (const auto &n : face_normals)
      height = std::max(height, (n[0] * x + n[1] * y) / sin_theta);
    return height;
  }

  double Pyramid::profile(const double x, const double y) const
  {
    const double sharp = sharp_profile(x, y);
    if (R == 0. || !std::isfinite(sharp))
      return sharp;
    // G(z) = gap at (x, y, z) (apex at the origin) is convex and decreasing with slope
    // n_z <= -sin(theta). On the sharp solid's surface (z = R + sharp) G = -R, so the root
    // lies in [R + sharp - R / sin(theta), R + sharp]; Newton from the lower end, where G >= 0,
    // climbs monotonically to it.
    const double upper = R + sharp;
    double       z = upper - R / sin_theta;
    const double tolerance = 4. * std::numeric_limits<double>::epsilon() * (upper + R);
    for (unsigned int iteration = 0; iteration < 100; ++iteration)
      {
        const SurfaceProjection p = project(Point<3>(x, y, z), 0.);
        const double            step = -p.gap / p.normal[2];
        z = std::clamp(z + step, 0., upper);
        if (std::abs(step) <= tolerance)
          break;
      }
    return z;
  }

  SurfaceProjection Pyramid::project(const Point<3> &x, const double depth) const
  {
    const double height = x[2] + depth;
    if (!std::isfinite(x[0]) || !std::isfinite(x[1]) || !std::isfinite(height))
      return failed_projection();

    // Position relative to the sharp solid's apex at (0, 0, R).
    const Tensor<1, 3> p({x[0], x[1], height - R});
    const Point<3>     apex(0., 0., R);
    const unsigned int n = n_faces();

    // Signed distances to the face planes; the point is inside the sharp solid iff all <= 0.
    std::array<double, max_faces> plane_distance{}; // no allocation per projection
    unsigned int                  nearest_plane = 0;
    for (unsigned int i = 0; i < n; ++i)
      {
        plane_distance[i] = face_normals[i] * p;
        if (plane_distance[i] > plane_distance[nearest_plane])
          nearest_plane = i;
      }

    SharpProjection sharp;
    if (plane_distance[nearest_plane] <= 0.)
      {
        // Inside: the ball of radius min_i |s_i| around p lies inside every half-space, so the
        // foot on the nearest plane lies on that face.
        const double s = plane_distance[nearest_plane];
        sharp.signed_distance = s;
        sharp.boundary_point = apex + (p - s * face_normals[nearest_plane]);
        sharp.normal = face_normals[nearest_plane];
        return offset_projection(sharp, R, depth);
      }

    // Outside: the projection onto the convex cone lies in a face's interior, on an edge ray or
    // at the apex; every candidate below is a point of the cone, so the nearest one is it.
    double       best = robust_norm(p); // the apex
    Tensor<1, 3> best_foot;             // relative to the apex
    Tensor<1, 3> best_normal;
    bool         best_is_face = false;
    for (unsigned int i = 0; i < n; ++i)
      {
        const double s = plane_distance[i];
        if (!(s > 0.) || !(s < best))
          continue;
        const Tensor<1, 3> foot = p - s * face_normals[i];
        bool               on_face = true;
        for (unsigned int j = 0; j < n && on_face; ++j)
          on_face = (j == i) || face_normals[j] * foot <= 0.;
        if (on_face)
          {
            best = s;
            best_foot = foot;
            best_normal = face_normals[i];
            best_is_face = true;
          }
      }
    bool         on_edge = false;
    unsigned int best_edge = 0;
    for (unsigned int k = 0; k < n; ++k)
      {
        const double t = edge_directions[k] * p;
        if (!(t > 0.))
          continue;
        const Tensor<1, 3> foot = t * edge_directions[k];
        const double       distance = robust_norm(p - foot);
        if (distance < best)
          {
            best = distance;
            best_foot = foot;
            best_is_face = false;
            on_edge = true;
            best_edge = k;
          }
      }
    if (!best_is_face)
      {
        if (!on_edge)
          best_foot = Tensor<1, 3>();
        const Tensor<1, 3> offset = p - best_foot;
        if (best > 0.)
          best_normal = offset / best;
        else if (on_edge)
          {
            // On the edge itself (only reachable through round-off): the bisecting normal.
            best_normal = face_normals[best_edge] + face_normals[(best_edge + 1) % n];
            best_normal /= best_normal.norm();
          }
        else
          best_normal = Tensor<1, 3>({0., 0., -1.});
      }
    sharp.signed_distance = best;
    sharp.boundary_point = apex + best_foot;
    sharp.normal = best_normal;
    return offset_projection(sharp, R, depth);
  }

  double Pyramid::projected_area(const double h) const
  {
    if (!(h > 0.))
      return 0.;
    const double n = n_faces();
    if (h >= R * (1. - sin_theta))
      {
        const double offset_h = h + blunting_offset();
        return sharp_area_coefficient() * offset_h * offset_h - n * corner_deficit();
      }
    // Below the faces' lowest point the section is the tip sphere's circle of radius rho_s,
    // with elliptic bulges of the edge cylinders once h > R (1 - sin(beta)).
    const double rho_s_squared = h * (2. * R - h);
    const double sin_beta = std::sin(edge_angle), cos_beta = std::cos(edge_angle);
    // The sphere point A + R u (|u| = 1, u_z = (h - R)/R) joins edge k's cylinder where u is
    // perpendicular to the edge: cos(phi - psi_k) = (R - h) cot(beta) / rho_s.
    const double junction_cosine = (R - h) * cos_beta / sin_beta / std::sqrt(rho_s_squared);
    if (junction_cosine >= 1.)
      return std::numbers::pi * rho_s_squared;
    const double half_width = std::acos(junction_cosine); // of the elliptic arc around psi_k

    // r(phi)^2 on the arc, phi measured from the edge: the larger root of
    // |w|^2 - (w.e)^2 = R^2, w = (r cos, r sin, h - R) relative to the apex A = (0, 0, R),
    // w.e = a r + b, a = sin(beta) cos(phi), b = (h - R) cos(beta).
    const double b = (h - R) * cos_beta;
    const double c = (h - R) * (h - R) * sin_beta * sin_beta - R * R;
    const auto   r_squared = [&](const double phi) {
      const double a = sin_beta * std::cos(phi);
      const double r =
          (a * b + std::sqrt(std::max(0., a * a * b * b - (1. - a * a) * c))) / (1. - a * a);
      return r * r;
    };
    const dealii::QGauss<1> gauss(20);
    double                  arc_integral = 0.;
    for (unsigned int q = 0; q < gauss.size(); ++q)
      arc_integral += gauss.weight(q) * half_width * r_squared(half_width * gauss.point(q)[0]);
    // 2n half-sectors of angle pi/n: sphere part plus elliptic part.
    return 2. * n *
           (0.5 * rho_s_squared * (std::numbers::pi / n - half_width) + 0.5 * arc_integral);
  }
} // namespace indentsim::indenter
