// The weighted least-squares fit of a calibration: residuals from the forward runs, and the
// bounded minimisation of their sum of squares by Ceres Solver (Levenberg-Marquardt with the
// bounds as box constraints), the Jacobian by forward differences whose p + 1 runs go out as one
// batch (side by side with --jobs); a run that fails at a perturbed point is replaced by one on
// the other side or at half the step.
//
// The difference step of a parameter is its own `step` if given, else
// solver.finite_difference_step * max(|x|, 1e-3 (max - min)); it points inward at an upper bound.
//
// Residuals (docs/calibration.md): for data set d with weight w_d, n_d comparison points,
// measured values y_i and the scale s_d = max |y_i|,
//   r_i = sqrt(w_d / n_d) (y_sim(x_i) - y_i) / s_d,
// so that each data set adds w_d times its mean square relative misfit, whatever its number of
// points and its unit; indentation features take each feature's mean measured |value| for s_d.
// Units: those of the parameters.
#pragma once

#include "calibration/CalibrationFile.h"
#include "calibration/ForwardRuns.h"

#include <functional>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace indentsim::calibration
{
  // The residual vector of a parameter point, through the forward runs.
  class ResidualModel
  {
  public:
    ResidualModel(const Calibration &calibration, ForwardRuns &runs);

    std::size_t n_residuals() const { return n_residuals_; }

    // Per point the residuals, or nullopt if its runs failed or fell short of the data.
    std::vector<std::optional<std::vector<double>>> residuals(const std::vector<Point> &points);

    // Per data set the simulated values at its comparison points; nullopt if the runs failed.
    std::optional<std::vector<std::vector<double>>> simulated(const Point &point);

    // Residuals of simulated values (per data set) as defined above.
    std::vector<double> residuals_of(const std::vector<std::vector<double>> &simulated) const;

    // Why the last point whose runs finished gave no residuals (a curve cut short, a feature
    // that could not be computed); empty if none failed so.
    const std::string &last_failure() const { return last_failure_; }

  private:
    const Calibration &calibration_;
    ForwardRuns       &runs_;
    std::size_t        n_residuals_ = 0;
    std::string        last_failure_;
  };

  struct IterationRecord
  {
    unsigned int iteration = 0;
    double       cost = 0.; // half the sum of squared residuals (Ceres' cost)
    Point        x;
    bool         step_accepted = true;
    unsigned int forward_runs = 0; // computed so far (cached ones not counted)
    double       wall_time_s = 0.;
  };

  struct FitResult
  {
    Point                        x;
    std::vector<double>          residuals;
    std::vector<double>          jacobian; // row-major, residuals x parameters, at x
    double                       initial_cost = 0., cost = 0.;
    unsigned int                 iterations = 0;
    bool                         converged = false;
    std::string                  termination; // Ceres' message
    std::vector<IterationRecord> history;
    std::vector<std::string>     at_bound; // "material.yield_stress at its min 0.05"
  };

  // Minimises from the parameters' starts. `progress` gets a line per iteration (cost,
  // parameters, forward runs, wall time). Throws std::runtime_error if the runs at the start
  // fail (nothing to minimise).
  FitResult fit(const Calibration &calibration, ResidualModel &model, ForwardRuns &runs,
                std::ostream &progress);

  // Per point its residuals, or nullopt where its runs failed (ResidualModel::residuals, or a
  // stand-in in the tests).
  using SampleResiduals =
      std::function<std::vector<std::optional<std::vector<double>>>(const std::vector<Point> &)>;

  // One column's difference: (r(x with x_j = above) - r(x with x_j = below)) / (above - below).
  struct Difference
  {
    double below = 0., above = 0.;
    bool   operator==(const Difference &) const = default;
  };

  // The residuals at x and the Jacobian of differences (row-major), column j from the first of
  // candidates[j] whose two points' runs finished. The first candidates of all columns go out as
  // one batch with x; the columns with a failed run then try their next candidates, again as one
  // batch, so that a forward run failing at one perturbed point costs a retry, not the fit.
  // nullopt if the run at x fails or a column runs out of candidates.
  std::optional<std::pair<std::vector<double>, std::vector<double>>>
  difference_jacobian(const SampleResiduals &sample, const Point &x,
                      const std::vector<std::vector<Difference>> &candidates);

  // The Jacobian behind the statistics at the optimum: central differences with the step
  // h = solver.statistics_step * max(|x|, 1e-3 (max - min)), or the parameter's own `step` if
  // that is larger; one-sided from x where a side leaves the bounds (toward the farther bound,
  // clipped to it). A step this wide sees through the small jumps of a forward model (contact
  // nodes) that decorrelate the columns of a narrow difference and would hide parameters the
  // data cannot separate. Where a run fails: one-sided from x, the other side, then h/2.
  std::optional<std::pair<std::vector<double>, std::vector<double>>>
  statistics_jacobian(const Calibration &calibration, ResidualModel &model, const Point &x);

  // Forward-difference Jacobian at `x` with the residuals there, from one batch of p + 1 points;
  // a step points down where up would leave the bounds. Where a run fails: the other side, then
  // half the step.
  std::optional<std::pair<std::vector<double>, std::vector<double>>>
  residuals_and_jacobian(const Calibration &calibration, ResidualModel &model, const Point &x);
} // namespace indentsim::calibration
