// The augmented-Lagrangian Newton solver of one increment of IndentationProblem, in the steps
// of deal.II's step-42: a predictor, then augmentation passes (eqs. 17-18); each pass is a
// semi-smooth Newton iteration on the residual whose contact active set only grows within the
// pass (NodeToSurfaceContact::start_pass), with a backtracking line search and, when the active
// set still cycles, a frozen active set. Under force control the depth h is a further
// unknown (a bordered Newton system). Units: um, mN, GPa.
#include "problems/IndentationProblem.h"

#include <deal.II/base/utilities.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>

namespace indentsim::problems
{
  using namespace dealii;
  using nonlinear::IncrementStatus;
  using ActiveSet = contact::NodeToSurfaceContact::ActiveSet;

  // The state of one increment's Newton solve, over all its passes.
  template <int dim>
  struct IndentationProblem<dim>::NewtonIncrement
  {
    NewtonIncrement(const IndexSet &owned, const MPI_Comm communicator, const double depth_start,
                    const std::optional<double> target_force, const double symmetry_factor,
                    const double force_scale)
      : depth(depth_start)
      , force_control(target_force.has_value())
      , model_force_target(force_control ? *target_force / symmetry_factor : 0.0)
      , depth_start_of_step(depth_start)
      , reference(force_scale)
      , du(owned, communicator)
      , u_owned(owned, communicator)
      , u_start(owned, communicator)
    {
      if (force_control)
        {
          residual_derivative.reinit(owned, communicator);
          force_gradient.reinit(owned, communicator);
          coupled_update.reinit(owned, communicator);
          coupling.residual_derivative = &residual_derivative;
          coupling.force_gradient = &force_gradient;
        }
    }

    // Under force control the depth h is an unknown: it starts at the guess and moves with the
    // Newton updates; under depth control it stays fixed.
    double       depth;
    const bool   force_control;
    const double model_force_target; // the force target of the model (quarter: a quarter) [mN]
    PETScWrappers::MPI::Vector residual_derivative, force_gradient, coupled_update;
    contact::NodeToSurfaceContact::DepthCoupling coupling;
    double depth_start_of_step; // h at the start of the Newton step (line search)
    double depth_update = 0;
    // Scale of the relative convergence test [mN]: the largest indenter force (model) of the
    // run's converged states and the largest reaction of the bottom face at this increment's
    // iterates after a Newton update. Forces the body carries, not the first residual or the
    // iterates' contact force: both grow with the contact penalty times the penetration of an
    // iterate (the predictor's first residual is 4 to 18 times the force with the automatic
    // penalty, hundreds of times with a penalty 100 times larger), and a tolerance relative to
    // them would accept iterates whose force is off by as much. The largest force so far keeps
    // the test meaningful where the force falls towards zero (unloading) and where an
    // increment was cut back to a tiny size (the residual cannot fall below the round-off of
    // the element forces).
    double reference;
    // The increment's first residual: a residual 1e10 times it and the reference has diverged.
    double                     first_norm = 0;
    PETScWrappers::MPI::Vector du, u_owned, u_start;
    unsigned int               last_linear_iterations = 0;
    unsigned int               pass = 0;
    // The element part of residual_ and matrix_ belongs to solution_ and was assembled with the
    // matrix: a pass that starts right after an augmentation replaces the contact part only.
    bool            element_system_current = false;
    AssemblyResult  last_assembly;
    IncrementStatus failure = IncrementStatus::converged; // why the increment failed
  };

  // The state of one augmentation pass, and of its current iterate.
  template <int dim>
  struct IndentationProblem<dim>::NewtonPass
  {
    static constexpr double min_alpha = 1. / 16;
    double                  previous_norm = std::numeric_limits<double>::infinity();
    double                  alpha = 1;      // line-search step length of the last update
    bool                    frozen = false; // the active set is frozen (it cycled)
    bool   freezing = false;    // ... from the next iterate on, which decides the set freely
    double pass_start_norm = 0; // |R| at the first iterate of this pass
    // |R| at the last two iterates of this pass (for the prediction below): the last one,
    // whether it was the predictor, and the one before if a full Newton step joined them.
    double norm_one_back = 0, norm_two_back = 0;
    bool   one_back_predictor = false;

