#include "materials/crystal/Orientation.h"
#include "materials/crystal/SlipSystems.h"

#include <deal.II/base/symmetric_tensor.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <sstream>
#include <stdexcept>

namespace indentsim::materials
{
  namespace
  {
    constexpr double degree = std::numbers::pi / 180.0;

    dealii::Tensor<1, 3> normalized(const std::array<double, 3> &v, const char *name)
    {
      const double norm = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
      if (!(norm > 0.0) || !std::isfinite(norm))
        {
          std::ostringstream message;
          message << name << " [" << v[0] << ", " << v[1] << ", " << v[2]
                  << "] must be a non-zero vector";
          throw std::invalid_argument(message.str());
        }
      dealii::Tensor<1, 3> result;
      for (unsigned int i = 0; i < 3; ++i)
        result[i] = v[i] / norm;
      return result;
    }
  } // namespace

  dealii::Tensor<2, 3> bunge_rotation(const std::array<double, 3> &euler_deg)
  {
    const double         c1 = std::cos(euler_deg[0] * degree), s1 = std::sin(euler_deg[0] * degree);
    const double         c = std::cos(euler_deg[1] * degree), s = std::sin(euler_deg[1] * degree);
    const double         c2 = std::cos(euler_deg[2] * degree), s2 = std::sin(euler_deg[2] * degree);
    dealii::Tensor<2, 3> g;
    g[0][0] = c1 * c2 - s1 * s2 * c;
    g[0][1] = s1 * c2 + c1 * s2 * c;
    g[0][2] = s2 * s;
    g[1][0] = -c1 * s2 - s1 * c2 * c;
    g[1][1] = -s1 * s2 + c1 * c2 * c;
    g[1][2] = c2 * s;
    g[2][0] = s1 * s;
    g[2][1] = -c1 * s;
    g[2][2] = c;
    return g;
  }

  std::array<double, 3> bunge_angles(const dealii::Tensor<2, 3> &g)
  {
    const double Phi = std::acos(std::clamp(g[2][2], -1.0, 1.0));
    double       phi1, phi2;
    if (std::abs(std::sin(Phi)) > 1e-10)
      {
        phi1 = std::atan2(g[2][0], -g[2][1]);
        phi2 = std::atan2(g[0][2], g[1][2]);
      }
    else
      {
        // Gimbal lock: only phi1 + phi2 (or phi1 - phi2) is defined; put it all in phi1.
        phi1 = std::atan2(g[0][1], g[0][0]);
        phi2 = 0.0;
      }
    const auto wrap = [](double angle) {
      angle /= degree;
      return angle < 0.0 ? angle + 360.0 : angle;
    };
    return {{wrap(phi1), Phi / degree, wrap(phi2)}};
  }

  dealii::Tensor<2, 3>
  rotation_from_surface_normal(const std::array<double, 3> &surface_normal,
                               const std::array<double, 3> &reference_direction)
  {
    const dealii::Tensor<1, 3> z = normalized(surface_normal, "surface_normal");
    const dealii::Tensor<1, 3> x = normalized(reference_direction, "reference_direction");
    if (std::abs(z * x) > 1e-6)
      {
        std::ostringstream message;
        message << "reference_direction [" << reference_direction[0] << ", "
                << reference_direction[1] << ", " << reference_direction[2]
                << "] is not perpendicular to surface_normal [" << surface_normal[0] << ", "
                << surface_normal[1] << ", " << surface_normal[2]
                << "] (their dot product must vanish, e.g. [1, -1, 0] for [1, 1, 1])";
        throw std::invalid_argument(message.str());
      }
    const dealii::Tensor<1, 3> y = dealii::cross_product_3d(z, x);
    // Columns of g are the sample axes in crystal components.
    dealii::Tensor<2, 3> g;
    for (unsigned int i = 0; i < 3; ++i)
      {
        g[i][0] = x[i];
        g[i][1] = y[i];
        g[i][2] = z[i];
      }
    return g;
  }

  std::vector<dealii::Tensor<2, 3>> random_orientations(const unsigned int  n,
                                                        const std::uint64_t seed)
  {
    std::mt19937_64 generator(seed);
    // 53 random bits -> uniform in [0, 1), identical on every platform.
    const auto uniform = [&generator]() { return double(generator() >> 11) * 0x1.0p-53; };
    std::vector<dealii::Tensor<2, 3>> result;
    result.reserve(n);
    for (unsigned int k = 0; k < n; ++k)
      {
        const double u1 = uniform(), u2 = uniform(), u3 = uniform();
        const double two_pi = 2.0 * std::numbers::pi;
        // Shoemake (1992): (w, x, y, z) uniform on the unit 3-sphere.
        const double w = std::sqrt(1.0 - u1) * std::sin(two_pi * u2);
        const double x = std::sqrt(1.0 - u1) * std::cos(two_pi * u2);
        const double y = std::sqrt(u1) * std::sin(two_pi * u3);
        const double z = std::sqrt(u1) * std::cos(two_pi * u3);
        // Rotation matrix of the unit quaternion; used as g (the uniform measure on SO(3) is
        // invariant under transposition, so g or g^T are equally uniform).
        dealii::Tensor<2, 3> g;
        g[0][0] = 1 - 2 * (y * y + z * z);
        g[0][1] = 2 * (x * y - z * w);
        g[0][2] = 2 * (x * z + y * w);
        g[1][0] = 2 * (x * y + z * w);
        g[1][1] = 1 - 2 * (x * x + z * z);
        g[1][2] = 2 * (y * z - x * w);
        g[2][0] = 2 * (x * z - y * w);
        g[2][1] = 2 * (y * z + x * w);
        g[2][2] = 1 - 2 * (x * x + y * y);
        result.push_back(g);
      }
    return result;
  }

  bool is_mirror_plane(const std::string &lattice, const dealii::Tensor<2, 3> &g,
                       const dealii::Tensor<1, 3> &sample_normal)
  {
    dealii::Tensor<1, 3> n = g * sample_normal;
    n /= n.norm();
    const dealii::Tensor<2, 3> reflection =
        dealii::Tensor<2, 3>(dealii::unit_symmetric_tensor<3>()) -
        2.0 * dealii::outer_product(n, n);
    for (const dealii::Tensor<2, 3> &operation : point_group(lattice))
      if ((operation - reflection).norm() < 1e-8)
        return true;
    return false;
  }
} // namespace indentsim::materials
