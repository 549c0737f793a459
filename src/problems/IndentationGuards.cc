// The physics guards of an indentation run, checked after every accepted step
// (IndentationRun.cc; thresholds and advice in mesh/MeshAdequacy.h): the contact against the
// refined region (the run stops before the contact reaches its edge), the plastic zone against
// the specimen's faces, the contact-element resolution at the maximum, a damage profile cut
// off before its damage ends, a contact force that leaves a mirror plane of the problem and a
// pyramid whose faces run along the mesh lines (warnings).
// Units: um, mN, GPa.
#include "case/DamageProfile.h"
#include "case/Schema.h"
#include "indenter/Pyramid.h"
#include "mesh/MeshAdequacy.h"
#include "output/RunRecorder.h"
#include "problems/IndentationProblem.h"

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>
#include <numbers>
#include <sstream>

namespace indentsim::problems
{
  using namespace dealii;
  using mesh::short_number;
  namespace guard = mesh::guard;

  template <int dim>
  void IndentationProblem<dim>::check_guards(output::RunRecorder      &recorder,
                                             const nonlinear::Segment &segment,
                                             const StepRecord &record, const bool at_max)
  {
    check_refined_region(recorder, segment, record);
    check_plastic_zone(recorder);
    check_damage_profile_end(recorder);
    check_mirror_symmetry(recorder, record);
    check_faces_along_mesh_lines(recorder);
    if (at_max)
      check_contact_resolution(recorder, record);
  }

  template <int dim>
  void IndentationProblem<dim>::warn(output::RunRecorder &recorder, const std::string &topic,
                                     const std::string &text)
  {
    if (std::any_of(warnings_.begin(), warnings_.end(),
                    [&](const output::RunWarning &w) { return w.topic == topic; }))
      return;
    warnings_.push_back({topic, text});
    if (Utilities::MPI::this_mpi_process(communicator_) != 0)
      return;
    recorder.log_note("warning: " + text);
    if (pcout_.is_active())
      std::cerr << "indentsim: warning: " << text << std::endl;
  }

  // A damage profile whose last row still has more than 1 % of the peak's dose: below it the
  // substrate holds (the dose is 0 beyond the table), a step in strength the table may not mean.
  template <int dim>
  void IndentationProblem<dim>::check_damage_profile_end(output::RunRecorder &recorder)
  {
    const io::DamageProfileParameters &profile = case_.material.damage_profile;
    if (profile.dpa.empty() || !(profile.dpa.back() > 0.01 * io::peak_dose(profile)))
      return;
    std::ostringstream message;
    message << "material.damage_profile ends at " << short_number(profile.dpa.back()) << " dpa ("
            << short_number(100 * profile.dpa.back() / io::peak_dose(profile))
            << " % of its peak) at the depth " << short_number(profile.depth.back())
            << " um; below it the dose is 0 and the substrate holds: extend the table to where "
               "the damage ends (a row with 0 dpa) if the cut is not meant";
    warn(recorder, "damage_profile_end", message.str());
  }