    // The current iterate.
    bool           predictor = false;
    bool           matrix_assembled = true;
    bool           search_failed = false;
    AssemblyResult assembly;
    double         force_error = 0; // force control: F(u, h) - F* [mN]
  };

  namespace
  {
    void log_iterate(ConditionalOStream &out, const unsigned int pass, const unsigned int it,
                     const std::string &text)
    {
      out << "      pass " << pass << " it " << std::setw(2) << it << "  " << text << std::endl;
    }
  } // namespace

  template <int dim>
  IncrementStatus IndentationProblem<dim>::solve_increment(const double                depth_start,
                                                           StepRecord                 &record,
                                                           const bool                  extrapolate,
                                                           const std::optional<double> target_force)
  {
    NewtonIncrement increment(solid_.locally_owned, communicator_, depth_start, target_force,
                              symmetry_factor(), converged_force_scale_);
    record.newton_iterations = 0;
    record.augmentations = 0;
    depth_trial_ = increment.depth;
    if (extrapolate && has_previous_)
      apply_predictor(increment);

    const double tolerance = case_.contact.penetration_tolerance;
    for (; increment.pass <= case_.contact.max_augmentations; ++increment.pass)
      {
        NewtonPass pass;
        contact_->start_pass();
        IterateOutcome outcome = IterateOutcome::next_iterate;
        for (unsigned int it = 0; it <= case_.solver.max_newton_iterations; ++it)
          {
            outcome = newton_iteration(increment, pass, it, record);
            if (outcome != IterateOutcome::next_iterate)
              break;
          }
        if (outcome == IterateOutcome::failed)
          return increment.failure;
        if (outcome != IterateOutcome::converged && outcome != IterateOutcome::augment_early)
          return IncrementStatus::too_many_iterations;

        // Augmented until no node penetrates, no node carrying pressure stands off the indenter
        // (p g = 0 of eq. 17: a multiplier from an earlier pass can hold a node that has
        // separated) and the sticking nodes do not slip (eq. 18), to the tolerance.
        const contact::ContactSummary summary = contact_->summary();
        if (outcome == IterateOutcome::converged && summary.conditions_met(tolerance))
          {
            fill_converged_record(increment.depth, record);
            return IncrementStatus::converged;
          }
        // From the fourth pass on, nodes that alternate between penetrating and standing off are
        // damped (NodeToSurfaceContact::augment); earlier passes are the plain Uzawa update.
        const double multiplier_change = contact_->augment(increment.pass >= 3, tolerance);
        pcout_ << "      pass " << increment.pass << "  augmented: penetration " << std::scientific
               << std::setprecision(2) << summary.max_penetration << " um, active gap "
               << summary.max_active_gap << " um, largest multiplier change " << multiplier_change
               << " mN" << std::defaultfloat << std::endl;
        ++record.augmentations;
        ++statistics_.augmentations;
      }
    return IncrementStatus::too_many_augmentations;
  }

  // Predictor: linear extrapolation of the last two converged states to the new depth when the
  // indenter keeps its direction (not at the reversal to unloading, where the response changes
  // from plastic to elastic). It satisfies the homogeneous constraints and saves the first
  // Newton iterations' walk from the old state. run() retries a failed extrapolated increment
  // from the converged state before it cuts the increment back.
  template <int dim>
  void IndentationProblem<dim>::apply_predictor(NewtonIncrement &increment)
  {
    const double last = depth_converged_ - depth_previous_;
    const double ratio = last != 0 ? (increment.depth - depth_converged_) / last : 0;
    if (!(ratio > 0 && ratio <= 2))
      return;
    increment.u_owned = solution_converged_;
    increment.u_start = solution_converged_;
    increment.u_start -= solution_previous_;
    increment.u_owned.add(ratio, increment.u_start);
    solution_ = increment.u_owned;
    contact_->extrapolate_multipliers(ratio);
  }

