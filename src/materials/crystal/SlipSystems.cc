#include "materials/crystal/SlipSystems.h"

#include <deal.II/base/symmetric_tensor.h>

#include <cmath>
#include <stdexcept>

namespace indentsim::materials
{
  using dealii::Tensor;

  Tensor<2, 3> SlipSystems::schmid_tensor(const unsigned int r) const
  {
    return dealii::outer_product(direction[r], normal[r]);
  }

  namespace
  {
    // A family's seed: plane and direction in the lattice's own indices (cubic: three Miller
    // indices, the fourth unused; hexagonal: four Miller–Bravais indices).
    struct FamilySeed
    {
      const char           *name;
      std::array<double, 4> plane, direction;
      unsigned int          count;
    };

    constexpr FamilySeed fcc_seeds[] = {{"{111}<110>", {1, 1, 1, 0}, {0, 1, -1, 0}, 12}};
    constexpr FamilySeed bcc_seeds[] = {{"{110}<111>", {1, -1, 0, 0}, {1, 1, 1, 0}, 12},
                                        {"{112}<111>", {1, 1, -2, 0}, {1, 1, 1, 0}, 12},
                                        {"{123}<111>", {1, 2, -3, 0}, {1, 1, 1, 0}, 24}};
    constexpr FamilySeed hcp_seeds[] = {{"basal", {0, 0, 0, 1}, {2, -1, -1, 0}, 3},
                                        {"prismatic", {1, 0, -1, 0}, {-1, 2, -1, 0}, 3},
                                        {"pyramidal_a", {1, 0, -1, 1}, {-1, 2, -1, 0}, 6},
                                        {"pyramidal_ca", {1, 0, -1, 1}, {-1, -1, 2, 3}, 12},
                                        {"pyramidal_ca2", {1, 1, -2, 2}, {-1, -1, 2, 3}, 6}};

    std::vector<FamilySeed> seeds(const std::string &lattice)
    {
      if (lattice == "fcc")
        return {std::begin(fcc_seeds), std::end(fcc_seeds)};
      if (lattice == "bcc")
        return {std::begin(bcc_seeds), std::end(bcc_seeds)};
      if (lattice == "hcp")
        return {std::begin(hcp_seeds), std::end(hcp_seeds)};
      throw std::invalid_argument("material.lattice = \"" + lattice +
                                  "\" is not supported; allowed: fcc, bcc, hcp");
    }

    FamilySeed seed(const std::string &lattice, const std::string &family)
    {
      const std::vector<FamilySeed> list = seeds(lattice);
      for (const FamilySeed &s : list)
        if (family == s.name)
          return s;
      std::string allowed;
      for (const FamilySeed &s : list)
        allowed += (allowed.empty() ? "" : ", ") + std::string(s.name);
      throw std::invalid_argument("material.slip_families: \"" + family +
                                  "\" is not a slip family of " + lattice +
                                  "; allowed: " + allowed);
    }

    Tensor<2, 3> rotation_about_z(const double angle)
    {
      Tensor<2, 3> R;
      R[0][0] = R[1][1] = std::cos(angle);
      R[0][1] = -std::sin(angle);
      R[1][0] = std::sin(angle);
      R[2][2] = 1;
      return R;
    }

    bool same(const Tensor<2, 3> &a, const Tensor<2, 3> &b)
    {
      return (a - b).norm() < 1e-9;
    }

    // The closure of a set of generators under multiplication.
    std::vector<Tensor<2, 3>> group_generated_by(const std::vector<Tensor<2, 3>> &generators)
    {
      std::vector<Tensor<2, 3>> group = {Tensor<2, 3>(dealii::unit_symmetric_tensor<3>())};
      for (std::size_t i = 0; i < group.size(); ++i)
        for (const Tensor<2, 3> &g : generators)
          {
            const Tensor<2, 3> product = g * group[i];
            bool               known = false;
            for (const Tensor<2, 3> &h : group)
              known = known || same(h, product);
            if (!known)
              group.push_back(product);
          }
      return group;
    }
  } // namespace

