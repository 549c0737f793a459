// Slip kinematics of a crystal lattice: the slip directions m_0^r and plane normals n_0^r of
// eq. 13, unit vectors in the crystal frame (the lattice's cubic axes). A lattice is a value
// of this type; the crystal-plasticity integrator only sees the Schmid tensors m_0^r (x) n_0^r,
// so adding BCC or HCP families means adding a function here, not touching the integrator.
#pragma once

#include <deal.II/base/tensor.h>

#include <string>
#include <vector>

namespace indentsim::materials
{
  struct SlipSystems
  {
    std::string                       name;
    std::vector<dealii::Tensor<1, 3>> direction; // m_0^r, unit, crystal frame
    std::vector<dealii::Tensor<1, 3>> normal;    // n_0^r, unit, crystal frame, m . n = 0

    unsigned int size() const { return direction.size(); }
    // Schmid tensor m_0^r (x) n_0^r.
    dealii::Tensor<2, 3> schmid_tensor(unsigned int r) const;
  };

  // FCC {111}<110>: 4 planes x 3 directions = 12 systems, numbered as in Schmid & Boas
  // (planes (111), (-1-11), (1-1-1)... see the .cc for the table).
  SlipSystems fcc_slip_systems();

  // The slip systems of a lattice named in the case file ("fcc"). Throws std::invalid_argument
  // for any other name.
  SlipSystems slip_systems(const std::string &lattice);
} // namespace indentsim::materials
