// Times the linear solver on systems written by a run with
// INDENTSIM_DUMP_LINEAR_SYSTEMS=DIR:K (PETSc binary: matrix, right-hand side, rigid-body modes),
// to compare preconditioners and their options without rerunning the Newton iterations.
//
//   build/bench_linear_solver [-rtol R] [-reuse | -keep] FILE... [PETSc options]
//   build/bench_linear_solver [-rtol R] -plane N [-plane N ...] [PETSc options]
//
// Defaults: the options indentsim itself uses (GMRES, right-preconditioned, true-residual test,
// ML smoothed aggregation with the rigid-body modes as near-null space, Chebyshev smoothing
// with point-block Jacobi on the matrix's block size, which a dump's .info file gives: 3, the
// nodal blocks, in 3D systems; a dump whose .info file says 1 can be read in nodal blocks with
// -viewer_binary_skip_info -matload_block_size 3 -vecload_block_size 3); any PETSc option
// overrides them (e.g. -pc_type gamg, -mg_levels_pc_type sor). -reuse keeps the first
// system's preconditioner for the following ones (indentsim reuses it while it works); -keep
// keeps one solver object and sets its preconditioner up again for each system (what options
// such as -pc_ml_reuse_interpolation act on).
// -plane N generates, instead of reading files, the system of an axisymmetric (r, z) elastic
// cylinder (E = 69 GPa, nu = 0.26, radius and height 100 um) of N x N bilinear quadrilaterals,
// 2 (N + 1)^2 DOFs in 2 x 2 nodal blocks, u_r = 0 on the axis, u_z = 0 at the bottom, pressed by
// a unit force per node on the top within r < 10 um, near-null space the z translation (what
// indentsim's 2D problems give the AMG): the 2D cost of the solver kinds
// (LinearSolver::choose_kind), e.g. with -ksp_type preonly -pc_type lu
// -pc_factor_mat_solver_type mumps for the direct one. Each plane system is solved twice: the
// second time after its values changed (scaled), as in a later Newton iteration, so the direct
// solver refactors numerically on the kept symbolic analysis (its second setup_s is the figure).
// Prints per system: DOFs, preconditioner setup [s], Krylov solve [s], iterations, and the
// true relative residual. Units of the systems: mN/um, mN, um.
#include <petscksp.h>

