#include "materials/IsotropicHardening.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace indentsim::materials
{
  namespace
  {
    std::string number_text(const double value)
    {
      std::ostringstream text;
      text.precision(12);
      text << value;
      return text.str();
    }

    // `name` is the parameter, or an entry of it ("stress[2]").
    void require(const bool condition, const std::string &name, const double value,
                 const std::string &allowed)
    {
      if (!condition)
        throw InvalidHardeningParameter(name.substr(0, name.find('[')),
                                        name + " = " + number_text(value) + ": " + allowed);
    }

    void require_yield_stress(const double yield_stress)
    {
      require(yield_stress > 0.0 && std::isfinite(yield_stress), "yield_stress", yield_stress,
              "the initial yield stress must be positive and finite [GPa]");
    }

    void require_modulus(const double hardening_modulus)
    {
      require(hardening_modulus >= 0.0 && std::isfinite(hardening_modulus), "hardening_modulus",
              hardening_modulus, "the hardening modulus must be non-negative and finite [GPa]");
    }
  } // namespace

  IsotropicHardening IsotropicHardening::linear(const double yield_stress,
                                                const double hardening_modulus)
  {
    require_yield_stress(yield_stress);
    require_modulus(hardening_modulus);
    IsotropicHardening law;
    law.kind = Law::linear;
    law.yield_stress = yield_stress;
    law.hardening_modulus = hardening_modulus;
    return law;
  }

  IsotropicHardening IsotropicHardening::power(const double yield_stress,
                                               const double young_modulus, const double exponent)
  {
    require_yield_stress(yield_stress);
    require(young_modulus > 0.0 && std::isfinite(young_modulus), "young_modulus", young_modulus,
            "Young's modulus must be positive and finite [GPa]");
    require(exponent >= 0.0 && exponent < 1.0, "exponent", exponent,
            "the power-law exponent n must satisfy 0 <= n < 1 (0: perfect plasticity)");
    IsotropicHardening law;
    law.kind = Law::power;
    law.yield_stress = yield_stress;
    law.young_modulus = young_modulus;
    law.exponent = exponent;
    return law;
  }

  IsotropicHardening IsotropicHardening::voce(const double yield_stress, const double saturation,
                                              const double rate, const double hardening_modulus)
  {
    require_yield_stress(yield_stress);
    require(saturation >= 0.0 && std::isfinite(saturation), "saturation", saturation,
            "the Voce saturation Q must be non-negative and finite [GPa]");
    require(rate > 0.0 && std::isfinite(rate), "rate", rate,
            "the Voce rate b must be positive and finite");
    require_modulus(hardening_modulus);
    IsotropicHardening law;
    law.kind = Law::voce;
    law.yield_stress = yield_stress;
    law.saturation = saturation;
    law.rate = rate;
    law.hardening_modulus = hardening_modulus;
    return law;
  }

  IsotropicHardening IsotropicHardening::table(std::vector<double> plastic_strain,
                                               std::vector<double> stress)
  {
    if (plastic_strain.size() != stress.size())
      throw InvalidHardeningParameter("stress",
                                      "the table has " + std::to_string(plastic_strain.size()) +
                                          " plastic strains and " + std::to_string(stress.size()) +
                                          " stresses; give one stress per plastic strain");
    if (plastic_strain.size() < 2)
      throw InvalidHardeningParameter("plastic_strain", "the table has " +
                                                            std::to_string(plastic_strain.size()) +
                                                            " point; it needs at least 2");
    require(plastic_strain[0] == 0.0, "plastic_strain[0]", plastic_strain[0],
            "the table must start at plastic strain 0 (the initial yield stress)");
    for (std::size_t i = 1; i < plastic_strain.size(); ++i)
      require(plastic_strain[i] > plastic_strain[i - 1] && std::isfinite(plastic_strain[i]),
              "plastic_strain[" + std::to_string(i) + "]", plastic_strain[i],
              "the plastic strains must increase strictly (the previous one is " +
                  number_text(plastic_strain[i - 1]) + ") and be finite");
    require(stress[0] > 0.0 && std::isfinite(stress[0]), "stress[0]", stress[0],
            "the first stress is the initial yield stress and must be positive and finite [GPa]");
    for (std::size_t i = 1; i < stress.size(); ++i)
      require(stress[i] >= stress[i - 1] && std::isfinite(stress[i]),
              "stress[" + std::to_string(i) + "]", stress[i],
              "the stresses must not decrease (the previous one is " + number_text(stress[i - 1]) +
                  " GPa; softening is not supported) and be finite");

    IsotropicHardening law;
    law.kind = Law::table;
    law.yield_stress = stress[0];
    for (std::size_t i = 0; i + 1 < stress.size(); ++i)
      law.table_slope.push_back((stress[i + 1] - stress[i]) /
                                (plastic_strain[i + 1] - plastic_strain[i]));
    law.table_strain = std::move(plastic_strain);
    law.table_stress = std::move(stress);
    return law;
  }

  unsigned int IsotropicHardening::n_segments() const
  {
    return kind == Law::table ? static_cast<unsigned int>(table_slope.size()) : 1;
  }

  unsigned int IsotropicHardening::segment(const double eps_p) const
  {
    if (kind != Law::table)
      return 0;
    // The last table point at or below eps_p, capped at the last segment.
    const auto above = std::upper_bound(table_strain.begin(), table_strain.end(), eps_p);
    const long index = std::distance(table_strain.begin(), above) - 1;
    return static_cast<unsigned int>(std::clamp(index, 0L, long(table_slope.size()) - 1));
  }

  double IsotropicHardening::segment_start(const unsigned int k) const
  {
    return kind == Law::table ? table_strain[k] : 0.0;
  }

  double IsotropicHardening::segment_end(const unsigned int k) const
  {
    return kind == Law::table && k + 1 < table_slope.size()
               ? table_strain[k + 1]
               : std::numeric_limits<double>::infinity();
  }

  IsotropicHardening::FlowStress IsotropicHardening::segment_line(const unsigned int k,
                                                                  const double       eps_p) const
  {
    if (kind == Law::linear)
      return {yield_stress + hardening_modulus * eps_p, hardening_modulus};
    return {table_stress[k] + table_slope[k] * (eps_p - table_strain[k]), table_slope[k]};
  }

  IsotropicHardening::FlowStress IsotropicHardening::evaluate(const double eps_p) const
  {
    if (piecewise_linear())
      return segment_line(segment(eps_p), eps_p);
    if (eps_p >= 0.0)
      return evaluate_nonnegative(eps_p);
    // Below 0 (Newton iterates only): the tangent line at 0.
    const FlowStress at_zero = evaluate_nonnegative(0.0);
    return {at_zero.stress + at_zero.slope * eps_p, at_zero.slope};
  }

  IsotropicHardening::FlowStress IsotropicHardening::evaluate_nonnegative(const double eps_p) const
  {
    switch (kind)
      {
      case Law::power:
        {
          // sigma_y0 (1 + E eps_p / sigma_y0)^n, h = E n (1 + E eps_p / sigma_y0)^(n - 1)
          const double base = 1.0 + young_modulus * eps_p / yield_stress;
          const double stress = yield_stress * std::pow(base, exponent);
          return {stress, young_modulus * exponent * stress / (yield_stress * base)};
        }
      case Law::voce:
        {
          // sigma_y0 + Q (1 - exp(-b eps_p)) + H eps_p, h = Q b exp(-b eps_p) + H
          const double decay = std::exp(-rate * eps_p);
          return {yield_stress - saturation * std::expm1(-rate * eps_p) + hardening_modulus * eps_p,
                  saturation * rate * decay + hardening_modulus};
        }
      case Law::linear:
      case Law::table:
        break;
      }
    return segment_line(segment(eps_p), eps_p);
  }
} // namespace indentsim::materials
