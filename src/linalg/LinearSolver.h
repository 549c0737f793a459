// The linear solver of the Newton iterations, K du = -R, for the indentation and tensile
// problems. Units follow the system: K in mN/um, R in mN, du in um.
//
// Two kinds, chosen by solver.linear_solver (auto picks by size, see choose_kind):
//  - direct: LU factorization by MUMPS through PETSc. The symbolic analysis is done once per
//    sparsity pattern and reused by every later factorization (the pattern never changes).
//  - iterative: CG (symmetric tangents) or GMRES preconditioned by Trilinos ML's smoothed-
//    aggregation algebraic multigrid (through PETSc's PCML) with the six rigid-body modes of
//    the nodes as near-null space (the modes an aggregation-AMG needs for elasticity;
//    translations alone converge slowly). PETSc's GAMG remains selectable with
//    PETSC_OPTIONS="-indentsim_pc_type gamg"; ML sets up and solves faster on the paper's
//    systems (bench/bench_linear_solver). The levels are smoothed by two
//    Chebyshev steps on point-block Jacobi: the matrix is told its 3 x 3 nodal blocks
//    (MatSetBlockSize), whose inverses the smoother applies (fewer Krylov iterations than
//    point Jacobi). The Krylov method and the smoothers
//    apply a copy of the matrix in PETSc's block format (BlockMatrixCopy.h), which multiplies
//    faster; ML builds its hierarchy from the assembled AIJ matrix.
//    The preconditioner is built for one Newton matrix and reused for the following ones as
//    long as that pays: the iterations the reused one costs beyond the rate (iterations per
//    decade of residual reduction) of the first solve after its build are added up, and it is
//    rebuilt once they reach the price of a build (setup_cost_in_iterations); a solve that
//    fails with a reused one is repeated with a fresh one. The Newton matrices of a load step
//    differ little. The relative tolerance is passed per solve (inexact Newton,
//    see IndentationProblem).
// The preconditioner reads PETSc options with the prefix "indentsim_" (e.g. environment
// PETSC_OPTIONS="-indentsim_ksp_monitor"), for diagnostics only. The environment variable
// INDENTSIM_DUMP_LINEAR_SYSTEMS=DIR:K writes every K-th system to DIR for
// bench/bench_linear_solver.
#pragma once

#include "case/Case.h"
#include "linalg/BlockMatrixCopy.h"

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/lac/petsc_sparse_matrix.h>
#include <deal.II/lac/petsc_vector.h>

#include <petscksp.h>

#include <string>
#include <vector>

namespace indentsim::linalg
{
  class LinearSolver
  {
  public:
    enum class Kind
    {
      direct,
      iterative
    };
    // Systems with at least this many unknowns are solved iteratively under
    // solver.linear_solver: auto. AMG-GMRES is faster per solve from about 20k DOFs on the 2-core
    // machine (the paper's J2 case at 24 x 24, 23k DOFs: 0.21 s against 0.32 s with MUMPS;
    // crystal (011) at 48 x 48 quarter, 36k DOFs, two ranks: 1.25 s per MUMPS solve), but it is
    // less robust: the J2 Berkovich case at 24 x 24 (full model, 23k DOFs) stalled at 3.47 um
    // with AMG-GMRES (no descent from the Newton direction, down to increments of 2e-4 um) and
    // passed with MUMPS. Until that is understood the direct solver stays the default below
    // 60k DOFs; `solver.linear_solver: iterative` selects AMG.
    static constexpr unsigned long iterative_threshold_dofs = 60000;
    // The kind `setting` (solver.linear_solver: auto | direct | iterative) selects for a system of n_dofs unknowns.
    // Axisymmetric (dim = 2) systems go to the direct solver: 2D fill grows only as n log n.
    static Kind choose_kind(const io::Choice<io::LinearSolverChoice> &setting, unsigned long n_dofs,
                            unsigned int dim = 3);

    // Sets the OpenMP threads of MUMPS and the threads of OpenBLAS to one, unless the user set
    // OMP_NUM_THREADS or OPENBLAS_NUM_THREADS. Our threads are TBB's (assembly) and MPI ranks;
    // idle OpenMP workers spin and steal CPU time from the assembly. Call once at start.
    static void limit_library_threads();

    LinearSolver(MPI_Comm communicator);
    ~LinearSolver();
    LinearSolver(const LinearSolver &) = delete;
    LinearSolver &operator=(const LinearSolver &) = delete;

    // Prepares for systems on `dof_handler` (vector-valued Q1, three components): the kind and,
    // for the iterative kind, the rigid-body modes. `symmetric`: the tangent is symmetric (CG
    // instead of GMRES).
    // dim = 2: the axisymmetric (r, z) model, whose only rigid mode is the z translation (u_r
    // strains the hoop), without nodal blocks.
    template <int dim>
    void setup(const dealii::DoFHandler<dim> &dof_handler, Kind kind, bool symmetric);

    struct Result
    {
      bool         converged = false;
      unsigned int iterations = 0;            // Krylov iterations (1 for direct)
      std::string  reason;                    // PETSc's converged/diverged reason
      unsigned int preconditioner_setups = 0; // AMG builds or LU factorizations in this solve
      double       setup_seconds = 0;         // their wall time [s] (part of the solve's)
    };
    // Solves matrix x = rhs (x is overwritten) to relative residual `relative_tolerance`
    // (iterative) or exactly (direct). A solve that does not converge (zero pivot, iteration
    // limit) is reported in the result; the caller cuts the load step back.
    Result solve(const dealii::PETScWrappers::MPI::SparseMatrix &matrix,
                 dealii::PETScWrappers::MPI::Vector             &x,
                 const dealii::PETScWrappers::MPI::Vector &rhs, double relative_tolerance);

    // The price of an AMG build in Krylov iterations of the same system: ML's setup took as
    // long as 30-40 iterations on the paper's systems (bench_linear_solver, and the setup and
    // solve times of whole runs in run_summary.json). A constant, not a timing, so that a run
    // repeats itself to the bit.
    static constexpr double setup_cost_in_iterations = 30;

    Kind        kind() const { return kind_; }
    std::string description() const;

  private:
    void destroy();
    void configure_amg(); // the AMG's PETSc options (prefix indentsim_)
    void use_gmres();     // right-preconditioned, true-residual test
    void use_cg();        // true-residual test
    void dump_system(const dealii::PETScWrappers::MPI::SparseMatrix &matrix,
                     const dealii::PETScWrappers::MPI::Vector       &rhs);

    MPI_Comm                                        communicator_;
    Kind                                            kind_ = Kind::direct;
    bool                                            symmetric_ = false;
    KSP                                             ksp_ = nullptr;
    Mat                                             operator_ = nullptr; // the matrix of ksp_
    std::vector<dealii::PETScWrappers::MPI::Vector> rigid_body_modes_;   // orthonormal
    bool            nodal_blocks_ = false; // the unknowns come in 3 x 3 nodal blocks
    BlockMatrixCopy block_copy_;           // the matrix the iterative solver applies (blocks)
    bool            rebuild_preconditioner_ = true;
    double          iterations_per_decade_ = 0; // of the first solve after the last build
    double          stale_iterations_ = 0;      // iterations beyond that rate since the build
    unsigned long   n_solves_ = 0;              // solves so far (INDENTSIM_DUMP_LINEAR_SYSTEMS)
  };

  template <>
  void LinearSolver::setup(const dealii::DoFHandler<2> &, Kind, bool);
  template <>
  void LinearSolver::setup(const dealii::DoFHandler<3> &, Kind, bool);
} // namespace indentsim::linalg