  // The contact may cover at most guard::refined_region_margin of the refined region's
  // half-widths, and no active node may stand on the region's outermost ring of contact nodes
  // (reference positions: a check independent of the deformation).
  template <int dim>
  void IndentationProblem<dim>::check_refined_region(output::RunRecorder      &recorder,
                                                     const nonlinear::Segment &segment,
                                                     const StepRecord         &record)
  {
    const contact::ContactPatch   patch = contact_patch();
    const mesh::PatchExtent       reached{patch.max_abs_x, patch.max_abs_y};
    const io::SpecimenParameters &s = case_.specimen;
    const double half_x = mesh_info_.refined_half_x, half_y = mesh_info_.refined_half_y;
    const double tolerance = 1e-6 * mesh_info_.contact_element_size;
    unsigned int on_edge = 0;
    for (const contact::ContactNode &node : contact_->nodes())
      if (node.active &&
          (std::abs(node.X[0]) >= half_x - tolerance || std::abs(node.X[1]) >= half_y - tolerance))
        on_edge = 1;
    on_edge = Utilities::MPI::max(on_edge, communicator_);
    const double fraction = mesh::refined_fraction(reached, s);
    if (fraction <= guard::refined_region_margin && on_edge == 0)
      return;

    // The contact the refined region must hold at the end of the loading: this one grown to
    // the maximum (A ~ h^2 at depth control, A ~ F at force control), or check's prediction if
    // larger.
    const bool force_control = case_.loading.control == io::Control::force;
    double     growth = 1;
    if (segment.kind == nonlinear::SegmentKind::load && record.depth > 0 && record.force > 0)
      growth = force_control ? std::sqrt(std::max(1.0, case_.loading.max_force / record.force))
                             : std::max(1.0, case_.loading.max_depth / record.depth);
    // Active nodes on the outermost ring: the contact reaches the edge (the faces with hanging
    // nodes there are left out of the interpolated patch).
    const double      edge_x = on_edge ? std::max(reached.x, half_x) : reached.x;
    const double      edge_y = on_edge ? std::max(reached.y, half_y) : reached.y;
    mesh::PatchExtent needed{edge_x * growth, edge_y * growth};
    if (const auto prediction = mesh::predict_contact(case_, *indenter_))
      {
        needed.x = std::max(needed.x, prediction->extent.x);
        needed.y = std::max(needed.y, prediction->extent.y);
      }
    const bool         along_x = reached.x / half_x >= reached.y / half_y;
    std::ostringstream message;
    message << "the contact reached ";
    if (fraction > guard::refined_region_margin)
      message << short_number(along_x ? reached.x : reached.y) << " um from the axis along "
              << (along_x ? "x" : "y") << ", beyond "
              << short_number(100 * guard::refined_region_margin)
              << " % of the refined region's half-width " << short_number(along_x ? half_x : half_y)
              << " um,";
    else
      message << "the outermost ring of contact nodes (the edge of the refined region, half-width "
              << short_number(std::min(half_x, half_y)) << " um)";
    message << " at the depth " << short_number(record.depth) << " um (force "
            << short_number(record.force) << " mN, step " << record.step << ")"
            << ": contact nodes exist only on the refined region (specimen.refined_region = "
            << io::format_triple(s.refined_region) << ", specimen.contact_elements = "
            << (mesh_info_.graded ? std::string("auto") : std::to_string(s.contact_elements))
            << "), so beyond this step the specimen's surface would pass through the indenter "
               "and the force would mean nothing. The outputs up to this step are kept. ";
    if (mesh_info_.graded)
      message << "The automatic mesh was designed for a contact radius of "
              << short_number(s.grading.contact_radius) << " um (from "
              << (force_control ? "loading.max_force with the hardness 3 sigma_y, at most "
                                  "loading.max_depth"
                                : "loading.max_depth with the pile-up allowance")
              << "); the contact grew larger: "
              << (force_control ? "give loading.max_depth the depth the force reaches, or a "
                                  "smaller loading.max_force"
                                : "the material piles up more than the design allows; give "
                                  "contact_elements a number and a larger refined_region");
    else
      message << "For "
              << (force_control
                      ? "loading.max_force = " + short_number(case_.loading.max_force) + " mN"
                      : "loading.max_depth = " + short_number(case_.loading.max_depth) + " um")
              << " use " << mesh::enlargement_advice(s, needed) << ", or a smaller "
              << (force_control ? "loading.max_force" : "loading.max_depth");
    recorder.log_note("stopped: " + message.str());
    throw mesh::MeshOutgrownError(message.str());
  }

