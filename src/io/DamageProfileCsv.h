// A damage profile (material.damage_profile.file) from CSV: the damage in displacements per
// atom against the depth below the original surface, as SRIM-type calculations give it.
// Units: depth um after conversion, damage dpa.
//
// Format (io/CsvTable.h for comments, delimiters and encodings): a header naming a depth column
// with its unit (`depth_um`, `depth_nm`, `depth (nm)`, `depth [µm]`; the first column starting
// with `depth`) and a `dpa` column (the first starting with `dpa` or `damage`); further
// columns are ignored. Every other line is one point. The rules of the profile itself (from
// >= 0, strictly increasing, doses >= 0) are checked with the case.
#pragma once

#include <string>
#include <vector>

namespace indentsim::io
{
  struct DamageProfileTable
  {
    std::vector<double> depth; // [um]
    std::vector<double> dpa;   // [dpa]
  };

  // Throws std::invalid_argument naming the line, the column and what is allowed (not the file:
  // the caller names it with its key).
  DamageProfileTable read_damage_profile_csv(const std::string &path);
} // namespace indentsim::io
