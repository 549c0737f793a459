#include "linalg/LinearSolver.h"

#include <deal.II/base/mpi.h>

#include <petscmat.h>

#include <dlfcn.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>

#include <stdexcept>
#include <string>

namespace indentsim::linalg
{
  using namespace dealii;

  namespace
  {
    void check(const PetscErrorCode code, const char *what)
    {
      if (code != 0)
        throw std::runtime_error(std::string("PETSc error ") + std::to_string(code) + " in " +
                                 what);
    }

    // Options of the preconditioner and Krylov solver, under the prefix "indentsim_" so that
    // nothing else in the process sees them; an option the user already set wins.
    void set_default_option(const char *name, const char *value)
    {
      PetscBool set = PETSC_FALSE;
      check(PetscOptionsHasName(nullptr, nullptr, name, &set), "PetscOptionsHasName");
      if (!set)
        check(PetscOptionsSetValue(nullptr, name, value), "PetscOptionsSetValue");
    }
  } // namespace

  void LinearSolver::dump_system(const PETScWrappers::MPI::SparseMatrix &matrix,
                                 const PETScWrappers::MPI::Vector       &rhs)
  {
    // INDENTSIM_DUMP_LINEAR_SYSTEMS=DIR:K writes every K-th system (PETSc binary: matrix,
    // right-hand side, then the six rigid-body modes if the solver is iterative) to
    // DIR/system_<solve>.bin, for bench/bench_linear_solver. Diagnostics only.
    const char *setting = std::getenv("INDENTSIM_DUMP_LINEAR_SYSTEMS");
    ++n_solves_;
    if (setting == nullptr)
      return;
    const std::string text(setting);
    const auto        colon = text.rfind(':');
    const long        every = colon == std::string::npos ? 1 : std::atol(text.c_str() + colon + 1);
    if (every <= 0 || (n_solves_ - 1) % every != 0)
      return;
    const std::string file =
        text.substr(0, colon) + "/system_" + std::to_string(n_solves_ - 1) + ".bin";
    PetscViewer viewer;
    check(PetscViewerBinaryOpen(communicator_, file.c_str(), FILE_MODE_WRITE, &viewer),
          "PetscViewerBinaryOpen");
    check(MatView(static_cast<Mat>(matrix), viewer), "MatView");
    check(VecView(static_cast<const Vec &>(rhs), viewer), "VecView");
    for (const auto &mode : rigid_body_modes_)
      check(VecView(static_cast<const Vec &>(mode), viewer), "VecView");
    check(PetscViewerDestroy(&viewer), "PetscViewerDestroy");
  }

  void LinearSolver::limit_library_threads()
  {
    // Looked up at run time: neither library is a link dependency of ours.
    const auto call = [](const char *environment, const char *function) {
      if (std::getenv(environment) != nullptr)
        return;
      using SetThreads = void (*)(int);
      if (void *symbol = dlsym(RTLD_DEFAULT, function))
        reinterpret_cast<SetThreads>(symbol)(1);
    };
    call("OMP_NUM_THREADS", "omp_set_num_threads");
    call("OPENBLAS_NUM_THREADS", "openblas_set_num_threads");
  }

  double LinearSolver::predicted_direct_seconds(const unsigned int dim, const unsigned long n_dofs)
  {
    const double n = static_cast<double>(n_dofs);
    return dim == 2 ? direct_coefficient_2d * std::pow(n, 1.5) : direct_coefficient_3d * n * n;
  }

  double LinearSolver::predicted_iterative_seconds(const unsigned int  dim,
                                                   const unsigned long n_dofs)
  {
    const double n = static_cast<double>(n_dofs);
    return (dim == 2 ? iterative_coefficient_2d : iterative_coefficient_3d) * n *
           std::pow(n / iterative_reference_dofs, iterative_cost_exponent);
  }

  LinearSolver::Kind LinearSolver::choose_kind(const io::Choice<io::LinearSolverChoice> &setting,
                                               const unsigned int dim, const unsigned long n_dofs)
  {
    if (dim != 2 && dim != 3)
      throw std::invalid_argument("LinearSolver::choose_kind: dimension " + std::to_string(dim) +
                                  " (allowed: 2, 3)");
    if (setting == io::LinearSolverChoice::direct)
      return Kind::direct;
    if (setting == io::LinearSolverChoice::iterative)
      return Kind::iterative;
    if (setting != io::LinearSolverChoice::automatic)
      throw std::invalid_argument("solver.linear_solver: unknown value '" + to_string(setting) +
                                  "' (allowed: auto, direct, iterative)");
    return predicted_iterative_seconds(dim, n_dofs) < predicted_direct_seconds(dim, n_dofs)
               ? Kind::iterative
               : Kind::direct;
  }