  // The plastic zone (cells whose quadrature points exceed the threshold of equivalent plastic
  // strain, located by their centres) against each face of the specimen except the top and
  // the symmetry planes: a warning once the elastic ligament between the zone and the face is
  // thinner than the zone's own reach from the indent axis (lateral faces) or from the surface
  // (bottom).
  template <int dim>
  void IndentationProblem<dim>::check_plastic_zone(output::RunRecorder &recorder)
  {
    // Reach of the zone towards +x, -x, +y, -y and -z (0: no plastic cell).
    std::array<double, 5> reach{};
    bool                  plastic = false;
    const unsigned int    n_q = history_.n_q_points(), n_state = history_.n_state();
    for (const auto &cell : solid_.dof_handler.active_cell_iterators())
      {
        if (!cell->is_locally_owned())
          continue;
        const std::span<const double> state = history_.converged(cell);
        double                        largest = 0;
        for (unsigned int q = 0; q < n_q; ++q)
          largest = std::max(
              largest, material_->equivalent_plastic_strain(state.subspan(q * n_state, n_state)));
        if (!(largest > guard::plastic_strain_threshold))
          continue;
        plastic = true;
        // The axisymmetric section's (r, z) stands for the zone's reach in every direction.
        const Point<dim> p = cell->center();
        const Point<3> c = dim == 3 ? Point<3>(p[0], p[1], p[dim - 1]) : Point<3>(p[0], p[0], p[1]);
        reach[0] = std::max(reach[0], c[0]);
        reach[1] = std::max(reach[1], -c[0]);
        reach[2] = std::max(reach[2], c[1]);
        reach[3] = std::max(reach[3], -c[1]);
        reach[4] = std::max(reach[4], -c[2]);
      }
    const bool any = Utilities::MPI::max(plastic ? 1u : 0u, communicator_) > 0;
    if (!any)
      return;
    for (double &r : reach)
      r = Utilities::MPI::max(r, communicator_);

    const io::SpecimenParameters &s = case_.specimen;
    const std::array<double, 5>   face_distance = {
          {s.size[0] / 2, s.size[0] / 2, s.size[1] / 2, s.size[1] / 2, s.size[2]}};
    const char *faces[5] = {"x = +", "x = -", "y = +", "y = -", "z = -"};
    const char *topics[5] = {"plastic_zone_x_max", "plastic_zone_x_min", "plastic_zone_y_max",
                             "plastic_zone_y_min", "plastic_zone_bottom"};
    for (unsigned int f = 0; f < 5; ++f)
      {
        if ((mesh_info_.quarter && (f == 1 || f == 3)) ||
            (mesh_info_.axisymmetric && f < 4 && f != 0))
          continue; // symmetry planes; the axisymmetric model has one lateral face r = R
        const double distance = face_distance[f] - reach[f];
        if (!(distance < reach[f]))
          continue;
        const bool         bottom = f == 4;
        std::ostringstream text;
        text << "the plastic zone (equivalent plastic strain > "
             << short_number(guard::plastic_strain_threshold) << ") reaches "
             << short_number(reach[f]) << " um "
             << (bottom ? "below the surface"
                        : std::string("from the indent axis towards ") + faces[f] +
                              short_number(face_distance[f]))
             << ", " << short_number(std::max(distance, 0.0)) << " um from the "
             << (bottom ? "fixed bottom face z = -" + short_number(s.size[2])
                        : std::string("lateral face ") + faces[f] + short_number(face_distance[f]))
             << ": closer than its own reach, so the "
             << (bottom ? "fixed bottom stiffens" : "free lateral face softens")
             << " the response and the force depends on the specimen's size; make "
             << (bottom ? "specimen.size[2] (now " + short_number(s.size[2]) + " um) at least " +
                              short_number(std::ceil(2 * reach[f])) + " um"
                        : std::string("specimen.size[") + (f < 2 ? "0" : "1") + "] (now " +
                              short_number(s.size[f < 2 ? 0 : 1]) + " um) at least " +
                              short_number(std::ceil(4 * reach[f])) + " um")
             << " (twice the zone's reach from the indent)";
        warn(recorder, mesh_info_.axisymmetric && f == 0 ? "plastic_zone_lateral" : topics[f],
             text.str());
      }
  }

