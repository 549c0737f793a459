// Whether a mesh can hold an indent: the documented thresholds of the physics guards and the
// predictions and advice they print (docs/user-guide.md, "Guards on the mesh and the
// specimen"). `check` refuses a case whose refined region cannot hold the predicted contact
// (case/CaseValidator.cc); a run stops when the contact nears the edge of the refined region
// and warns about the plastic zone and the resolution of the contact
// (problems/IndentationGuards.cc). Units: um, mN, GPa.
//
// Contact nodes exist only on the refined region's top face (IndentationProblem::setup), so a
// contact that reaches its edge lets the specimen's surface pass through the indenter: the force
// beyond that depth means nothing.
#pragma once

#include "case/Case.h"
#include "indenter/IndenterSurface.h"

#include <optional>
#include <stdexcept>
#include <string>

namespace indentsim::mesh
{
  namespace guard
  {
    // The contact may cover at most this fraction of the refined region's half-width along x
    // and y (one element of 10 % margin on a 12 x 12 mesh, where the next ring of nodes that
    // touches moves the perimeter by a whole element).
    inline constexpr double refined_region_margin = 0.9;
    // check's prediction takes the area function at h_c = 1.2 h_max for the plastic models:
    // pile-up raises the contact above the ideal shape's cross-section at h_max (by 8-20 % in
    // depth for the paper's J2 material, E/sigma_y = 226, on 24 x 24 and 48 x 48 meshes).
    inline constexpr double pile_up_allowance = 1.2;
    // An elastic (neo-Hookean) surface sinks in: Sneddon's contact depth is h_c = (2/pi) h for
    // a cone and h/2 for a paraboloid; the prediction takes the cone's.
    inline constexpr double elastic_contact_depth_ratio = 2 / 3.141592653589793;
    // Fewer contact elements across the contact radius at the maximum depth give a warning:
    // with 4.7 elements the elastic Hertz force is 3 % high (tests/verification), and the
    // paper's J2 force moves by 8 % from 24 x 24 (3 elements) to 48 x 48 (6 elements).
    inline constexpr double min_elements_across_contact = 5;
    // A lateral contact force normal to a mirror plane of the indenter, the material and the
    // mesh, relative to the vertical force, beyond which the solution has broken the symmetry
    // (a node slid off a Berkovich edge: 5-15 %; the Vickers pyramid with R = 0.05 um at 0 deg on
    // the automatic mesh reaches 0.2 % about x = 0, cause unknown, so the guard flags only what
    // moves the force by per cents).
    inline constexpr double mirror_force = 1e-2;
    // The plastic zone: equivalent plastic strain above 0.2 % (the offset yield strain).
    inline constexpr double plastic_strain_threshold = 2e-3;
    // Force control: the hardness H = 3 sigma_y (Tabor's constraint factor; crystal:
    // sigma_y = 3.06 tau0, the Taylor factor of FCC polycrystals, which BCC {110}<111> shares:
    // its Schmid tensors' symmetric parts are FCC's with m and n swapped) gives the contact area
    // F/H. With several families, tau0 of the softest: the hardness is then underestimated and
    // the predicted contact overestimated, on the safe side of the guards.
    inline constexpr double constraint_factor = 3;
    inline constexpr double fcc_taylor_factor = 3.06;
  } // namespace guard

  // The contact (or predicted contact) patch's largest |x| and |y| [um].
  struct PatchExtent
  {
    double x = 0, y = 0;
  };

  // The extent of {(x, y): profile(x, y) < height} of the indenter: the boundary searched along
  // 720 rays from the axis. For an axisymmetric shape x = y = sqrt(A(height)/pi).
  PatchExtent indenter_extent(const indenter::IndenterSurface &surface, double height);

  // The largest fraction of the refined region's half-widths (refined_region[0]/2,
  // refined_region[1]/2) that `extent` covers.
  double refined_fraction(const PatchExtent &extent, const io::SpecimenParameters &specimen);

  struct ContactPrediction
  {
    PatchExtent extent;    // predicted at the maximum of the loading [um]
    double      depth = 0; // the maximum depth it is predicted at [um]
    std::string basis;     // how it was predicted, for the messages
  };
  // h_c / h_max of the prediction: pile_up_allowance for the plastic models,
  // elastic_contact_depth_ratio for neo-Hookean.
  double contact_depth_ratio(const io::Case &the_case);

  // The contact at the maximum of the loading. Depth control: the indenter's cross-section at
  // h_c = contact_depth_ratio * max_depth. Force control: the cross-section whose area is
  // max_force / H (H = 3 sigma_y), at most that at pile_up_allowance * max_depth (the run stops
  // beyond max_depth); no prediction for neo-Hookean under force control (no hardness).
  std::optional<ContactPrediction> predict_contact(const io::Case                  &the_case,
                                                   const indenter::IndenterSurface &surface);

  // The height h_c of the contact's edge above the indenter's apex at the maximum of the
  // loading, independent of the mesh: contact_depth_ratio * max_depth, or under force control
  // the smaller of that and the height whose cross-section is max_force / H (where the model
  // has a hardness) [um].
  double predicted_contact_height(const io::Case                  &the_case,
                                  const indenter::IndenterSurface &surface);

  // The largest loading.max_depth whose predicted contact the refined region holds [um].
  double largest_depth_held(const io::Case &the_case, const indenter::IndenterSurface &surface);

  // What to change so that the refined region holds a contact of `needed` extent with the
  // margin, keeping the contact-element size: "specimen.refined_region: [..] and
  // specimen.contact_elements: N (...)", with specimen.size when the region outgrows it.
  std::string enlargement_advice(const io::SpecimenParameters &specimen, const PatchExtent &needed);

  // The smallest valid contact_elements (a multiple of 4) that gives `elements` contact
  // elements across a contact radius `radius` on the case's refined region.
  unsigned int contact_elements_for(const io::SpecimenParameters &specimen, double radius,
                                    double elements);

  // A run whose contact has outgrown the refined region (exit code 5, apps/indentsim.cc).
  class MeshOutgrownError : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };

  // Up to 4 significant digits, for messages ("7.35", "120").
  std::string short_number(double value);
} // namespace indentsim::mesh