  LinearSolver::LinearSolver(const MPI_Comm communicator)
    : communicator_(communicator)
  {
  }

  LinearSolver::~LinearSolver()
  {
    destroy();
  }

  void LinearSolver::destroy()
  {
    if (ksp_ != nullptr)
      KSPDestroy(&ksp_);
    ksp_ = nullptr;
    operator_ = nullptr;
    rebuild_preconditioner_ = true;
  }

  std::string LinearSolver::description() const
  {
    if (kind_ == Kind::direct)
      return "direct (MUMPS LU)";
    return std::string(symmetric_ ? "iterative (CG" : "iterative (GMRES") +
           " + ML smoothed-aggregation AMG with rigid-body modes)";
  }

  namespace
  {
    // The AMG's near-null space at a node at x, component c, mode m: 3D, the three translations
    // and the three rotations omega x X about x, y, z (components (0,-z,y), (z,0,-x), (-y,x,0));
    // 2D axisymmetric (r, z), the translation along z alone.
    template <int dim>
    unsigned int n_near_null_modes()
    {
      return dim == 3 ? 6 : 1;
    }
    template <int dim>
    double near_null_mode(const unsigned int mode, const unsigned int c, const Point<dim> &x)
    {
      if constexpr (dim == 2)
        return c == 1 ? 1.0 : 0.0;
      else
        {
          if (mode < 3)
            return mode == c ? 1.0 : 0.0;
          const double rotations[3][3] = {{0., -x[2], x[1]}, {x[2], 0., -x[0]}, {-x[1], x[0], 0.}};
          return rotations[mode - 3][c];
        }
    }
  } // namespace

  template <int dim>
  void LinearSolver::setup(const DoFHandler<dim> &dof_handler, const Kind kind,
                           const bool symmetric)
  {
    destroy();
    kind_ = kind;
    symmetric_ = symmetric;
    block_size_ = dim;
    rebuild_preconditioner_ = true;
    rigid_body_modes_.clear();
    // MUMPS: METIS's nested-dissection ordering (ICNTL(7) = 5) and no row and column scaling
    // (ICNTL(8) = 0). On the axisymmetric default example the scaling, recomputed with every
    // factorization, is an eighth of the solver's time, and METIS's factors are cheaper than
    // the automatic choice's; together the linear solves take 18 % less time and the forces
    // agree to 1e-10 of the largest (docs/performance.md, "Axisymmetric mode"). The contact
    // penalty's entries are about 30 times the bulk's diagonal, not the orders of magnitude
    // scaling is for; MUMPS's threshold pivoting keeps the LU stable without it.
    set_default_option("-indentsim_mat_mumps_icntl_7", "5");
    set_default_option("-indentsim_mat_mumps_icntl_8", "0");
    if (kind_ == Kind::direct)
      return;

    // The near-null space at the nodes, orthonormalized (any centre of the rotations spans the
    // same space).
    const IndexSet &owned = dof_handler.locally_owned_dofs();
    // The dim unknowns of a node are consecutive and start at a multiple of dim (deal.II
    // numbers a vertex's DoFs together; nothing here renumbers them), so the matrix has
    // dim x dim nodal blocks, which the smoother inverts (point-block Jacobi). Checked, not
    // assumed.
    nodal_blocks_ = owned.n_elements() % dim == 0;
    rigid_body_modes_.resize(n_near_null_modes<dim>());
    for (auto &mode : rigid_body_modes_)
      mode.reinit(owned, communicator_);
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int v : cell->vertex_indices())
          {
            const Point<dim> x = cell->vertex(v);
            for (unsigned int c = 0; c < dim; ++c)
              {
                const types::global_dof_index dof = cell->vertex_dof_index(v, c);
                const types::global_dof_index first = cell->vertex_dof_index(v, 0);
                if (dof != first + c || first % dim != 0)
                  nodal_blocks_ = false;
                if (!owned.is_element(dof))
                  continue;
                for (unsigned int m = 0; m < rigid_body_modes_.size(); ++m)
                  rigid_body_modes_[m](dof) = near_null_mode<dim>(m, c, x);
              }
          }
    nodal_blocks_ = Utilities::MPI::min(nodal_blocks_ ? 1 : 0, communicator_) == 1;
    for (auto &mode : rigid_body_modes_)
      mode.compress(VectorOperation::insert);
    // Modified Gram-Schmidt.
    for (unsigned int i = 0; i < rigid_body_modes_.size(); ++i)
      {
        for (unsigned int j = 0; j < i; ++j)
          rigid_body_modes_[i].add(-(rigid_body_modes_[i] * rigid_body_modes_[j]),
                                   rigid_body_modes_[j]);
        rigid_body_modes_[i] /= rigid_body_modes_[i].l2_norm();
      }