  // At the maximum: the contact elements across the equivalent contact radius sqrt(A/pi).
  template <int dim>
  void IndentationProblem<dim>::check_contact_resolution(output::RunRecorder &recorder,
                                                         const StepRecord    &record)
  {
    // The recorded contact counts the area of the active nodes only, which is nothing like the
    // contact while it spans less than an element (one active node at the apex). The contact
    // radius is at least that of the indenter's cross-section at half the depth (the elastic
    // sink-in of a paraboloid, the deepest of Sneddon's profiles).
    const double geometric_radius =
        std::sqrt(indenter_->projected_area(0.5 * record.depth) / std::numbers::pi);
    const double radius =
        std::max(std::sqrt(record.contact_area / std::numbers::pi), geometric_radius);
    const double element = mesh_info_.element_size_at(radius);
    if (!(radius > 0) || radius / element >= guard::min_elements_across_contact)
      return;
    const io::SpecimenParameters &s = case_.specimen;
    if (mesh_info_.graded)
      {
        // The automatic mesh resolves contacts from max_depth / 8 (mesh/MeshDesign.h).
        std::ostringstream text;
        text << short_number(radius / element)
             << " elements across the contact radius at the maximum (a = " << short_number(radius)
             << " um at the depth " << short_number(record.depth)
             << " um): the automatic mesh was designed for a contact radius of "
             << short_number(s.grading.contact_radius)
             << " um; set loading.max_depth to the depth actually reached";
        warn(recorder, "contact_resolution", text.str());
        return;
      }
    const unsigned int needed =
        mesh::contact_elements_for(s, radius, guard::min_elements_across_contact);
    std::ostringstream text;
    text << short_number(radius / element)
         << " contact elements across the contact radius at the maximum (a = sqrt(A/pi) = "
         << short_number(radius) << " um at the depth " << short_number(record.depth)
         << " um, contact element " << short_number(element) << " um): fewer than "
         << short_number(guard::min_elements_across_contact)
         << ", so the force depends on the mesh by several per cent; specimen.contact_elements: "
         << needed << " (now " << s.contact_elements << ", on specimen.refined_region "
         << io::format_triple(s.refined_region) << ") gives "
         << short_number(guard::min_elements_across_contact) << " or more";
    if (needed > io::max_contact_elements)
      text << "; that is beyond the largest allowed, " << io::max_contact_elements
           << ": make specimen.refined_region smaller around this contact, or indent deeper";
    warn(recorder, "contact_resolution", text.str());
  }

  // The planes x = 0 and y = 0 that the indenter, the material and the full 3D model share:
  // the indenter's height is compared with its mirror image at 1 152 points of the refined
  // region's top face; the material must be isotropic (a crystal's orientation need not keep
  // the plane), and the model full (the quarter model's planes carry the symmetry reactions; the
  // axisymmetric one has no lateral force). The full model's mesh is symmetric about both planes.
  template <int dim>
  std::array<bool, 2> IndentationProblem<dim>::shared_mirror_planes() const
  {
    if (dim != 3 || mesh_info_.quarter || case_.material.model == io::ModelKind::crystal)
      return {false, false};
    std::array<bool, 2> planes{true, true};
    const double        reach = std::min(mesh_info_.refined_half_x, mesh_info_.refined_half_y);
    for (unsigned int i = 1; i <= 16; ++i)
      for (unsigned int k = 0; k < 72; ++k)
        {
          const double r = reach * i / 16, phi = 2 * std::numbers::pi * (k + 0.25) / 72;
          const double x = r * std::cos(phi), y = r * std::sin(phi);
          const double z = indenter_->profile(x, y), tolerance = 1e-9 * (std::abs(z) + r);
          planes[0] = planes[0] && std::abs(indenter_->profile(-x, y) - z) <= tolerance;
          planes[1] = planes[1] && std::abs(indenter_->profile(x, -y) - z) <= tolerance;
        }
    return planes;
  }