#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace
{
  double seconds_since(const std::chrono::steady_clock::time_point start)
  {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  // The axisymmetric plane system of -plane N (see above); `modes` gets the z translation.
  void plane_system(const int n, Mat *A, Vec *b, std::vector<Vec> &modes)
  {
    const double   E = 69, nu = 0.26, length = 100, h = length / n;
    const PetscInt n_nodes = (n + 1) * (n + 1), n_dofs = 2 * n_nodes;
    const double   lambda = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = E / (2 * (1 + nu));
    const auto     node = [n](int i, int j) { return PetscInt(j * (n + 1) + i); }; // i: r, j: z
    MatCreate(PETSC_COMM_WORLD, A);
    MatSetSizes(*A, PETSC_DECIDE, PETSC_DECIDE, n_dofs, n_dofs);
    MatSetType(*A, MATMPIAIJ);
    MatSetBlockSize(*A, 2);
    MatMPIAIJSetPreallocation(*A, 18, nullptr, 18, nullptr);
    PetscInt first_row, end_row;
    MatGetOwnershipRange(*A, &first_row, &end_row);
    // Element stiffness by 2 x 2 Gauss points, strains (rr, zz, theta theta, rz), weight 2 pi r.
    const double gauss[2] = {0.5 - 0.5 / std::sqrt(3.0), 0.5 + 0.5 / std::sqrt(3.0)};
    const int    corner[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        {
          if (2 * node(i, j) < first_row || 2 * node(i, j) >= end_row)
            continue; // the element belongs to the owner of its first node
          double ke[8][8] = {};
          for (const double xi : gauss)
            for (const double eta : gauss)
              {
                const double r = (i + xi) * h;
                double       B[4][8] = {};
                for (int a = 0; a < 4; ++a)
                  {
                    const double sx = corner[a][0] ? xi : 1 - xi, sy = corner[a][1] ? eta : 1 - eta;
                    const double dx = (corner[a][0] ? 1 : -1) * sy / h,
                                 dy = (corner[a][1] ? 1 : -1) * sx / h;
                    B[0][2 * a] = dx;
                    B[1][2 * a + 1] = dy;
                    B[2][2 * a] = sx * sy / r;
                    B[3][2 * a] = dy;
                    B[3][2 * a + 1] = dx;
                  }
                const double D[4][4] = {{lambda + 2 * mu, lambda, lambda, 0},
                                        {lambda, lambda + 2 * mu, lambda, 0},
                                        {lambda, lambda, lambda + 2 * mu, 0},
                                        {0, 0, 0, mu}};
                const double weight = 2 * M_PI * r * h * h / 4;
                for (int p = 0; p < 8; ++p)
                  for (int q = 0; q < 8; ++q)
                    for (int k = 0; k < 4; ++k)
                      for (int l = 0; l < 4; ++l)
                        ke[p][q] += B[k][p] * D[k][l] * B[l][q] * weight;
              }
          PetscInt dofs[8];
          for (int a = 0; a < 4; ++a)
            for (int c = 0; c < 2; ++c)
              dofs[2 * a + c] = 2 * node(i + corner[a][0], j + corner[a][1]) + c;
          MatSetValues(*A, 8, dofs, 8, dofs, &ke[0][0], ADD_VALUES);
        }
    MatAssemblyBegin(*A, MAT_FINAL_ASSEMBLY);
    MatAssemblyEnd(*A, MAT_FINAL_ASSEMBLY);
    MatCreateVecs(*A, nullptr, b);
    VecSet(*b, 0.0);
    for (int i = 0; i <= n; ++i)
      if (i * h < 0.1 * length && 2 * node(i, n) >= first_row && 2 * node(i, n) < end_row)
        VecSetValue(*b, 2 * node(i, n) + 1, -1.0, INSERT_VALUES);
    VecAssemblyBegin(*b);
    VecAssemblyEnd(*b);
    std::vector<PetscInt> fixed; // u_r on the axis, u_z at the bottom (rows owned here)
    for (int j = 0; j <= n; ++j)
      if (2 * node(0, j) >= first_row && 2 * node(0, j) < end_row)
        fixed.push_back(2 * node(0, j));
    for (int i = 0; i <= n; ++i)
      if (2 * node(i, 0) >= first_row && 2 * node(i, 0) < end_row)
        fixed.push_back(2 * node(i, 0) + 1);
    MatZeroRowsColumns(*A, PetscInt(fixed.size()), fixed.data(), 1.0, nullptr, nullptr);
    Vec mode;
    VecDuplicate(*b, &mode);
    for (PetscInt row = first_row; row < end_row; ++row)
      VecSetValue(mode, row, row % 2 == 1 ? 1.0 : 0.0, INSERT_VALUES);
    VecAssemblyBegin(mode);
    VecAssemblyEnd(mode);
    VecNormalize(mode, nullptr);
    modes.push_back(mode);
  }

  void set_default(const char *name, const char *value)
  {
    PetscBool set = PETSC_FALSE;
    PetscOptionsHasName(nullptr, nullptr, name, &set);
    if (!set)
      PetscOptionsSetValue(nullptr, name, value);
  }
} // namespace

int main(int argc, char **argv)
{
  std::vector<std::string> files;
  std::vector<int>         plane_sizes;
  double                   rtol = 1e-4;
  bool                     reuse = false;
  bool                     keep = false; // one KSP for all systems, set up again for each
  std::vector<char *>      petsc_arguments{argv[0]};
  for (int i = 1; i < argc; ++i)
    {
      if (std::strcmp(argv[i], "-rtol") == 0 && i + 1 < argc)
        rtol = std::atof(argv[++i]);
      else if (std::strcmp(argv[i], "-reuse") == 0)
        reuse = true;
      else if (std::strcmp(argv[i], "-keep") == 0)
        keep = true;
      else if (std::strcmp(argv[i], "-plane") == 0 && i + 1 < argc)
        {
          plane_sizes.push_back(std::atoi(argv[++i]));
          files.push_back("plane_" + std::to_string(plane_sizes.back()));
          files.push_back("plane_" + std::to_string(plane_sizes.back()) + "_again");
        }
      else if (argv[i][0] == '-')
        {
          petsc_arguments.push_back(argv[i]);
          const bool next_is_option =
              i + 1 < argc && argv[i + 1][0] == '-' && std::isalpha(argv[i + 1][1]);
          if (i + 1 < argc && !next_is_option && std::strstr(argv[i + 1], ".bin") == nullptr)
            petsc_arguments.push_back(argv[++i]);
        }
      else
        files.emplace_back(argv[i]);
    }
  int petsc_argc = static_cast<int>(petsc_arguments.size());
  petsc_arguments.push_back(nullptr); // argv[argc] = NULL, as MPI_Init expects
  char **petsc_argv = petsc_arguments.data();
  PetscInitialize(&petsc_argc, &petsc_argv, nullptr, nullptr);
  if (files.empty())
    {
      PetscPrintf(PETSC_COMM_WORLD, "usage: bench_linear_solver [-rtol R] [-reuse | -keep] FILE... "
                                    "| -plane N... [PETSc options]\n");
      PetscFinalize();
      return 2;
    }
  set_default("-ksp_type", "gmres");
  set_default("-ksp_gmres_restart", "200");
  set_default("-ksp_pc_side", "right");
  set_default("-ksp_norm_type", "unpreconditioned");
  set_default("-pc_type", "ml");
  set_default("-pc_ml_nullspace", "user");
  set_default("-pc_gamg_threshold", "0.01");
  set_default("-pc_gamg_square_graph", "1");
  set_default("-mg_levels_ksp_type", "chebyshev");
  set_default("-mg_levels_pc_type", "pbjacobi");
  set_default("-mg_levels_ksp_max_it", "2");

  KSP ksp = nullptr;
  PetscPrintf(PETSC_COMM_WORLD, "file dofs setup_s solve_s iterations true_relative_residual\n");
  double total_setup = 0, total_solve = 0;
  long   total_iterations = 0;
  Mat    plane_matrix = nullptr; // -plane: kept for its second solve
  Vec    plane_rhs = nullptr;
  for (const auto &file : files)
    {
      Mat              A;
      Vec              b, x;
      std::vector<Vec> modes;
      const bool       plane = file.rfind("plane_", 0) == 0;
      const bool       plane_again = plane && file.find("_again") != std::string::npos;
      if (plane_again)
        {
          // The same pattern with new values: a later Newton iteration's system.
          A = plane_matrix;
          b = plane_rhs;
          MatScale(A, 2.0);
          VecScale(b, 2.0);
          MatCreateVecs(A, &x, nullptr);
          plane_matrix = nullptr;
          plane_rhs = nullptr;
        }
      else if (plane)
        {
          plane_system(std::atoi(file.c_str() + 6), &A, &b, modes);
          MatCreateVecs(A, &x, nullptr);
          PetscObjectReference(reinterpret_cast<PetscObject>(A));
          PetscObjectReference(reinterpret_cast<PetscObject>(b));
          plane_matrix = A;
          plane_rhs = b;
        }
      else
        {
          PetscViewer viewer;
          PetscViewerBinaryOpen(PETSC_COMM_WORLD, file.c_str(), FILE_MODE_READ, &viewer);
          MatCreate(PETSC_COMM_WORLD, &A);
          MatSetType(A, MATMPIAIJ);
          MatLoad(A, viewer);
          MatCreateVecs(A, &x, &b);
          VecLoad(b, viewer);
          // The rigid-body modes follow if the run was iterative (none after a direct run's
          // system): read until the file ends, which PETSc reports as an error, silenced here.
          PetscPushErrorHandler(PetscIgnoreErrorHandler, nullptr);
          for (int k = 0; k < 6; ++k)
            {
              Vec mode;
              VecDuplicate(b, &mode);
              if (VecLoad(mode, viewer) != 0)
                {
                  VecDestroy(&mode);
                  break;
                }
              modes.push_back(mode);
            }
          PetscPopErrorHandler();
          PetscViewerDestroy(&viewer);
        }
      if (!modes.empty())
        {
          MatNullSpace near_null_space;
          MatNullSpaceCreate(PETSC_COMM_WORLD, PETSC_FALSE, PetscInt(modes.size()), modes.data(),
                             &near_null_space);
          MatSetNearNullSpace(A, near_null_space);
          MatNullSpaceDestroy(&near_null_space);
        }
      const bool fresh = ksp == nullptr || !reuse;
      if (ksp == nullptr || (!reuse && !keep && !plane_again))
        {
          if (ksp)
            KSPDestroy(&ksp);
          KSPCreate(PETSC_COMM_WORLD, &ksp);
          KSPSetFromOptions(ksp);
        }
      // -operator_type baij: the Krylov method and the smoothers apply a copy of the matrix
      // in that storage format (the hierarchy is still built from the AIJ matrix).
      Mat       op = A;
      char      operator_type[64] = "";
      PetscBool has_operator_type = PETSC_FALSE;
      PetscOptionsGetString(nullptr, nullptr, "-operator_type", operator_type,
                            sizeof(operator_type), &has_operator_type);
      if (has_operator_type)
        {
          const auto convert_start = std::chrono::steady_clock::now();
          MatConvert(A, operator_type, MAT_INITIAL_MATRIX, &op);
          PetscPrintf(PETSC_COMM_WORLD, "converted to %s in %.3f s\n", operator_type,
                      seconds_since(convert_start));
        }
      KSPSetOperators(ksp, op, A);
      KSPSetReusePreconditioner(ksp, fresh ? PETSC_FALSE : PETSC_TRUE);
      KSPSetTolerances(ksp, rtol, 0.0, PETSC_DEFAULT, 1000);
      auto start = std::chrono::steady_clock::now();
      KSPSetUp(ksp);
      PC pc;
      KSPGetPC(ksp, &pc);
      if (fresh)
        PCSetUp(pc);
      const double setup = seconds_since(start);
      start = std::chrono::steady_clock::now();
      KSPSolve(ksp, b, x);
      const double solve = seconds_since(start);
      PetscInt     iterations;
      KSPGetIterationNumber(ksp, &iterations);
      Vec r;
      VecDuplicate(b, &r);
      MatMult(A, x, r);
      VecAYPX(r, -1.0, b);
      PetscReal rn, bn;
      VecNorm(r, NORM_2, &rn);
      VecNorm(b, NORM_2, &bn);
      PetscInt n;
      MatGetSize(A, &n, nullptr);
      PetscPrintf(PETSC_COMM_WORLD, "%s %d %.3f %.3f %d %.2e\n", file.c_str(), int(n), setup, solve,
                  int(iterations), double(rn / bn));
      total_setup += setup;
      total_solve += solve;
      total_iterations += iterations;
      VecDestroy(&r);
      for (auto &mode : modes)
        VecDestroy(&mode);
      VecDestroy(&x);
      VecDestroy(&b);
      if (op != A)
        MatDestroy(&op);
      MatDestroy(&A);
    }
  PetscPrintf(PETSC_COMM_WORLD, "total setup %.3f s, solve %.3f s, %ld iterations\n", total_setup,
              total_solve, total_iterations);
  if (ksp)
    KSPDestroy(&ksp);
  PetscFinalize();
  return 0;
}
