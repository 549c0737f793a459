// The hardening table of J2 (material.hardening: {law: table, file: ...}) from a CSV file: the
// true stress against the equivalent plastic strain of a tensile test. Units: stress in GPa.
//
// Format: comma-separated; blank lines and lines starting with '#' are skipped (a UTF-8
// byte-order mark and CRLF line endings are accepted); the first other line is the header of
// two columns, the plastic strain (`plastic_strain`, dimensionless) and the stress with its
// unit in the name (`true_stress_GPa`, `true_stress_MPa`, `stress (MPa)`); every further line
// is one point. The rules of the table itself (from 0, increasing, non-decreasing stress) are
// checked with the case (materials/IsotropicHardening.h).
#pragma once

#include <string>
#include <vector>

namespace indentsim::io
{
  struct HardeningTable
  {
    std::vector<double> plastic_strain; // eps_p [-]
    std::vector<double> stress;         // true stress [GPa]
  };

  // Throws std::invalid_argument naming the line and what is allowed (not the file: the caller
  // names it with its key).
  HardeningTable read_hardening_table_csv(const std::string &path);
} // namespace indentsim::io
