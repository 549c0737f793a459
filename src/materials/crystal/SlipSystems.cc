#include "materials/crystal/SlipSystems.h"

#include <cmath>
#include <stdexcept>

namespace indentsim::materials
{
  dealii::Tensor<2, 3> SlipSystems::schmid_tensor(const unsigned int r) const
  {
    return dealii::outer_product(direction[r], normal[r]);
  }

  SlipSystems fcc_slip_systems()
  {
    // Plane normals {111} (Miller indices) and, for each, the three <110> directions lying in it.
    const int table[12][6] = {
        // n           m
        {1, 1, 1, 0, 1, -1},  {1, 1, 1, -1, 0, 1},   {1, 1, 1, 1, -1, 0},   {-1, -1, 1, 0, -1, -1},
        {-1, -1, 1, 1, 0, 1}, {-1, -1, 1, -1, 1, 0}, {1, -1, -1, 0, -1, 1}, {1, -1, -1, -1, 0, -1},
        {1, -1, -1, 1, 1, 0}, {-1, 1, -1, 0, 1, 1},  {-1, 1, -1, 1, 0, -1}, {-1, 1, -1, -1, -1, 0},
    };
    SlipSystems systems;
    systems.name = "fcc {111}<110>";
    for (const auto &row : table)
      {
        dealii::Tensor<1, 3> n, m;
        for (unsigned int i = 0; i < 3; ++i)
          {
            n[i] = row[i] / std::sqrt(3.0);
            m[i] = row[3 + i] / std::sqrt(2.0);
          }
        systems.normal.push_back(n);
        systems.direction.push_back(m);
      }
    return systems;
  }

  SlipSystems slip_systems(const std::string &lattice)
  {
    if (lattice == "fcc")
      return fcc_slip_systems();
    throw std::invalid_argument("material.lattice = \"" + lattice +
                                "\" is not supported; allowed: fcc");
  }
} // namespace indentsim::materials
