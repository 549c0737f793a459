// Uniaxial tension of a cube, the calibration test of the paper (section 3, fig. 3): a cube of
// n x n x n trilinear hexahedra of 1 um edge (edge L = n um, n = specimen.elements_per_side),
// one grain per element (specimen.grains: per_element, random orientations) or a single
// crystal. Total-Lagrangian, the element kernel of FiniteStrainElement.h (F-bar per
// specimen.f_bar), the material of materials::create_material. Units: um, mN, GPa.
//
// Boundary conditions (x, y, z sample axes, the cube is [0, L]^3):
//   u_x = 0 on x = 0,  u_y = 0 on y = 0,  u_z = 0 on z = 0   (frictionless rollers),
//   u_z = L (exp(eps) - 1) on z = L (uniform), tangentially free,
//   x = L and y = L traction-free.
// An isotropic material therefore deforms homogeneously and the rollers are exact symmetry
// planes of the octant of a larger bar; a polycrystal deforms heterogeneously but its top face
// stays flat.
//
// The logarithmic strain eps grows in loading.steps equal increments to loading.max_strain.
// Each increment is solved by Newton's method (PETSc MPI matrix, linalg/LinearSolver.h) with the
// standard treatment of the inhomogeneous Dirichlet condition: the first iteration applies the
// increment of u_z on the top face through inhomogeneous constraints (a linearised predictor
// over the whole cube), later iterations use the homogeneous constraints. A failing material
// point or a diverging Newton iteration halves the increment (up to loading.max_cutbacks
// successive halvings); nothing is recorded from an unconverged state.
#pragma once

#include "case/Case.h"
#include "fem/CellWorkspace.h"
#include "fem/FiniteStrainElement.h"
#include "fem/QuadraturePointHistory.h"
#include "fem/SolidDiscretisation.h"
#include "linalg/LinearSolver.h"
#include "materials/MaterialModel.h"
#include "nonlinear/IncrementStatus.h"
#include "output/OutputFile.h"
#include "output/RunStatistics.h"

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/timer.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/petsc_sparse_matrix.h>
#include <deal.II/lac/petsc_vector.h>

#include <memory>
#include <span>
#include <string>
#include <vector>

namespace indentsim::problems
{
  // One row of stress_strain.csv, at the end of a load step.
  struct TensileRecord
  {
    unsigned int step = 0;
    double       log_strain = 0;         // ln(1 + u_top / L) [-]
    double       true_stress = 0;        // volume average of the Cauchy stress sigma_zz [GPa]
    double       engineering_strain = 0; // u_top / L [-]
    double       force = 0;              // total z force on the top face [mN]
    unsigned int newton_iterations = 0;  // summed over the sub-increments of a cut-back step
    unsigned int cutbacks = 0;           // halvings needed in this step
    double       wall_time = 0;          // [s] since the start of the run
  };

  class TensileProblem
  {
  public:
    // Copies the case; the material is materials::create_material(the_case.material).
    TensileProblem(const io::Case &the_case, MPI_Comm communicator, bool verbose = true);
    ~TensileProblem();

    // Builds the cube, dofs, constraints and the oriented initial material states.
    void setup();

    // Runs the loading. With a non-empty `output_directory` (which must exist) rank 0 writes
    // `csv_file_name` there and appends to run.log, and with `write_paraview_file` the final
    // state goes to specimen_NNNN.pvtu (NNNN = last step); a run writing stress_strain.csv also
    // writes run_summary.json (RunStatistics.h). Throws std::runtime_error if an
    // increment fails after loading.max_cutbacks halvings.
    void run(const std::string &output_directory, const std::string &csv_file_name,
             bool write_paraview_file);

    const std::vector<TensileRecord> &records() const { return records_; }
    unsigned int                      n_cells() const;
    unsigned int                      n_dofs() const;

    // Index i + n j + n^2 k of the element whose centre lies in [i, i+1) x [j, j+1) x [k, k+1)
    // (um): the grain number, independent of the MPI partition.
    unsigned int lexicographic_index(const dealii::Point<3> &cell_centre) const;

  private:
    struct AssemblyResult
    {
      materials::UpdateStatus status = materials::UpdateStatus::success;
      double                  top_force = 0; // z force on the face z = L [mN]
      double                  volume = 0;    // current volume, integral of det F [um^3]
    };
    // The Dirichlet conditions of the header; `top_increment` [um] is the inhomogeneity of u_z
    // on z = L (0: the homogeneous set of the correction iterations).
    void make_dirichlet_constraints(double                             top_increment,
                                    dealii::AffineConstraints<double> &constraints) const;
    // Residual (as the right-hand side -R) and tangent scattered with `constraints`.
    AssemblyResult assemble(const dealii::AffineConstraints<double> &constraints);
    // l2 norm of the right-hand side over the unconstrained dofs [mN].
    double free_residual_norm(const dealii::AffineConstraints<double> &constraints) const;

    // Newton from the last converged state to top displacement `u_top` [um].
    nonlinear::IncrementStatus solve_increment(double u_top, unsigned int &iterations,
                                               AssemblyResult &result);
    // One load step in sub-increments with cut-backs.
    AssemblyResult solve_step(unsigned int step, double target, double &strain,
                              TensileRecord &record, output::AppendFile &log);
    void           accept_increment();
    void           reject_increment();

    void write_paraview(const std::string &output_directory, unsigned int index);

    const io::Case                    case_;
    MPI_Comm                          communicator_;
    dealii::ConditionalOStream        pcout_;
    fem::SolidDiscretisation<3>       solid_; // mesh, elements, DoFs, index sets
    dealii::AffineConstraints<double> constraints_homogeneous_;
    dealii::AffineConstraints<double> constraints_increment_;

    std::unique_ptr<materials::MaterialModel> material_;
    bool                                      use_f_bar_;
    unsigned int                              n_per_side_;
    double                                    edge_length_;

    dealii::PETScWrappers::MPI::SparseMatrix matrix_;
    linalg::LinearSolver                     linear_solver_;
    dealii::PETScWrappers::MPI::Vector       solution_;           // ghosted
    dealii::PETScWrappers::MPI::Vector       solution_converged_; // ghosted
    dealii::PETScWrappers::MPI::Vector       rhs_;                // owned

    // Material states of the quadrature points; grain number per cell.
    fem::QuadraturePointHistory history_;
    std::vector<unsigned int>   grain_of_cell_;
    double                      u_top_converged_ = 0; // [um]

    std::vector<TensileRecord> records_;
    output::RunStatistics      statistics_;
    dealii::Timer              wall_timer_;
  };
} // namespace indentsim::problems
