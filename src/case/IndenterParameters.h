// The rigid indenter (indenter.*). Lengths in um, angles in degrees.
#pragma once

#include "case/Choice.h"

#include <array>
#include <string>

namespace indentsim::io
{
  enum class IndenterShape
  {
    rounded_cone,
    sphere,
    cone,
    vickers,
    berkovich,
    flat_punch,
    profile_table
  };
  template <>
  struct ChoiceWords<IndenterShape>
  {
    static constexpr std::array<ChoiceWord<IndenterShape>, 7> words = {
        {{IndenterShape::rounded_cone, "rounded_cone"},
         {IndenterShape::sphere, "sphere"},
         {IndenterShape::cone, "cone"},
         {IndenterShape::vickers, "vickers"},
         {IndenterShape::berkovich, "berkovich"},
         {IndenterShape::flat_punch, "flat_punch"},
         {IndenterShape::profile_table, "profile_table"}}};
  };

  // Every key is read and range-checked for every shape, but each shape uses only its own keys
  // (listed after each member).
  struct IndenterParameters
  {
    Choice<IndenterShape> shape = IndenterShape::rounded_cone;
    double a = 2.48;              // rounded_cone: slope parameter [-] (eq. 16), half-angle atan(a)
    double delta = 0.005;         // rounded_cone: tip rounding [um], tip radius a^2 delta
    double radius = 10.0;         // sphere, flat_punch: radius [um]
    double half_angle_deg = 70.3; // cone: half-angle [deg] (70.3: the area function 24.5 h^2
                                  // of the Vickers and Berkovich pyramids)
    double tip_radius = 0.0;      // cone, vickers, berkovich: tip (and edge) radius [um], 0: sharp
                                  // (cone only: a pyramid needs > 0, CaseValidator)
    double rotation_deg = 0.0;    // vickers, berkovich: about +z, counterclockwise from above;
                                  // 0: face 0's normal along +x (Pyramid.h)
    double edge_radius = 0.0;     // flat_punch: rounding of the rim [um], 0: sharp
    // profile_table: the CSV table (ProfileTable.h). A relative path in a case file is relative
    // to the case file's directory; the reader stores the absolute path, so that the resolved
    // case works from any directory. In a Case built in code it is relative to the working
    // directory.
    std::string file = "";

    bool operator==(const IndenterParameters &) const = default;
  };
} // namespace indentsim::io