    // ML (Trilinos' smoothed aggregation, through PETSc) with the rigid-body modes: its setup
    // is an order of magnitude cheaper than PETSc's GAMG on our systems (bench_linear_solver,
    // docs/performance.md). GAMG stays available: -indentsim_pc_type gamg.
    set_default_option("-indentsim_pc_ml_nullspace", "user");
    set_default_option("-indentsim_pc_gamg_reuse_interpolation", "true");
    set_default_option("-indentsim_pc_gamg_threshold", "0.01");
    set_default_option("-indentsim_pc_gamg_square_graph", "1");
    set_default_option("-indentsim_mg_levels_ksp_type", "chebyshev");
    // Point-block Jacobi (the nodal blocks inverted) in the Chebyshev smoother: about a
    // third fewer Krylov iterations than point Jacobi on the paper's systems.
    set_default_option("-indentsim_mg_levels_pc_type", "pbjacobi");
    set_default_option("-indentsim_mg_levels_ksp_max_it", "2");
  }

  template void LinearSolver::setup<2>(const DoFHandler<2> &, Kind, bool);
  template void LinearSolver::setup<3>(const DoFHandler<3> &, Kind, bool);

  // The Krylov solvers test convergence on the true residual ||b - A x||, so that the
  // inexact-Newton forcing term means what it says. Left-preconditioned GMRES would test the
  // AMG-preconditioned residual, which a stale reused preconditioner can make small while the
  // true residual is not: the Newton direction then fails to descend. Right preconditioning keeps the same
  // Krylov space and minimizes the true residual.
  void LinearSolver::use_gmres()
  {
    check(KSPSetType(ksp_, KSPGMRES), "KSPSetType");
    check(KSPGMRESSetRestart(ksp_, 200), "KSPGMRESSetRestart");
    check(KSPSetPCSide(ksp_, PC_RIGHT), "KSPSetPCSide");
    check(KSPSetNormType(ksp_, KSP_NORM_UNPRECONDITIONED), "KSPSetNormType");
  }

  void LinearSolver::use_cg()
  {
    check(KSPSetType(ksp_, KSPCG), "KSPSetType");
    check(KSPSetNormType(ksp_, KSP_NORM_UNPRECONDITIONED), "KSPSetNormType");
  }

  LinearSolver::Result LinearSolver::solve(const PETScWrappers::MPI::SparseMatrix &matrix,
                                           PETScWrappers::MPI::Vector             &x,
                                           const PETScWrappers::MPI::Vector       &rhs,
                                           const double relative_tolerance)
  {
    if (rhs.l2_norm() == 0.0)
      {
        // Nothing to solve (e.g. the first iteration of an increment with no load change);
        // some preconditioners fail on a zero right-hand side.
        x = 0;
        return Result{true, 0, "zero right-hand side"};
      }
    dump_system(matrix, rhs);
    const Mat petsc_matrix = static_cast<Mat>(matrix);
    if (ksp_ == nullptr || operator_ != petsc_matrix)
      {
        destroy();
        if (kind_ == Kind::iterative && nodal_blocks_)
          check(MatSetBlockSize(petsc_matrix, static_cast<PetscInt>(block_size_)),
                "MatSetBlockSize");
        check(KSPCreate(communicator_, &ksp_), "KSPCreate");
        check(KSPSetOptionsPrefix(ksp_, "indentsim_"), "KSPSetOptionsPrefix");
        PC pc;
        check(KSPGetPC(ksp_, &pc), "KSPGetPC");
        if (kind_ == Kind::direct)
          {
            check(KSPSetType(ksp_, KSPPREONLY), "KSPSetType");
            check(PCSetType(pc, PCLU), "PCSetType");
            check(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS), "PCFactorSetMatSolverType");
          }
        else
          {
            if (symmetric_)
              use_cg();
            else
              use_gmres();
            check(PCSetType(pc, PCML), "PCSetType");
            std::vector<Vec> modes;
            for (const auto &mode : rigid_body_modes_)
              modes.push_back(static_cast<const Vec &>(mode));
            MatNullSpace near_null_space;
            check(MatNullSpaceCreate(communicator_, PETSC_FALSE, PetscInt(modes.size()),
                                     modes.data(), &near_null_space),
                  "MatNullSpaceCreate");
            check(MatSetNearNullSpace(petsc_matrix, near_null_space), "MatSetNearNullSpace");
            check(MatNullSpaceDestroy(&near_null_space), "MatNullSpaceDestroy");
          }
        check(KSPSetFromOptions(ksp_), "KSPSetFromOptions");
        operator_ = petsc_matrix;
      }
    // The same Mat with new values: the direct solver refactors numerically (the symbolic
    // analysis is kept); the iterative one keeps its preconditioner unless it must be rebuilt
    // (ML rebuilds its hierarchy; GAMG recomputes the coarse operators on the kept interpolation).
    // With 3 x 3 nodal blocks, the Krylov method and the smoothers apply a BAIJ copy of the
    // matrix (BlockMatrixCopy.h: 38 % less time per solve on j2_48); ML builds its hierarchy
    // from the AIJ matrix itself. 2D systems apply the AIJ matrix.
    const Mat applied = (kind_ == Kind::iterative && nodal_blocks_ && block_size_ == 3)
                            ? block_copy_.update(petsc_matrix)
                            : petsc_matrix;
    check(KSPSetOperators(ksp_, applied, petsc_matrix), "KSPSetOperators");
    const bool rebuilt = kind_ == Kind::direct || rebuild_preconditioner_;
    if (kind_ == Kind::iterative)
      {
        check(KSPSetReusePreconditioner(ksp_, rebuilt ? PETSC_FALSE : PETSC_TRUE),
              "KSPSetReusePreconditioner");
        check(KSPSetTolerances(ksp_, relative_tolerance, 0.0, PETSC_DEFAULT, 1000),
              "KSPSetTolerances");
      }
    Result result;
    // The preconditioner (AMG hierarchy or LU factors) is built by KSPSetUp; timed on its own.
    const auto set_up = [&]() {
      const auto start = std::chrono::steady_clock::now();
      check(KSPSetUp(ksp_), "KSPSetUp");
      result.setup_seconds +=
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      ++result.preconditioner_setups;
    };
    if (rebuilt)
      set_up();
    const auto run = [&]() {
      check(KSPSolve(ksp_, static_cast<const Vec &>(rhs), static_cast<const Vec &>(x)), "KSPSolve");
      KSPConvergedReason reason;
      check(KSPGetConvergedReason(ksp_, &reason), "KSPGetConvergedReason");
      return reason;
    };
    KSPConvergedReason reason = run();
    PetscInt           iterations = 0;
    check(KSPGetIterationNumber(ksp_, &iterations), "KSPGetIterationNumber");
    PetscInt total_iterations = iterations;
    if (kind_ == Kind::iterative && symmetric_ &&
        (reason == KSP_DIVERGED_INDEFINITE_PC || reason == KSP_DIVERGED_INDEFINITE_MAT))
      {
        // A symmetric tangent need not be positive definite (geometric stiffness under
        // compression, softening contact curvature), and CG detects it: switch to GMRES for
        // the rest of the run and solve again.
        symmetric_ = false;
        use_gmres();
        reason = run();
        check(KSPGetIterationNumber(ksp_, &iterations), "KSPGetIterationNumber");
        total_iterations += iterations;
      }
    bool fresh_after_failure = false;
    if (kind_ == Kind::iterative && !rebuilt && reason < 0)
      {
        fresh_after_failure = true;
        // The reused preconditioner failed: a fresh one for the same matrix.
        check(KSPSetReusePreconditioner(ksp_, PETSC_FALSE), "KSPSetReusePreconditioner");
        set_up();
        reason = run();
        check(KSPGetIterationNumber(ksp_, &iterations), "KSPGetIterationNumber");
        total_iterations += iterations;
      }
    // Staleness of a reused preconditioner, measured in Krylov iterations per decade of residual
    // reduction (the tolerance varies from solve to solve): the iterations a solve needs beyond
    // the rate of the first solve after the build are the price of not rebuilding. Once they add
    // up to the price of a build, it is rebuilt (the rent-or-buy rule: at most twice the
    // cost of the best choice made in hindsight).
    const double decades = std::max(1.0, -std::log10(relative_tolerance));
    if (kind_ == Kind::iterative && (rebuilt || (reason > 0 && fresh_after_failure)))
      {
        iterations_per_decade_ = static_cast<double>(iterations) / decades;
        stale_iterations_ = 0;
      }
    else if (kind_ == Kind::iterative)
      stale_iterations_ +=
          std::max(0.0, static_cast<double>(iterations) - iterations_per_decade_ * decades);
    rebuild_preconditioner_ = stale_iterations_ >= setup_cost_in_iterations;
    iterations = total_iterations;
    result.converged = reason > 0;
    result.iterations = kind_ == Kind::direct ? 1u : static_cast<unsigned int>(iterations);
    result.reason = KSPConvergedReasons[reason];
    return result;
  }
} // namespace indentsim::linalg
