// One row of the load-penetration record: the state at the end of a converged step of an
// indentation run. Forces and areas are those of the whole indent (multiplied by 4 for the
// quarter model). Units: um, mN, GPa, s.
#pragma once

#include <string>

namespace indentsim::nonlinear
{
  struct StepRecord
  {
    unsigned int step = 0;
    unsigned int cycle = 0;          // load-unload cycle of the programme (0: initial state)
    std::string  segment = "start";  // start | load | hold | unload
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
    double       wall_time = 0;       // [s] since the start of the run
  };
} // namespace indentsim::nonlinear