  // One iterate of a pass: evaluate it, then a line-search step back, a convergence or
  // augmentation decision, or the Newton update to the next iterate.
  template <int dim>
  typename IndentationProblem<dim>::IterateOutcome
  IndentationProblem<dim>::newton_iteration(NewtonIncrement &increment, NewtonPass &pass,
                                            const unsigned int it, StepRecord &record)
  {
    const bool   failed = evaluate_iterate(increment, pass, it);
    const double norm = failed ? std::numeric_limits<double>::infinity()
                               : std::hypot(residual_.l2_norm(), pass.force_error);
    // Newton with a backtracking line search on the residual norm: a full step that fails in a
    // material point or raises the residual (typically an active-set change of the contact) is
    // shortened, down to 1/16; contact chattering and large trial strains are damped instead
    // of cutting the whole increment back.
    if (it > 0 && pass.alpha > NewtonPass::min_alpha && !(norm <= pass.previous_norm))
      {
        pass.alpha = nonlinear::line_search_step(pass.alpha, pass.previous_norm, norm,
                                                 NewtonPass::min_alpha);
        // The rejected iterate's contact statuses go with it.
        contact_->reject_last_evaluation();
        if (pass.alpha <= NewtonPass::min_alpha && !pass.frozen)
          {
            // The semi-smooth iteration cycles between active sets: freeze the set of the
            // damped iterate (decided freely there), converge with it, then check it
            // (check_convergence).
            pass.frozen = true;
            pass.freezing = true;
            log_iterate(pcout_, increment.pass, it, "active set frozen");
          }
        increment.u_owned = increment.u_start;
        increment.u_owned.add(pass.alpha, increment.du);
        solution_ = increment.u_owned;
        increment.depth = increment.depth_start_of_step + pass.alpha * increment.depth_update;
        pcout_ << "      pass " << increment.pass << " it " << std::setw(2) << it
               << "  line search: step length " << pass.alpha << std::endl;
        return IterateOutcome::next_iterate;
      }
    if (pass.search_failed || failed)
      {
        if (!pass.search_failed)
          pcout_ << "      material point: " << materials::to_string(pass.assembly.status)
                 << std::endl;
        increment.failure = pass.search_failed ? IncrementStatus::contact_search_failure
                                               : IncrementStatus::material_failure;
        return IterateOutcome::failed;
      }
    record.bottom_reaction = pass.assembly.bottom_reaction;

    if (it > 0 && pass.alpha == 1 && pass.norm_one_back > 0)
      newton_reduction_.at(increment.pass, it) = norm / pass.norm_one_back;
    if (increment.pass == 0 && it == 0)
      increment.first_norm = norm;
    if (it > 0)
      increment.reference = std::max(increment.reference, std::abs(pass.assembly.bottom_reaction));
    pcout_ << "      pass " << increment.pass << " it " << std::setw(2) << it
           << "  |R| = " << std::scientific << std::setprecision(3) << norm << " mN"
           << std::defaultfloat;
    if (statistics_.linear_solves > 0 && it > 0 &&
        linear_solver_.kind() == linalg::LinearSolver::Kind::iterative)
      pcout_ << "  (last linear solve: " << increment.last_linear_iterations << " iterations)";
    pcout_ << std::endl;
    if (!std::isfinite(norm) ||
        norm > 1e10 * std::max({increment.reference, increment.first_norm, absolute_tolerance_}))
      {
        increment.failure = IncrementStatus::newton_diverged;
        return IterateOutcome::failed;
      }
    if (it == 0)
      pass.pass_start_norm = norm;

    if (const std::optional<IterateOutcome> end = check_convergence(increment, pass, it, norm))
      return *end;
    if (it == case_.solver.max_newton_iterations)
      return IterateOutcome::out_of_iterations;
    if (!pass.matrix_assembled)
      {
        // The prediction missed: the matrix of this iterate (its residual again, the same to
        // the bit).
        ++statistics_.residual_first_misses;
        if (assemble(true).status != materials::UpdateStatus::success)
          {
            increment.failure = IncrementStatus::material_failure;
            return IterateOutcome::failed;
          }
      }
    increment.failure = newton_update(increment, pass, norm);
    if (increment.failure != IncrementStatus::converged)
      return IterateOutcome::failed;
    ++record.newton_iterations;
    return IterateOutcome::next_iterate;
  }

