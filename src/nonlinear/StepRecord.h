// One row of the load-penetration record: the state at the end of a converged step of an
// indentation run. Forces and areas are those of the whole indent (multiplied by 4 for the
// quarter model). Units: um, mN, GPa, s.
#pragma once

#include <string>

namespace indentsim::nonlinear
{
  // The plastic zone's boundary: where plastic flow has begun, the boundary of Johnson's
  // expanding-cavity model (1e-4 is 1/40 of the yield strain of the paper's J2 material; the
  // zone is the same to 1 % with 1e-6).
  inline constexpr double plastic_zone_threshold = 1e-4;

  struct StepRecord
  {
    unsigned int step = 0;
    unsigned int cycle = 0;          // load-unload cycle of the programme (0: initial state)
    std::string  segment = "start";  // start | load | hold | unload | partial_unload | reload
    double       depth = 0;          // indenter apex depth [um]
    double       force = 0;          // indenter force [mN]
    double       contact_radius = 0; // largest radius of the interpolated perimeter [um]
    double       contact_area = 0;   // projected area inside the interpolated perimeter [um^2]
    unsigned int n_active_nodes = 0; // active nodes of the model (not symmetry-multiplied)
    unsigned int n_stick_nodes = 0;  // of them sticking (friction) ...
    unsigned int n_slip_nodes = 0;   // ... and slipping (all of them without friction)
    double       max_pressure = 0;   // largest nodal contact pressure (nominal) [GPa]
    unsigned int newton_iterations = 0;
    unsigned int augmentations = 0;
    unsigned int cutbacks = 0;
    double       max_penetration = 0; // [um]
    double       bottom_reaction = 0; // [mN], whole indent
    // The plastic zone (equivalent plastic strain above plastic_zone_threshold at a Gauss
    // point; reference positions): its depth below the surface and radius from the axis [um],
    // its volume [um^3] (whole indent) and the part of it within the layers of a depth-graded
    // specimen [um^3].
    double plastic_zone_depth = 0;
    double plastic_zone_radius = 0;
    double plastic_zone_volume = 0;
    double plastic_zone_layer_volume = 0;
    double wall_time = 0; // [s] since the start of the run
  };
} // namespace indentsim::nonlinear
