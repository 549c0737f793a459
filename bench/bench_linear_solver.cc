// Times the linear solver on systems written by a run with
// INDENTSIM_DUMP_LINEAR_SYSTEMS=DIR:K (PETSc binary: matrix, right-hand side, rigid-body modes),
// to compare preconditioners and their options without rerunning the Newton iterations.
//
//   build/bench_linear_solver [-rtol R] [-reuse | -keep] FILE... [PETSc options]
//
// Defaults: the options indentsim itself uses (GMRES, right-preconditioned, true-residual test,
// ML smoothed aggregation with the rigid-body modes as near-null space, Chebyshev smoothing
// with point-block Jacobi on the matrix's block size: 3, the nodal blocks, in systems dumped
// since session 19; older dumps say 1 in their .info file, override it with
// -viewer_binary_skip_info -matload_block_size 3 -vecload_block_size 3); any PETSc option
// overrides them (e.g. -pc_type gamg, -mg_levels_pc_type sor). -reuse keeps the first
// system's preconditioner for the following ones (indentsim reuses it while it works); -keep
// keeps one solver object and sets its preconditioner up again for each system (what options
// such as -pc_ml_reuse_interpolation act on).
// Prints per system: DOFs, preconditioner setup [s], Krylov solve [s], iterations, and the
// true relative residual. Units of the systems: mN/um, mN, um.
#include <petscksp.h>

#include <cctype>
#include <chrono>
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
      PetscPrintf(
          PETSC_COMM_WORLD,
          "usage: bench_linear_solver [-rtol R] [-reuse | -keep] FILE... [PETSc options]\n");
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
  for (const auto &file : files)
    {
      PetscViewer viewer;
      PetscViewerBinaryOpen(PETSC_COMM_WORLD, file.c_str(), FILE_MODE_READ, &viewer);
      Mat A;
      MatCreate(PETSC_COMM_WORLD, &A);
      MatSetType(A, MATMPIAIJ);
      MatLoad(A, viewer);
      Vec b, x;
      MatCreateVecs(A, &x, &b);
      VecLoad(b, viewer);
      std::vector<Vec> modes;
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
      PetscViewerDestroy(&viewer);
      if (!modes.empty())
        {
          MatNullSpace near_null_space;
          MatNullSpaceCreate(PETSC_COMM_WORLD, PETSC_FALSE, PetscInt(modes.size()), modes.data(),
                             &near_null_space);
          MatSetNearNullSpace(A, near_null_space);
          MatNullSpaceDestroy(&near_null_space);
        }
      const bool fresh = ksp == nullptr || !reuse;
      if (ksp == nullptr || (!reuse && !keep))
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