  // The residual at which a pass ends: converged, or (a pass that is not the last) cut by 1e-3
  // and ready for an inexact augmentation [mN].
  namespace
  {
    double pass_end_threshold(const io::Case &the_case, const double absolute_tolerance,
                              const double reference, const unsigned int pass,
                              const double pass_start_norm)
    {
      return std::max({the_case.solver.residual_tolerance * reference, absolute_tolerance,
                       pass < the_case.contact.max_augmentations ? 1e-3 * pass_start_norm : 0.0});
    }
  } // namespace

  // Contact search and assembly at the current iterate; returns whether it failed (the search
  // or a material point). Residual first: an iterate that will probably end its pass
  // (converged, or an inexact pass ready to augment) needs its residual but not its matrix. When
  // the predicted residual (nonlinear::predicted_residual) falls below half the pass's end
  // threshold, the matrix waits until the residual says it is needed (then assembled at the same
  // iterate: the same numbers, bitwise, so the prediction only changes the cost).
  template <int dim>
  bool IndentationProblem<dim>::evaluate_iterate(NewtonIncrement &increment, NewtonPass &pass,
                                                 const unsigned int it)
  {
    pass.predictor = (increment.pass == 0 && it == 0);
    pass.matrix_assembled = true;
    if (!pass.predictor && !increment.force_control && !pass.frozen && pass.alpha == 1 &&
        pass.norm_one_back > 0)
      {
        const double end_threshold = pass_end_threshold(
            case_, absolute_tolerance_, increment.reference, increment.pass, pass.pass_start_norm);
        const double predicted = nonlinear::predicted_residual(
            pass.norm_one_back, pass.norm_two_back, newton_reduction_.at(increment.pass, it));
        pass.matrix_assembled = !(predicted <= 0.5 * end_threshold);
      }
    {
      const output::RunStatistics::Scope contact_timer(statistics_.contact);
      const ActiveSet                    mode = pass.predictor ? ActiveSet::predictor
                                                : (pass.frozen && !pass.freezing) ? ActiveSet::frozen
                                                                                  : ActiveSet::free;
      pass.freezing = false;
      const bool searched = contact_->evaluate(solution_, increment.depth, mode);
      pass.search_failed =
          Utilities::MPI::max(static_cast<unsigned int>(!searched), communicator_) > 0;
    }
    // An iterate predicted to end its pass while the contact conditions are not met yet ends
    // it by an augmentation: its matrix serves the next pass's first iterate (below), at the
    // same displacement, so it is assembled now.
    if (!pass.matrix_assembled && !pass.search_failed &&
        increment.pass < case_.contact.max_augmentations)
      pass.matrix_assembled =
          !contact_->summary().conditions_met(case_.contact.penetration_tolerance);
    if (increment.force_control)
      {
        increment.residual_derivative = 0;
        increment.force_gradient = 0;
        increment.coupling.force_derivative = 0;
      }
    const bool contact_only = increment.pass > 0 && it == 0 && increment.element_system_current &&
                              !pass.search_failed && reassemble_contact();
    pass.assembly = pass.search_failed ? AssemblyResult{}
                    : contact_only
                        ? increment.last_assembly
                        : assemble(pass.matrix_assembled,
                                   increment.force_control ? &increment.coupling : nullptr);
    increment.element_system_current = !increment.force_control && pass.matrix_assembled &&
                                       pass.assembly.status == materials::UpdateStatus::success;
    increment.last_assembly = pass.assembly;
    const bool failed =
        pass.search_failed || pass.assembly.status != materials::UpdateStatus::success;
    // Force control adds the force equation F(u, h) - F* = 0 to the residual [mN].
    pass.force_error = 0;
    if (increment.force_control)
      {
        // Collective on every rank, also after a failed material update.
        increment.residual_derivative.compress(VectorOperation::add);
        increment.force_gradient.compress(VectorOperation::add);
        increment.coupling.force_derivative =
            Utilities::MPI::sum(increment.coupling.force_derivative, communicator_);
        if (!failed)
          pass.force_error = contact_->summary().force_z - increment.model_force_target;
      }
    return failed;
  }

