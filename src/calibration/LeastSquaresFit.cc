// The bounded least-squares fit with Ceres Solver (see LeastSquaresFit.h).
#include "calibration/LeastSquaresFit.h"

#include "calibration/CurveData.h"
#include "case/Schema.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace indentsim::calibration
{
  ResidualModel::ResidualModel(const Calibration &calibration, ForwardRuns &runs)
    : calibration_(calibration)
    , runs_(runs)
  {
    for (const DataSet &d : calibration_.data)
      n_residuals_ += d.x.size();
  }

  std::vector<double>
  ResidualModel::residuals_of(const std::vector<std::vector<double>> &simulated) const
  {
    std::vector<double> r;
    for (std::size_t d = 0; d < calibration_.data.size(); ++d)
      {
        const DataSet &data = calibration_.data[d];
        const double   factor = std::sqrt(data.weight / double(data.x.size()));
        for (std::size_t i = 0; i < data.x.size(); ++i)
          r.push_back(factor * (simulated[d][i] - data.measured[i]) / data.scale_at(i));
      }
    return r;
  }

  std::vector<std::optional<std::vector<double>>>
  ResidualModel::residuals(const std::vector<Point> &points)
  {
    const auto                                      directories = runs_.run(points);
    std::vector<std::optional<std::vector<double>>> result;
    for (const auto &of_point : directories)
      {
        if (!of_point)
          {
            result.emplace_back(std::nullopt);
            continue;
          }
        try
          {
            std::vector<std::vector<double>> simulated;
            for (const DataSet &d : calibration_.data)
              simulated.push_back(
                  simulated_values(d, of_point->at(calibration_.forward_case_of(d))));
            result.emplace_back(residuals_of(simulated));
          }
        catch (const std::exception &error)
          {
            result.emplace_back(std::nullopt); // a curve cut short: a failed point
            last_failure_ = error.what();
          }
      }
    return result;
  }

  std::optional<std::vector<std::vector<double>>> ResidualModel::simulated(const Point &point)
  {
    const auto directories = runs_.run({point});
    if (!directories.front())
      return std::nullopt;
    std::vector<std::vector<double>> values;
    for (const DataSet &d : calibration_.data)
      values.push_back(
          simulated_values(d, directories.front()->at(calibration_.forward_case_of(d))));
    return values;
  }

  std::optional<std::pair<std::vector<double>, std::vector<double>>>
  difference_jacobian(const SampleResiduals &sample, const Point &x,
                      const std::vector<std::vector<Difference>> &candidates)
  {
    const std::size_t p = x.size();
    // Every point sampled so far with its residuals (nullopt: its runs failed).
    std::vector<std::pair<Point, std::optional<std::vector<double>>>> sampled;
    const auto find = [&](const Point &point) {
      return std::find_if(sampled.begin(), sampled.end(),
                          [&](const auto &s) { return s.first == point; });
    };
    const auto at = [&](const std::size_t j, const double value) {
      Point shifted = x;
      shifted[j] = value;
      return shifted;
    };
    std::vector<std::size_t> tried(p, 0); // per column, the candidate it is at
    std::vector<Point>       batch = {x};
    for (std::size_t j = 0; j < p; ++j)
      for (const double value : {candidates[j][0].below, candidates[j][0].above})
        batch.push_back(at(j, value));
    while (true)
      {
        std::vector<Point> unsampled;
        for (const Point &point : batch)
          if (find(point) == sampled.end() &&
              std::find(unsampled.begin(), unsampled.end(), point) == unsampled.end())
            unsampled.push_back(point);
        // A fallback may need no new run: a central difference's one-sided fallback reuses x
        // and the side that finished.
        if (!unsampled.empty())
          {
            const auto r = sample(unsampled);
            for (std::size_t k = 0; k < unsampled.size(); ++k)
              sampled.emplace_back(unsampled[k], r[k]);
          }
        if (!find(x)->second)
          return std::nullopt;
        // A column with a failed point moves on to its next candidate; all of them go out as
        // the next batch.
        batch.clear();
        for (std::size_t j = 0; j < p; ++j)
          {
            const Difference &d = candidates[j][tried[j]];
            if (find(at(j, d.below))->second && find(at(j, d.above))->second)
              continue;
            if (++tried[j] == candidates[j].size())
              return std::nullopt;
            batch.push_back(at(j, candidates[j][tried[j]].below));
            batch.push_back(at(j, candidates[j][tried[j]].above));
          }
        if (batch.empty())
          break;
      }
    const std::vector<double> &r0 = *find(x)->second;
    const std::size_t          m = r0.size();
    std::vector<double>        jacobian(m * p);
    for (std::size_t j = 0; j < p; ++j)
      {
        const Difference          &d = candidates[j][tried[j]];
        const std::vector<double> &below = *find(at(j, d.below))->second;
        const std::vector<double> &above = *find(at(j, d.above))->second;
        for (std::size_t i = 0; i < m; ++i)
          jacobian[i * p + j] = (above[i] - below[i]) / (d.above - d.below);
      }
    return std::make_pair(r0, jacobian);
  }

  namespace
  {
    // What a relative finite-difference step is relative to: |x|, or a thousandth of the
    // parameter's range where x is near zero.
    double difference_scale(const Parameter &parameter, const double x)
    {
      return std::max(std::abs(x), 1e-3 * (parameter.max - parameter.min));
    }

    // The one-sided differences of width h from x, clipped to the bounds, toward the farther
    // bound first, then the other side, then both at h/2: the fallbacks for a failed run.
    std::vector<Difference> one_sided(const Parameter &parameter, const double x, const double h)
    {
      const bool              upward = parameter.max - x >= x - parameter.min;
      std::vector<Difference> list;
      for (const double width : {h, h / 2})
        for (const bool up : {upward, !upward})
          {
            const Difference d = up ? Difference{x, std::min(x + width, parameter.max)}
                                    : Difference{std::max(x - width, parameter.min), x};
            if (d.above > d.below)
              list.push_back(d);
          }
      return list;
    }

    SampleResiduals sampler(ResidualModel &model)
    {
      return [&model](const std::vector<Point> &points) { return model.residuals(points); };
    }
  } // namespace

  std::optional<std::pair<std::vector<double>, std::vector<double>>>
  residuals_and_jacobian(const Calibration &calibration, ResidualModel &model, const Point &x)
  {
    std::vector<std::vector<Difference>> candidates;
    for (std::size_t j = 0; j < x.size(); ++j)
      {
        const Parameter &parameter = calibration.parameters[j];
        const double     h = parameter.step > 0. ? parameter.step
                                                 : calibration.solver.finite_difference_step *
                                                   difference_scale(parameter, x[j]);
        // Forward differences point up unless that leaves the bounds (not toward the farther
        // bound: a narrow step stays near x on either side).
        std::vector<Difference> list;
        if (x[j] + h <= parameter.max)
          list.push_back({x[j], x[j] + h});
        for (const Difference &d : one_sided(parameter, x[j], h))
          if (std::find(list.begin(), list.end(), d) == list.end())
            list.push_back(d);
        candidates.push_back(list);
      }
    return difference_jacobian(sampler(model), x, candidates);
  }

  std::optional<std::pair<std::vector<double>, std::vector<double>>>
  statistics_jacobian(const Calibration &calibration, ResidualModel &model, const Point &x)
  {
    std::vector<std::vector<Difference>> candidates;
    for (std::size_t j = 0; j < x.size(); ++j)
      {
        const Parameter &parameter = calibration.parameters[j];
        const double     h = std::max(parameter.step, calibration.solver.statistics_step *
                                                          difference_scale(parameter, x[j]));
        // Central where both sides lie within the bounds, else one-sided.
        std::vector<Difference> list;
        if (x[j] - h >= parameter.min && x[j] + h <= parameter.max)
          list.push_back({x[j] - h, x[j] + h});
        for (const Difference &d : one_sided(parameter, x[j], h))
          list.push_back(d);
        candidates.push_back(list);
      }
    return difference_jacobian(sampler(model), x, candidates);
  }

  namespace
  {
    using Clock = std::chrono::steady_clock;

    // One residual block of all residuals over one parameter block of all parameters.
    class ForwardModelCost : public ceres::CostFunction
    {
    public:
      ForwardModelCost(const Calibration &calibration, ResidualModel &model)
        : calibration_(calibration)
        , model_(model)
      {
        set_num_residuals(static_cast<int>(model.n_residuals()));
        mutable_parameter_block_sizes()->push_back(static_cast<int>(calibration.parameters.size()));
      }

      // false (a failed run) makes Ceres reject the step and shrink its trust region.
      bool Evaluate(double const *const *parameters, double *residuals,
                    double **jacobians) const override
      {
        const std::size_t   p = calibration_.parameters.size();
        const Point         x(parameters[0], parameters[0] + p);
        std::vector<double> r, jacobian;
        // A trial point outside the bounds (the trust region's step is not projected onto them)
        // is rejected like a failed run, without running.
        for (std::size_t j = 0; j < p; ++j)
          if (x[j] < calibration_.parameters[j].min || x[j] > calibration_.parameters[j].max)
            return false;
        if (jacobians != nullptr && jacobians[0] != nullptr)
          {
            const auto both = residuals_and_jacobian(calibration_, model_, x);
            if (!both)
              return false;
            r = both->first;
            jacobian = both->second;
            std::copy(jacobian.begin(), jacobian.end(), jacobians[0]);
          }
        else
          {
            const auto only = model_.residuals({x});
            if (!only.front())
              return false;
            r = *only.front();
          }
        std::copy(r.begin(), r.end(), residuals);
        return true;
      }

    private:
      const Calibration &calibration_;
      ResidualModel     &model_;
    };

    // A line per iteration, and the history.
    class Progress : public ceres::IterationCallback
    {
    public:
      Progress(const Calibration &calibration, const double *x, ForwardRuns &runs,
               std::ostream &out, std::vector<IterationRecord> &history)
        : calibration_(calibration)
        , x_(x)
        , runs_(runs)
        , out_(out)
        , history_(history)
        , start_(Clock::now())
      {
      }

      ceres::CallbackReturnType operator()(const ceres::IterationSummary &summary) override
      {
        IterationRecord record;
        record.iteration = static_cast<unsigned int>(summary.iteration);
        record.cost = summary.cost;
        record.x.assign(x_, x_ + calibration_.parameters.size());
        record.step_accepted = summary.step_is_successful;
        record.forward_runs = runs_.runs_computed();
        record.wall_time_s = std::chrono::duration<double>(Clock::now() - start_).count();
        history_.push_back(record);
        out_ << "iteration " << std::setw(3) << record.iteration << ": cost " << std::setw(11)
             << std::setprecision(5) << std::scientific << record.cost << std::defaultfloat
             << (record.step_accepted ? "" : " (step rejected)") << " ";
        for (std::size_t j = 0; j < record.x.size(); ++j)
          out_ << " " << calibration_.parameters[j].key << " " << std::setprecision(7)
               << record.x[j];
        out_ << "; " << record.forward_runs << " forward runs, " << std::fixed
             << std::setprecision(1) << record.wall_time_s << " s\n"
             << std::defaultfloat << std::flush;
        return ceres::SOLVER_CONTINUE;
      }

    private:
      const Calibration            &calibration_;
      const double                 *x_;
      ForwardRuns                  &runs_;
      std::ostream                 &out_;
      std::vector<IterationRecord> &history_;
      Clock::time_point             start_;
    };
  } // namespace

  FitResult fit(const Calibration &calibration, ResidualModel &model, ForwardRuns &runs,
                std::ostream &progress)
  {
    const std::size_t p = calibration.parameters.size();
    FitResult         result;
    result.x.resize(p);
    for (std::size_t j = 0; j < p; ++j)
      result.x[j] = calibration.parameters[j].start;
    if (!model.residuals({result.x}).front())
      throw std::runtime_error(
          "the forward runs at the start point failed" +
          (model.last_failure().empty() ? std::string() : " (" + model.last_failure() + ")") +
          "; the console output of each is in its directory under " + calibration.output_directory +
          "/forward/cases/");

    ceres::Problem problem;
    problem.AddResidualBlock(new ForwardModelCost(calibration, model), nullptr, result.x.data());
    for (std::size_t j = 0; j < p; ++j)
      {
        problem.SetParameterLowerBound(result.x.data(), int(j), calibration.parameters[j].min);
        problem.SetParameterUpperBound(result.x.data(), int(j), calibration.parameters[j].max);
      }
    ceres::Solver::Options options;
    options.minimizer_type = ceres::TRUST_REGION;
    options.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
    options.linear_solver_type = ceres::DENSE_QR;
    options.max_num_iterations = int(calibration.solver.max_iterations);
    options.function_tolerance = calibration.solver.function_tolerance;
    options.parameter_tolerance = calibration.solver.parameter_tolerance;
    options.gradient_tolerance = 1e-14;
    // No projected line search on the bounds: each of its trials would need a Jacobian, p + 1
    // forward runs, where a rejected trust-region step costs one.
    options.max_num_line_search_step_size_iterations = 0;
    options.num_threads = 1; // the parallelism is in the forward runs
    options.logging_type = ceres::SILENT;
    options.update_state_every_iteration = true;
    Progress callback(calibration, result.x.data(), runs, progress, result.history);
    options.callbacks.push_back(&callback);
    ceres::Solver::Summary summary;
    ceres::Solve(options, &problem, &summary);

    result.initial_cost = summary.initial_cost;
    result.cost = summary.final_cost;
    result.iterations = static_cast<unsigned int>(summary.iterations.size());
    result.converged = summary.termination_type == ceres::CONVERGENCE;
    result.termination = summary.message;
    const auto both = statistics_jacobian(calibration, model, result.x);
    if (!both)
      throw std::runtime_error("the forward runs for the Jacobian at the optimum failed");
    result.residuals = both->first;
    result.jacobian = both->second;
    for (std::size_t j = 0; j < p; ++j)
      {
        const Parameter &parameter = calibration.parameters[j];
        const double     tolerance = 1e-6 * (parameter.max - parameter.min);
        if (result.x[j] <= parameter.min + tolerance)
          result.at_bound.push_back(parameter.key + " at its min " +
                                    io::format_number(parameter.min));
        else if (result.x[j] >= parameter.max - tolerance)
          result.at_bound.push_back(parameter.key + " at its max " +
                                    io::format_number(parameter.max));
      }
    return result;
  }
} // namespace indentsim::calibration
