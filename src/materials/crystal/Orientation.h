// Crystal orientations as rotation matrices.
//
// Convention (Bunge, passive): the orientation g maps components in the sample frame to
// components in the crystal frame, v_crystal = g v_sample, with
//   g = R_z(phi2) R_x(Phi) R_z(phi1),   R_z(a) = [[c, s, 0], [-s, c, 0], [0, 0, 1]],
// so the rows of g are the crystal axes [100], [010], [001] written in the sample frame, and the
// columns of g are the sample axes x, y, z written in the crystal frame. Euler angles
// (0, 0, 0) put the crystal axes along the sample axes: the (001) plane is indented.
#pragma once

#include <deal.II/base/tensor.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace indentsim::materials
{
  // g from Bunge Euler angles (phi1, Phi, phi2) in degrees.
  dealii::Tensor<2, 3> bunge_rotation(const std::array<double, 3> &euler_deg);

  // Bunge Euler angles in degrees (phi1, phi2 in [0, 360), Phi in [0, 180]) of a rotation g.
  std::array<double, 3> bunge_angles(const dealii::Tensor<2, 3> &g);

  // g such that the crystal direction `surface_normal` [hkl] lies along the sample z axis and
  // the crystal direction `reference_direction` [uvw] along the sample x axis. Throws
  // std::invalid_argument (naming the vectors) if either is zero or they are not perpendicular
  // to within 1e-6 rad.
  dealii::Tensor<2, 3>
  rotation_from_surface_normal(const std::array<double, 3> &surface_normal,
                               const std::array<double, 3> &reference_direction);

  // Orientations drawn uniformly on SO(3) (Shoemake's uniform unit quaternions) from a 64-bit
  // Mersenne twister seeded with `seed`. The uniform deviates are formed bit by bit, so the
  // sequence is the same on every platform and compiler.
  std::vector<dealii::Tensor<2, 3>> random_orientations(unsigned int n, std::uint64_t seed);

  // True if the plane through the origin with sample-frame normal `sample_normal` is a mirror
  // plane of the lattice ("fcc", "bcc": m-3m, normals along <100> or <110>; "hcp": 6/mmm, the
  // basal plane and the planes containing c at multiples of 30 degrees from a1) for orientation
  // g: the reflection I - 2 n (x) n, n the crystal-frame normal, is in the point group. The
  // quarter model needs the planes x = 0 and y = 0 to be mirror planes.
  bool is_mirror_plane(const std::string &lattice, const dealii::Tensor<2, 3> &g,
                       const dealii::Tensor<1, 3> &sample_normal);
} // namespace indentsim::materials