  // Ends the pass when it may: an inexact augmentation, or convergence (with a frozen active
  // set, only if the set is consistent). Empty: the iterate takes a Newton update.
  template <int dim>
  std::optional<typename IndentationProblem<dim>::IterateOutcome>
  IndentationProblem<dim>::check_convergence(NewtonIncrement &increment, NewtonPass &pass,
                                             const unsigned int it, const double norm)
  {
    // Inexact augmentation: a pass that is not the last need not converge to the final
    // tolerance. Once Newton has cut this pass's residual by 1e-3 (its quadratic phase), or once
    // the residual is below a tenth of the residual the multiplier update will create
    // (augmentation_jump), an iterate that still penetrates clearly (twice the tolerance) is
    // augmented at once: the next pass starts from a residual that the skipped iteration would
    // hardly have changed. The last pass always converges fully, and the constraints are checked
    // on its converged state, so the answer is the same to the tolerances.
    if (!pass.predictor && !pass.frozen && it > 0 &&
        increment.pass < case_.contact.max_augmentations &&
        (norm <= 1e-3 * pass.pass_start_norm || norm <= 0.1 * contact_->augmentation_jump()))
      {
        const double tolerance = 2 * case_.contact.penetration_tolerance;
        if (!contact_->summary().conditions_met(tolerance))
          {
            log_iterate(pcout_, increment.pass, it,
                        "inexact pass: augmented before full convergence");
            return IterateOutcome::augment_early;
          }
      }
    // A pass converges only after a Newton iteration of its own: the first iterate of a pass
    // after an augmentation is the previous pass's displacement, on which the contact
    // conditions just failed. Accepting it unmoved (its residual can be below the tolerance when
    // the multipliers changed little) would augment again on the same displacement until
    // max_augmentations.
    if (!(it > 0 && norm <= std::max(case_.solver.residual_tolerance * increment.reference,
                                     absolute_tolerance_)))
      return std::nullopt;
    if (!pass.frozen)
      return IterateOutcome::converged;
    // Converged with a frozen active set: accept it if it is consistent (no node changes status
    // when the set is free), else iterate on with the free set.
    contact_->evaluate(solution_, increment.depth, ActiveSet::free);
    pass.frozen = false;
    if (contact_->n_status_changes() == 0)
      return IterateOutcome::converged;
    log_iterate(pcout_, increment.pass, it, "frozen active set inconsistent; released");
    pass.previous_norm = std::numeric_limits<double>::infinity();
    return IterateOutcome::next_iterate; // the same iterate again, with the free set
  }