  std::vector<Tensor<2, 3>> point_group(const std::string &lattice)
  {
    Tensor<2, 3> inversion = -Tensor<2, 3>(dealii::unit_symmetric_tensor<3>());
    if (lattice == "hcp")
      {
        Tensor<2, 3> two_fold_x; // 2-fold rotation about a1
        two_fold_x[0][0] = 1;
        two_fold_x[1][1] = two_fold_x[2][2] = -1;
        return group_generated_by({rotation_about_z(M_PI / 3), two_fold_x, inversion});
      }
    seeds(lattice); // throws for an unknown lattice
    Tensor<2, 3> four_fold_z = rotation_about_z(M_PI / 2), three_fold; // and about [111]
    three_fold[0][2] = three_fold[1][0] = three_fold[2][1] = 1;
    return group_generated_by({four_fold_z, three_fold, inversion});
  }

  Tensor<1, 3> miller_bravais_direction(const std::array<double, 4> &uvtw, const double c_over_a)
  {
    // u a1 + v a2 + t a3 + w c
    return Tensor<1, 3>({uvtw[0] - 0.5 * uvtw[1] - 0.5 * uvtw[2],
                         std::sqrt(3.0) / 2 * (uvtw[1] - uvtw[2]), uvtw[3] * c_over_a});
  }

  Tensor<1, 3> miller_bravais_plane_normal(const std::array<double, 4> &hkil, const double c_over_a)
  {
    // h a1* + k a2* + l c*, the reciprocal vectors of (a1, a2, c)
    return Tensor<1, 3>({hkil[0], (hkil[0] + 2 * hkil[1]) / std::sqrt(3.0), hkil[3] / c_over_a});
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
    systems.families = {"{111}<110>"};
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
        systems.family.push_back(0);
      }
    return systems;
  }

  std::vector<std::string> known_slip_families(const std::string &lattice)
  {
    std::vector<std::string> names;
    for (const FamilySeed &s : seeds(lattice))
      names.emplace_back(s.name);
    return names;
  }

  std::vector<std::string> default_slip_families(const std::string &lattice)
  {
    if (lattice == "hcp")
      return {"basal", "prismatic", "pyramidal_ca"};
    return {known_slip_families(lattice).front()};
  }

  unsigned int family_size(const std::string &lattice, const std::string &family)
  {
    return seed(lattice, family).count;
  }

  SlipSystems slip_systems(const std::string &lattice, const std::vector<std::string> &families,
                           const double c_over_a)
  {
    const std::vector<std::string> names =
        families.empty() ? default_slip_families(lattice) : families;
    if (lattice == "fcc" && names == std::vector<std::string>{"{111}<110>"})
      return fcc_slip_systems();
    const bool hexagonal = lattice == "hcp";
    if (hexagonal && !(c_over_a > 0))
      throw std::invalid_argument("material.c_over_a = " + std::to_string(c_over_a) +
                                  " is not allowed; hcp needs c/a > 0 (e.g. 1.593 for Zr)");
    const std::vector<Tensor<2, 3>> group = point_group(lattice);
    SlipSystems                     systems;
    systems.name = lattice;
    for (const std::string &name : names)
      {
        const FamilySeed s = seed(lattice, name);
        for (const std::string &known : systems.families)
          if (known == name)
            throw std::invalid_argument("material.slip_families: \"" + name + "\" is listed twice");
        systems.name += (systems.families.empty() ? " " : " + ") + name;
        Tensor<1, 3> n0, m0;
        if (hexagonal)
          {
            n0 = miller_bravais_plane_normal(s.plane, c_over_a);
            m0 = miller_bravais_direction(s.direction, c_over_a);
          }
        else
          for (unsigned int i = 0; i < 3; ++i)
            {
              n0[i] = s.plane[i];
              m0[i] = s.direction[i];
            }
        n0 /= n0.norm();
        m0 /= m0.norm();
        const std::size_t first = systems.size();
        for (const Tensor<2, 3> &g : group)
          {
            const Tensor<1, 3> m = g * m0, n = g * n0;
            const Tensor<2, 3> P = dealii::outer_product(m, n);
            bool               known = false;
            for (std::size_t r = first; r < systems.size(); ++r)
              known =
                  known || same(P, systems.schmid_tensor(r)) || same(P, -systems.schmid_tensor(r));
            if (known)
              continue;
            systems.direction.push_back(m);
            systems.normal.push_back(n);
            systems.family.push_back(systems.families.size());
          }
        if (systems.size() - first != s.count)
          throw std::logic_error("slip family " + name + " generated " +
                                 std::to_string(systems.size() - first) + " systems, expected " +
                                 std::to_string(s.count));
        systems.families.push_back(name);
      }
    return systems;
  }
} // namespace indentsim::materials
