// Slip kinematics of a crystal lattice: the slip directions m_0^r and plane normals n_0^r of
// eq. 13, unit vectors in the crystal frame, grouped in families ({111}<110>, basal, ...). The
// crystal-plasticity integrator only sees the Schmid tensors m_0^r (x) n_0^r; the hardening law
// sees each system's family.
//
// Crystal frames. Cubic lattices (FCC, BCC): the cubic axes. Hexagonal (HCP): a1 along x, the c
// axis along z, y = z x a1 (the direction [0 1 -1 0] in Miller–Bravais indices); a Miller–Bravais
// direction [u v t w] is u a1 + v a2 + t a3 + w c with a1 = (1, 0, 0), a2 = (-1/2, sqrt 3/2, 0),
// a3 = -(a1 + a2), c = (0, 0, c/a), and the normal of the plane (h k i l) is
// (h, (h + 2 k)/sqrt 3, l / (c/a)) (lattice parameter a = 1).
//
// A family is generated from one seed (plane, direction) by the lattice's point group (48
// operations for cubic, 24 for hexagonal), two systems being one when their Schmid tensors are
// equal up to sign (slip runs both ways). FCC keeps the numbering of Schmid & Boas.
#pragma once

#include <deal.II/base/tensor.h>

#include <array>
#include <string>
#include <vector>

namespace indentsim::materials
{
  struct SlipSystems
  {
    std::string                       name;      // e.g. "bcc {110}<111> + {112}<111>"
    std::vector<dealii::Tensor<1, 3>> direction; // m_0^r, unit, crystal frame
    std::vector<dealii::Tensor<1, 3>> normal;    // n_0^r, unit, crystal frame, m . n = 0
    std::vector<unsigned int>         family;    // the family of system r (index into families)
    std::vector<std::string>          families;  // the family names, in the order given

    unsigned int size() const { return direction.size(); }
    // Schmid tensor m_0^r (x) n_0^r.
    dealii::Tensor<2, 3> schmid_tensor(unsigned int r) const;
  };

  // FCC {111}<110>: 4 planes x 3 directions = 12 systems, numbered as in Schmid & Boas
  // (planes (111), (-1-11), (1-1-1)... see the .cc for the table).
  SlipSystems fcc_slip_systems();

  // The families a lattice knows, with their system counts:
  //   fcc: {111}<110> (12);
  //   bcc: {110}<111> (12), {112}<111> (12), {123}<111> (24);
  //   hcp: basal (0001)<11-20> (3), prismatic {10-10}<11-20> (3), pyramidal_a {10-11}<11-20> (6),
  //        pyramidal_ca {10-11}<11-23> (first order, 12), pyramidal_ca2 {11-22}<11-23> (second
  //        order, 6).
  std::vector<std::string> known_slip_families(const std::string &lattice);
  // The families used when the case file names none: fcc {111}<110>; bcc {110}<111>; hcp basal,
  // prismatic and pyramidal_ca (the set of zirconium and titanium models).
  std::vector<std::string> default_slip_families(const std::string &lattice);
  // The number of systems of one family.
  unsigned int family_size(const std::string &lattice, const std::string &family);

  // The slip systems of `lattice` ("fcc", "bcc", "hcp") with the named families (empty: the
  // default ones), families in the order given; c_over_a is used for hcp only. Throws
  // std::invalid_argument naming the lattice or family and what is allowed.
  SlipSystems slip_systems(const std::string              &lattice,
                           const std::vector<std::string> &families = {}, double c_over_a = 0.0);

  // The proper and improper rotations of the lattice's point group in its crystal frame: 48
  // (cubic m-3m) or 24 (hexagonal 6/mmm).
  std::vector<dealii::Tensor<2, 3>> point_group(const std::string &lattice);

  // Miller–Bravais indices to crystal-frame vectors (see the header comment), lattice parameter
  // a = 1: the direction [u v t w] and the normal of the plane (h k i l), not normalised.
  dealii::Tensor<1, 3> miller_bravais_direction(const std::array<double, 4> &uvtw, double c_over_a);
  dealii::Tensor<1, 3> miller_bravais_plane_normal(const std::array<double, 4> &hkil,
                                                   double                       c_over_a);
} // namespace indentsim::materials