  // The Newton update K du = -R (inexact: nonlinear::linear_tolerance) to the next iterate;
  // under force control the bordered system
  //   K du + R_h dh = -R,   F_u . du + F_h dh = -(F - F*),
  // solved with K a = -R and K b = -R_h as du = a + b dh, dh = -((F - F*) + F_u . a) / (F_h + F_u . b).
  template <int dim>
  IncrementStatus IndentationProblem<dim>::newton_update(NewtonIncrement &increment,
                                                         NewtonPass &pass, const double norm)
  {
    residual_ *= -1.0;
    // Under force control, where the same tolerance serves the bordered solve, no floor.
    const double oversolving_floor =
        increment.force_control
            ? 0.0
            : 1e-2 *
                  pass_end_threshold(case_, absolute_tolerance_, increment.reference,
                                     increment.pass, pass.pass_start_norm) /
                  norm;
    const double tolerance =
        nonlinear::linear_tolerance(norm, increment.reference, oversolving_floor);
    const auto solve = [&](PETScWrappers::MPI::Vector &x, const PETScWrappers::MPI::Vector &b) {
      linalg::LinearSolver::Result linear;
      {
        const output::RunStatistics::Scope timer(statistics_.linear_solve);
        linear = linear_solver_.solve(matrix_, x, b, tolerance);
      }
      statistics_.add_linear_solve(linear.iterations, linear.preconditioner_setups,
                                   linear.setup_seconds);
      return linear;
    };
    const linalg::LinearSolver::Result linear = solve(increment.du, residual_);
    increment.last_linear_iterations = linear.iterations;
    if (!linear.converged)
      {
        pcout_ << "      linear solver: " << linear.reason << " after " << linear.iterations
               << " iterations" << std::endl;
        return IncrementStatus::linear_solver_failure;
      }
    increment.depth_update = 0;
    if (increment.force_control)
      {
        increment.residual_derivative *= -1.0;
        if (!solve(increment.coupled_update, increment.residual_derivative).converged)
          return IncrementStatus::linear_solver_failure;
        const double stiffness = increment.coupling.force_derivative +
                                 increment.force_gradient * increment.coupled_update;
        if (stiffness > 1e-12 * std::max(1.0, std::abs(increment.model_force_target)))
          increment.depth_update =
              -(pass.force_error + increment.force_gradient * increment.du) / stiffness;
        else
          // No contact stiffness (no node touches the indenter): move the indenter onto the
          // nearest node, and a little beyond, to make contact.
          increment.depth_update =
              std::max(contact_->min_gap(), 0.0) + 0.01 * mesh_info_.contact_element_size;
        increment.du.add(increment.depth_update, increment.coupled_update);
      }
    constraints_all_.distribute(increment.du);
    increment.depth_start_of_step = increment.depth;
    increment.depth += increment.depth_update;
    increment.u_start = solution_;
    increment.u_owned = increment.u_start;
    increment.u_owned += increment.du;
    solution_ = increment.u_owned;
    // The predictor's residual belongs to another active set: no line search after it.
    pass.previous_norm = pass.predictor ? std::numeric_limits<double>::infinity() : norm;
    pass.norm_two_back = (pass.alpha == 1 && !pass.one_back_predictor) ? pass.norm_one_back : 0.0;
    pass.norm_one_back = norm;
    pass.one_back_predictor = pass.predictor;
    pass.alpha = 1;
    ++statistics_.newton_iterations;
    return IncrementStatus::converged;
  }

  template <int dim>
  void IndentationProblem<dim>::fill_converged_record(const double depth, StepRecord &record)
  {
    const contact::ContactSummary summary = contact_->summary();
    const double                  factor = symmetry_factor();
    trial_force_scale_ = std::abs(summary.force_z);
    depth_trial_ = depth;
    force_trial_ = summary.force_z * factor;
    record.depth = depth;
    record.force = summary.force_z * factor;
    const contact::ContactPatch patch = contact_patch();
    record.contact_area = patch.area * factor;
    record.contact_radius = patch.max_radius;
    record.n_active_nodes = summary.n_active;
    record.n_stick_nodes = summary.n_stick;
    record.n_slip_nodes = summary.n_slip;
    record.max_pressure = summary.max_pressure;
    record.max_penetration = summary.max_penetration;
    record.bottom_reaction *= factor;
  }
  template class IndentationProblem<2>;
  template class IndentationProblem<3>;
} // namespace indentsim::problems