  // Where the indenter, the material and the mesh are mirror-symmetric about a plane, so is the
  // solution, and the contact force has no component normal to the plane (the symmetric branch
  // of the guard's test leaves less than 1e-9 of the vertical force). More than guard::mirror_force
  // means that the solution has left the symmetric branch: typically a node on a sharp edge of
  // the indenter has slid off onto one face, where the face's inclined normal pushes it on.
  template <int dim>
  void IndentationProblem<dim>::check_mirror_symmetry(output::RunRecorder &recorder,
                                                      const StepRecord    &record)
  {
    const Tensor<1, 3> force = contact_->summary().force_on_specimen;
    const double       vertical = std::abs(force[2]);
    for (const unsigned int d : {0u, 1u})
      {
        if (!mirror_planes_[d] || !(vertical > absolute_tolerance_) ||
            !(std::abs(force[d]) > guard::mirror_force * vertical))
          continue;
        const char         axis = d == 0 ? 'x' : 'y';
        std::ostringstream message;
        message << "at the depth " << short_number(record.depth) << " um the contact force has the "
                << "lateral component F_" << axis << " = " << short_number(force[d]) << " mN, "
                << short_number(100 * std::abs(force[d]) / vertical) << " % of the vertical "
                << short_number(vertical) << " mN, although the indenter, "
                << "the material and the mesh are mirror-symmetric about the plane " << axis
                << " = 0: the solution has broken that symmetry (typically a node on a sharp edge "
                   "of the indenter slid off onto one face) and its forces are the mesh's, not the "
                   "indenter's; give the tip a larger indenter.tip_radius (0.01 um or more; "
                   "docs/user-guide.md, \"Indenters\")";
        warn(recorder, "mirror_symmetry", message.str());
      }
  }

  // A pyramid whose every face runs parallel to the x-y lines of the meshes (Vickers at a
  // multiple of 90 deg): each face's contact edge reaches a whole row of surface nodes at once,
  // and the force climbs in stairs (validation.md, "Vickers and Berkovich on the automatic
  // mesh": +-3.5 % in C = P/h^2 at 0 deg, +-0.3 % at 22.5 deg, +-1.4 % at 45 deg).
  template <int dim>
  void IndentationProblem<dim>::check_faces_along_mesh_lines(output::RunRecorder &recorder)
  {
    const auto *pyramid = dynamic_cast<const indenter::Pyramid *>(indenter_.get());
    if (dim != 3 || pyramid == nullptr || pyramid->faces_along_axes() < pyramid->n_faces())
      return;
    std::ostringstream message;
    message << "indenter.rotation_deg = " << short_number(pyramid->rotation_deg())
            << ": every face of the " << pyramid->name()
            << " pyramid runs parallel to the mesh lines (x, y), so each face's contact edge "
               "reaches a whole row of surface nodes at once and the force climbs in stairs (on "
               "the automatic full mesh of the paper's J2 case, C = P/h^2 jumps by +-3.5 % from "
               "step to step; docs/validation.md); a single depth, such as the P_max of the "
               "Oliver-Pharr analysis, may fall on either side of a stair. For a smooth curve "
               "turn the pyramid off the mesh lines: rotation_deg: 22.5 on the full model "
               "(specimen.symmetry: full; with a crystal, turn material.orientation about z by "
               "the same angle: +-0.3 %), or 45 on the quarter model (faces along the mesh "
               "diagonals: +-1.4 %)";
    warn(recorder, "faces_along_mesh_lines", message.str());
  }

  template class IndentationProblem<2>;
  template class IndentationProblem<3>;
} // namespace indentsim::problems
