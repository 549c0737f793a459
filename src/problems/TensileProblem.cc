#include "problems/TensileProblem.h"

#include "case/CaseFile.h"
#include "io/Version.h"
#include "materials/MaterialFactory.h"
#include "materials/crystal/Orientation.h"
#include "output/ParaViewFiles.h"
#include "output/RunRecorder.h"

#include <deal.II/base/function.h>
#include <deal.II/base/multithread_info.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/utilities.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/mapping_q_eulerian.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/petsc_solver.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/vector_tools.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace indentsim::problems
{
  using namespace dealii;
  using fem::CellContribution;
  using fem::CellWorkspace;
  using fem::element_residual_and_tangent;
  using fem::GhostedVector;
  using fem::run_on_owned_cells;
  using fem::to_thread_readable;
  using linalg::LinearSolver;
  using nonlinear::IncrementStatus;
  using output::RunDescription;
  using output::RunStatistics;
  using output::write_run_summary;

  namespace
  {
    // Boundary ids of GridGenerator::subdivided_hyper_cube with colorize = true.
    namespace face
    {
      constexpr types::boundary_id x_min = 0, y_min = 2, z_min = 4, z_max = 5;
    }

    void write_csv_header(std::ostream &out)
    {
      out << "step,log_strain,true_stress_GPa,engineering_strain,force_mN,newton_iterations,"
             "cutbacks,wall_time_s\n";
    }

    void write_csv_row(std::ostream &out, const TensileRecord &r)
    {
      out << r.step << ',' << std::setprecision(12) << r.log_strain << ',' << r.true_stress << ','
          << r.engineering_strain << ',' << r.force << ',' << r.newton_iterations << ','
          << r.cutbacks << ',' << std::setprecision(4) << r.wall_time << '\n'
          << std::flush;
    }
  } // namespace

  TensileProblem::TensileProblem(const io::Case &the_case, const MPI_Comm communicator,
                                 const bool verbose)
    : case_(the_case)
    , communicator_(communicator)
    , pcout_(std::cout, verbose && Utilities::MPI::this_mpi_process(communicator) == 0)
    , solid_(communicator)
    , material_(materials::create_material(the_case.material))
    , use_f_bar_(the_case.specimen.f_bar)
    , n_per_side_(the_case.specimen.elements_per_side)
    , edge_length_(the_case.specimen.elements_per_side) // elements of 1 um
    , linear_solver_(communicator)
  {
  }

  TensileProblem::~TensileProblem() = default;

  unsigned int TensileProblem::n_cells() const
  {
    return solid_.n_cells();
  }

  unsigned int TensileProblem::n_dofs() const
  {
    return solid_.n_dofs();
  }

  unsigned int TensileProblem::lexicographic_index(const Point<3> &cell_centre) const
  {
    const double element_size = edge_length_ / n_per_side_;
    unsigned int index[3];
    for (unsigned int d = 0; d < 3; ++d)
      index[d] = std::min(n_per_side_ - 1,
                          static_cast<unsigned int>(std::floor(cell_centre[d] / element_size)));
    return index[0] + n_per_side_ * (index[1] + n_per_side_ * index[2]);
  }

  void TensileProblem::setup()
  {
    const RunStatistics::Scope timer(statistics_.setup);
    GridGenerator::subdivided_hyper_cube(solid_.triangulation, n_per_side_, 0., edge_length_, true);
    solid_.distribute_dofs();

    make_dirichlet_constraints(0., constraints_homogeneous_);
    solid_.reinit_matrix(constraints_homogeneous_, matrix_);
    linear_solver_.setup(
        solid_.dof_handler,
        LinearSolver::choose_kind(case_.solver.linear_solver, 3, solid_.dof_handler.n_dofs()),
        material_->symmetric_tangent());
    solid_.reinit_ghosted(solution_);
    solid_.reinit_ghosted(solution_converged_);
    solid_.reinit_owned(rhs_);
    u_top_converged_ = 0;

    // Orientations: one for the whole cube, or one random orientation per element numbered by
    // the element's position, so that every MPI partition sees the same polycrystal.
    const auto                     &specimen = case_.specimen;
    const bool                      per_element = (specimen.grains == io::Grains::per_element);
    const unsigned int              n_cells_total = n_per_side_ * n_per_side_ * n_per_side_;
    const std::vector<Tensor<2, 3>> orientations =
        per_element ? materials::random_orientations(n_cells_total, specimen.seed)
                    : std::vector<Tensor<2, 3>>{materials::create_orientation(case_.material)};

    history_.reinit(solid_.triangulation.n_active_cells(), 8, material_->n_state_variables());
    const unsigned int n_q_points = history_.n_q_points(), n_state = history_.n_state();
    grain_of_cell_.assign(solid_.triangulation.n_active_cells(), 0);
    for (const auto &cell : solid_.dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          const unsigned int grain = lexicographic_index(cell->center());
          grain_of_cell_[cell->active_cell_index()] = grain;
          const Tensor<2, 3> &g = orientations[per_element ? grain : 0];
          const auto          states = history_.converged(cell);
          for (unsigned int q = 0; q < n_q_points; ++q)
            material_->oriented_initial_state(states.subspan(q * n_state, n_state), g);
        }
    history_.converged_changed();

    pcout_ << "Tensile cube (" << case_.material.model << "): " << n_per_side_
           << "^3 = " << n_cells() << " elements of 1 um, edge " << edge_length_ << " um, "
           << n_dofs() << " DOFs, grains " << specimen.grains
           << (per_element ? " (seed " + std::to_string(specimen.seed) + ")" : std::string())
           << ", F-bar " << (use_f_bar_ ? "on" : "off") << ", "
           << Utilities::MPI::n_mpi_processes(communicator_) << " MPI rank(s)" << std::endl;
  }

  void TensileProblem::make_dirichlet_constraints(const double               top_increment,
                                                  AffineConstraints<double> &constraints) const
  {
    constraints.clear();
    constraints.reinit(solid_.locally_relevant);
    const Functions::ZeroFunction<3>     zero(3);
    const Functions::ConstantFunction<3> top(std::vector<double>{0., 0., top_increment});
    const auto component = [this](const unsigned int c) { return solid_.component_mask(c); };
    VectorTools::interpolate_boundary_values(solid_.dof_handler, face::x_min, zero, constraints,
                                             component(0));
    VectorTools::interpolate_boundary_values(solid_.dof_handler, face::y_min, zero, constraints,
                                             component(1));
    VectorTools::interpolate_boundary_values(solid_.dof_handler, face::z_min, zero, constraints,
                                             component(2));
    VectorTools::interpolate_boundary_values(solid_.dof_handler, face::z_max, top, constraints,
                                             component(2));
    constraints.close();
  }

  TensileProblem::AssemblyResult
  TensileProblem::assemble(const AffineConstraints<double> &constraints)
  {
    AssemblyResult result;
    double         local_force = 0, local_volume = 0;
    ++statistics_.assemblies;
    const RunStatistics::Scope timer(statistics_.assembly);

    matrix_ = 0;
    rhs_ = 0;
    const GhostedVector u =
        to_thread_readable(solution_, solid_.locally_owned, solid_.locally_relevant, communicator_);
    const auto worker = [&](const DoFHandler<3>::active_cell_iterator &cell,
                            CellWorkspace &workspace, CellContribution &contribution) {
      workspace.reinit(cell, u);
      Vector<double> &r_local = contribution.vector;
      contribution.status = element_residual_and_tangent(
          *material_, use_f_bar_, workspace.u_local, history_.converged(cell),
          history_.current(cell), workspace.scratch, r_local, &contribution.matrix);
      if (contribution.status != materials::UpdateStatus::success)
        return;
      // The top face is held in z, so the internal force at its z dofs is the reaction.
      contribution.sums = {{0., 0.}};
      for (const unsigned int f : cell->face_indices())
        if (cell->face(f)->at_boundary() && cell->face(f)->boundary_id() == face::z_max)
          for (unsigned int a = 0; a < solid_.fe.n_dofs_per_cell(); ++a)
            if (solid_.fe.system_to_component_index(a).first == 2 &&
                solid_.fe.has_support_on_face(a, f))
              contribution.sums[0] += r_local[a];
      // Current volume: integral of det F over the reference cell (exact for Q1 with 2x2x2
      // Gauss points, det F being of degree 2 in each coordinate).
      for (unsigned int q = 0; q < history_.n_q_points(); ++q)
        {
          const Tensor<2, 3> F = deformation_gradient(workspace.scratch, q, workspace.u_local);
          contribution.sums[1] += determinant(F) * workspace.scratch.JxW[q];
        }
      r_local *= -1.0; // Newton: K du = -R
      cell->get_dof_indices(contribution.dof_indices);
    };
    const auto copier = [&](const CellContribution &contribution) {
      if (contribution.status != materials::UpdateStatus::success)
        {
          result.status = contribution.status;
          return; // every rank must still reach the collective calls below
        }
      constraints.distribute_local_to_global(contribution.matrix, contribution.vector,
                                             contribution.dof_indices, matrix_, rhs_);
      local_force += contribution.sums[0];
      local_volume += contribution.sums[1];
    };
    {
      const RunStatistics::Scope cell_loop_timer(statistics_.cell_loop);
      run_on_owned_cells(solid_.dof_handler, history_.n_q_points(), worker, copier);
    }
    matrix_.compress(VectorOperation::add);
    rhs_.compress(VectorOperation::add);

    result.top_force = Utilities::MPI::sum(local_force, communicator_);
    result.volume = Utilities::MPI::sum(local_volume, communicator_);
    const unsigned int failed = Utilities::MPI::max(
        static_cast<unsigned int>(result.status != materials::UpdateStatus::success),
        communicator_);
    if (failed && result.status == materials::UpdateStatus::success)
      result.status = materials::UpdateStatus::local_newton_failed; // failed on another rank
    return result;
  }

  double TensileProblem::free_residual_norm(const AffineConstraints<double> &constraints) const
  {
    double local = 0;
    for (const auto dof : solid_.locally_owned)
      if (!constraints.is_constrained(dof))
        local += rhs_(dof) * rhs_(dof);
    return std::sqrt(Utilities::MPI::sum(local, communicator_));
  }

  IncrementStatus TensileProblem::solve_increment(const double u_top, unsigned int &iterations,
                                                  AssemblyResult &result)
  {
    make_dirichlet_constraints(u_top - u_top_converged_, constraints_increment_);

    const auto                &tolerances = case_.solver;
    double                     reference = tolerances.absolute_tolerance;
    PETScWrappers::MPI::Vector du(solid_.locally_owned, communicator_);
    PETScWrappers::MPI::Vector u_owned(solid_.locally_owned, communicator_);
    iterations = 0;
    for (unsigned int it = 0; it <= tolerances.max_newton_iterations; ++it)
      {
        // Iteration 0 applies the increment (inhomogeneous), the others correct (homogeneous).
        const AffineConstraints<double> &constraints =
            it == 0 ? constraints_increment_ : constraints_homogeneous_;
        const AssemblyResult assembly = assemble(constraints);
        if (assembly.status != materials::UpdateStatus::success)
          {
            pcout_ << "      material point: " << materials::to_string(assembly.status)
                   << std::endl;
            return IncrementStatus::material_failure;
          }
        const double norm = free_residual_norm(constraints);
        pcout_ << "      it " << std::setw(2) << it << "  |R| = " << std::scientific
               << std::setprecision(3) << norm << " mN" << std::defaultfloat << std::endl;
        // The scale of the relative test: the out-of-balance force that the prescribed
        // increment creates at the free dofs in the first iteration.
        if (it == 0)
          reference = std::max(reference, norm);
        if (!std::isfinite(norm) || !std::isfinite(assembly.top_force) || norm > 1e10 * reference)
          return IncrementStatus::newton_diverged;
        if (it > 0 && norm <= std::max(tolerances.residual_tolerance * reference,
                                       tolerances.absolute_tolerance))
          {
            result = assembly;
            return IncrementStatus::converged;
          }
        if (it == tolerances.max_newton_iterations)
          break;

        LinearSolver::Result linear;
        {
          const RunStatistics::Scope timer(statistics_.linear_solve);
          linear = linear_solver_.solve(matrix_, du, rhs_,
                                        std::clamp(0.1 * norm / reference, 1e-10, 1e-4));
        }
        statistics_.add_linear_solve(linear.iterations, linear.preconditioner_setups,
                                     linear.setup_seconds);
        ++statistics_.newton_iterations;
        if (!linear.converged)
          {
            pcout_ << "      linear solver: " << linear.reason << std::endl;
            return IncrementStatus::linear_solver_failure;
          }
        constraints.distribute(du);
        u_owned = solution_;
        u_owned += du;
        solution_ = u_owned;
        ++iterations;
      }
    return IncrementStatus::too_many_iterations;
  }

  void TensileProblem::accept_increment()
  {
    history_.accept();
    solution_converged_ = solution_;
  }

  void TensileProblem::reject_increment()
  {
    history_.reject();
    solution_ = solution_converged_;
  }

  // Solves step `step` from the converged log strain `strain` to `target` in sub-increments,
  // halved on failure and kept halved for the rest of the step so that the record is always at
  // the nominal strain. Counts Newton iterations and cut-backs into `record`; returns the
  // assembly of the converged state.
  TensileProblem::AssemblyResult TensileProblem::solve_step(const unsigned int step,
                                                            const double target, double &strain,
                                                            TensileRecord      &record,
                                                            output::AppendFile &log)
  {
    const auto       &loading = case_.loading;
    const std::string model = io::to_string(case_.material.model);
    // Sub-increments of the step; halved on failure, and kept halved for the rest of the
    // step so that the record is always at the nominal strain.
    double         increment = target - strain;
    unsigned int   halvings = 0;
    AssemblyResult converged;
    while (strain < target)
      {
        const double next =
            (strain + increment >= target * (1 - 1e-14)) ? target : strain + increment;
        unsigned int          iterations = 0;
        const IncrementStatus status =
            solve_increment(edge_length_ * std::expm1(next), iterations, converged);
        record.newton_iterations += iterations;
        if (status == IncrementStatus::converged)
          {
            accept_increment();
            u_top_converged_ = edge_length_ * std::expm1(next);
            strain = next;
            continue;
          }
        reject_increment();
        ++record.cutbacks;
        ++statistics_.cutbacks;
        ++halvings;
        pcout_ << "    [" << model << "] step " << step << " to log strain " << next << ": "
               << to_string(status) << "; cutting the increment back to " << increment / 2
               << std::endl;
        if (log.is_open())
          log.stream() << "# step " << step << ": " << to_string(status)
                       << ", increment of log strain cut back to " << increment / 2 << '\n';
        if (halvings > loading.max_cutbacks)
          throw std::runtime_error("tensile increment to log strain " + std::to_string(next) +
                                   " failed after " + std::to_string(loading.max_cutbacks) +
                                   " cut-backs (" + to_string(status) + ")");
        increment /= 2;
      }
    return converged;
  }

  void TensileProblem::run(const std::string &output_directory, const std::string &csv_file_name,
                           const bool write_paraview_file)
  {
    const bool        root = Utilities::MPI::this_mpi_process(communicator_) == 0;
    const auto       &loading = case_.loading;
    const std::string model = io::to_string(case_.material.model);
    // The CSV (created whole with its header and the initial state, then appended to) and
    // run.log (appended to: the J2 comparison run continues it) on rank 0, flushed after every
    // step; a failed write stops every rank (output::write_collectively).
    output::AppendFile csv, log;
    const auto         flush = [&]() {
      output::write_collectively(communicator_, [&]() {
        csv.flush();
        log.flush();
      });
    };
    records_.assign(1, TensileRecord{});
    output::write_collectively(communicator_, [&]() {
      if (!root || output_directory.empty())
        return;
      const std::string csv_path = output_directory + "/" + csv_file_name;
      output::write_file(csv_path, [&](std::ostream &out) {
        write_csv_header(out);
        write_csv_row(out, records_.front());
      });
      csv.open(csv_path);
      log.open(output_directory + "/" + io::output_files::log);
      log.stream() << "# indentsim " << indentsim::version() << " tensile run log, model " << model
                   << ". Units: um, mN, GPa, s.\n"
                   << "# cube " << n_per_side_ << "^3 elements, edge " << edge_length_
                   << " um, DOFs " << n_dofs() << ", MPI ranks "
                   << Utilities::MPI::n_mpi_processes(communicator_) << ", results in "
                   << csv_file_name << '\n'
                   << "# step log_strain true_stress_GPa force_mN newton_iterations cutbacks "
                      "wall_time_s\n";
      log.flush();
    });
    wall_timer_.restart();

    double       strain = 0; // converged logarithmic strain
    unsigned int total_newton = 0;
    for (unsigned int step = 1; step <= loading.steps; ++step)
      {
        const double  target = loading.max_strain * step / loading.steps;
        TensileRecord record;
        record.step = step;
        const AssemblyResult converged = solve_step(step, target, strain, record, log);

        // With traction-free lateral faces and frictionless rollers, div sigma = 0 gives the
        // volume average  <sigma_zz> = (1/v) integral_boundary t_z z da = F_z H / v: only the
        // top face (z = H everywhere, u_z uniform) carries t_z at z != 0. For a homogeneous
        // deformation this is the Cauchy stress sigma_zz itself.
        const double u_top = u_top_converged_;
        const double height = edge_length_ + u_top;
        record.engineering_strain = u_top / edge_length_;
        record.log_strain = std::log1p(record.engineering_strain);
        record.force = converged.top_force;
        record.true_stress = converged.top_force * height / converged.volume;
        record.wall_time = wall_timer_.wall_time();
        total_newton += record.newton_iterations;
        records_.push_back(record);
        statistics_.steps = step;

        const double eta = record.wall_time / step * (loading.steps - step);
        pcout_ << "[" << model << "] step " << std::setw(3) << step << "/" << loading.steps
               << "  log strain " << std::setprecision(6) << record.log_strain << "  true stress "
               << record.true_stress << " GPa  force " << record.force << " mN  Newton "
               << record.newton_iterations << "  cut " << record.cutbacks << "  wall "
               << output::format_duration(record.wall_time) << "  ETA ~"
               << output::format_duration(eta) << std::endl;
        if (csv.is_open())
          write_csv_row(csv.stream(), record);
        if (log.is_open())
          log.stream() << step << ' ' << std::setprecision(10) << record.log_strain << ' '
                       << record.true_stress << ' ' << record.force << ' '
                       << record.newton_iterations << ' ' << record.cutbacks << ' '
                       << std::setprecision(4) << record.wall_time << '\n';
        flush();
      }
    pcout_ << "[" << model << "] finished: " << loading.steps << " steps, " << total_newton
           << " Newton iterations, wall time " << output::format_duration(wall_timer_.wall_time())
           << std::endl;
    if (log.is_open())
      log.stream() << "# finished: " << loading.steps << " steps, " << total_newton
                   << " Newton iterations, " << wall_timer_.wall_time() << " s\n";
    flush();
    if (write_paraview_file && !output_directory.empty())
      {
        const RunStatistics::Scope timer(statistics_.output);
        write_paraview(output_directory, loading.steps);
      }
    statistics_.total = statistics_.setup + wall_timer_.wall_time();
    if (!output_directory.empty() && csv_file_name == io::output_files::stress_strain_csv)
      {
        RunDescription description;
        description.test = "tensile";
        description.material_model = model;
        description.linear_solver = linear_solver_.description();
        description.cells = n_cells();
        description.dofs = n_dofs();
        description.mpi_ranks = Utilities::MPI::n_mpi_processes(communicator_);
        description.threads = MultithreadInfo::n_threads();
        description.final_value = records_.back().true_stress;
        description.final_value_name = "final_true_stress_GPa";
        write_run_summary(output_directory + "/" + io::output_files::run_summary, description,
                          statistics_, communicator_);
      }
  }

  void TensileProblem::write_paraview(const std::string &output_directory, const unsigned int index)
  {
    const unsigned int n_cells_local = solid_.triangulation.n_active_cells();
    Vector<float> sigma_zz(n_cells_local), von_mises(n_cells_local), plastic_strain(n_cells_local),
        grain(n_cells_local), rank(n_cells_local);
    const unsigned int        n_q_points = history_.n_q_points(), n_state = history_.n_state();
    CellWorkspace             workspace(solid_.fe, n_q_points);
    std::vector<Tensor<2, 3>> cauchy(n_q_points);
    std::vector<double>       state(history_.cell_length());
    const GhostedVector       u =
        to_thread_readable(solution_, solid_.locally_owned, solid_.locally_relevant, communicator_);
    for (const auto &cell : solid_.dof_handler.active_cell_iterators())
      {
        if (!cell->is_locally_owned())
          continue;
        // The converged state evaluated at the converged displacement: no further flow.
        workspace.reinit(cell, u);
        element_residual_and_tangent(*material_, use_f_bar_, workspace.u_local,
                                     history_.converged(cell), state, workspace.scratch,
                                     workspace.r_local, nullptr, &cauchy);
        const unsigned int index_of_cell = cell->active_cell_index();
        for (unsigned int q = 0; q < n_q_points; ++q)
          {
            const Tensor<2, 3> s = cauchy[q] - trace(cauchy[q]) / 3. * unit_symmetric_tensor<3>();
            sigma_zz[index_of_cell] += cauchy[q][2][2] / n_q_points;
            von_mises[index_of_cell] += std::sqrt(1.5 * scalar_product(s, s)) / n_q_points;
            plastic_strain[index_of_cell] +=
                material_->equivalent_plastic_strain(
                    std::span<const double>(state).subspan(q * n_state, n_state)) /
                n_q_points;
          }
        grain[index_of_cell] = grain_of_cell_[index_of_cell];
        rank[index_of_cell] = solid_.triangulation.locally_owned_subdomain();
      }

    DataOut<3> data_out;
    data_out.attach_dof_handler(solid_.dof_handler);
    const std::vector<DataComponentInterpretation::DataComponentInterpretation> vector_field(
        3, DataComponentInterpretation::component_is_part_of_vector);
    data_out.add_data_vector(u, std::vector<std::string>(3, "displacement_um"),
                             DataOut<3>::type_dof_data, vector_field);
    data_out.add_data_vector(sigma_zz, "cauchy_zz_GPa");
    data_out.add_data_vector(von_mises, "von_mises_GPa");
    data_out.add_data_vector(plastic_strain, "equivalent_plastic_strain");
    data_out.add_data_vector(grain, "grain");
    data_out.add_data_vector(rank, "mpi_rank");
    // DataOut works on threads: it reads the thread-readable copy, not the PETSc vector.
    const MappingQEulerian<3, GhostedVector> deformed(1, solid_.dof_handler, u);
    data_out.build_patches(deformed, 1);
    output::write_vtu_with_pvtu_record(
        data_out, output_directory, io::output_files::paraview_basename, index, 4, communicator_);
  }
} // namespace indentsim::problems
