// Total-Lagrangian finite-strain kernel of the axisymmetric bilinear quadrilateral, with an
// optional F-bar modification: the axisymmetric (r, z) counterpart of FiniteStrainElement.h.
// Units: lengths and displacements in um, stresses in GPa, volumes in um^3, element forces in mN.
//
// The 2D point (x, y) is the reference point (R, Z), R >= 0 the distance from the axis. The
// displacement (u_r, u_z) comes from FESystem(FE_Q<2>(1), 2) with the node-wise dof numbering
// a = 2 i + c (c = 0: u_r, c = 1: u_z; require_axisymmetric_dof_layout checks it). The 3x3
// tensors are in the physical cylindrical components, order (r, theta, z) = (0, 1, 2):
//   F = [[1 + du_r/dR, 0, du_r/dZ], [0, 1 + u_r/R, 0], [du_z/dR, 0, 1 + du_z/dZ]],
// with the hoop stretch 1 + u_r/R. Weights are those of the FULL ring, dV = 2 pi R dR dZ, so
// that the element residual holds whole-ring nodal forces in mN (the force of the whole indent).
//
// G_a = dF/du_a: for dof (i, r) the entries dN_i/dR at (r, R), dN_i/dZ at (r, Z) and N_i/R at
// (theta, theta); for (i, z) dN_i/dR at (z, R) and dN_i/dZ at (z, Z). The residual is
// R_a = sum_q P(F_bar) : B_a dV_q with B_a = dF_bar/du_a, the tangent
// K_ab = B_a : A : B_b + P : dB_a/du_b (exact; symmetric whenever A = dP/dF is).
//
// F-bar (de Souza Neto et al. 1996, variationally consistent total-Lagrangian form, as in 3D):
//   F_bar = theta F,  theta = (J_0 / J)^(1/3),
//   B_a = theta [G_a + 1/3 F c_a],  c_a = d ln J_0/du_a - tr(F^-1 G_a),
//   P : dB_a/du_b = theta/3 [c_b P:G_a + c_a P:G_b + p/3 c_a c_b + p d_ab],  p = P : F,
//   d_ab = dc_a/du_b = d^2 ln J_0/du_a du_b + tr(F^-1 G_b F^-1 G_a).
// J_0 is the element's volume-weighted mean of J over the Gauss points by default
// (FBarDilatation::element_mean, the mean dilatation of Nagtegaal, Parks and Rice 1974): then
// sum_q c_a dV_q = 0 in every homogeneous state, and a homogeneous state is in exact nodal
// equilibrium on any mesh. J_0 = det F at the element centre (element_centre, the 3D kernel's
// choice) breaks that in axisymmetry: the ring weight 2 pi R makes the volume mean of dF/du_a
// differ from its centre value, which leaves the spurious nodal force
// (p/3) sum_q c_a dV_q = -+ (p/3) 2 pi h^2/(3 (1 + b)) on the u_z dofs of a rectangle of radial
// half-width h under u_r = a R, u_z = b Z, which does not cancel on graded or distorted cells
// (docs/theory.md, "Axisymmetric element"; the tests
// AxisymmetricElement.CentreDilatationLeavesTheClosedFormSpuriousForce and
// AxisymmetricElement.GradedPatchIsInInteriorEquilibrium).
#pragma once

#include "materials/MaterialModel.h"

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/fe/fe.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <array>
#include <span>
#include <vector>

namespace indentsim::fem
{
  using dealii::Tensor;

  // Where the F-bar element takes its volumetric part J_0 (see above).
  enum class FBarDilatation
  {
    element_mean,  // sum_q J_q dV_q / sum_q dV_q: exact homogeneous states on any mesh
    element_centre // det F at the element centre, as the 3D kernel
  };

  // A tensor of the block form [[X_rr, 0, X_rz], [0, X_tt, 0], [X_zr, 0, X_zz]] by its five
  // entries, in the order (rr, rz, zr, zz, tt). F, G_a, F^-1 and their products all have this
  // form, so the kernel multiplies and contracts them at 5 entries instead of 9 (and A : B_a at
  // 25 instead of 81).
  using MeridianTensor = std::array<double, 5>;

  struct AxisymmetricScratch
  {
    static constexpr unsigned int n_nodes = 4, n_dofs = 8;

    // n_q_points = k^2 Gauss points (k x k); 4 (2 x 2) by default. Throws std::invalid_argument
    // otherwise.
    explicit AxisymmetricScratch(unsigned int n_q_points = 4);

    unsigned int   n_q_points;
    FBarDilatation dilatation = FBarDilatation::element_mean;

    // Filled by reinit_axisymmetric, at the Gauss points [q] and at the element centre (0):
    std::vector<std::array<double, n_nodes>>       values; // N_i
    std::vector<std::array<Tensor<1, 2>, n_nodes>> grad;   // (dN_i/dR, dN_i/dZ) [1/um]
    std::vector<double>                            radius; // R [um]
    std::vector<double>                            dV;     // 2 pi R det(dX/dxi) w [um^3]
    std::array<double, n_nodes>                    values0;
    std::array<Tensor<1, 2>, n_nodes>              grad0;
    double                                         radius0 = 0;

    // The bilinear shape functions on the reference square (deal.II's FE_Q<2>(1), shape
    // function i at vertex i) and the Gauss rule: fixed at construction.
    std::vector<std::array<double, n_nodes>>       reference_values;
    std::vector<std::array<Tensor<1, 2>, n_nodes>> reference_grad;
    std::vector<double>                            weights;
    std::array<double, n_nodes>                    reference_values0;
    std::array<Tensor<1, 2>, n_nodes>              reference_grad0;

    // Work arrays of the kernel (allocated once).
    std::vector<MeridianTensor>                     F;        // [q]
    std::vector<std::array<MeridianTensor, n_dofs>> G, H;     // [q][a] G_a, F^-1 G_a
    std::vector<std::array<double, n_dofs>>         trace;    // [q][a] tr(F^-1 G_a)
    std::array<MeridianTensor, n_dofs>              B;        // [a] B_a
    std::array<double, n_dofs>                      c, dlnJ0; // [a]
    std::array<std::array<double, n_dofs>, n_dofs>  d2lnJ0;   // [a][b]
  };

  // Throws std::invalid_argument unless `fe` is FESystem(FE_Q<2>(1), 2) with dof a = component
  // a % 2 of node (vertex) a / 2, the numbering the kernel assumes.
  void require_axisymmetric_dof_layout(const dealii::FiniteElement<2> &fe);

  // Fills the scratch from the four vertices (deal.II vertex order; x = R, y = Z, in um) with
  // the bilinear map, as CellWorkspace.cc does for the hexahedron (no FEValues: bitwise
  // reproducible whatever the thread). Throws std::invalid_argument if the map is not
  // orientation-preserving or a Gauss point or the centre lies at R <= 0 (a vertex at R < 0).
  void reinit_axisymmetric(AxisymmetricScratch                   &scratch,
                           const std::array<dealii::Point<2>, 4> &vertices);

  // F in (r, theta, z) components at Gauss point q (q = n_q_points: the element centre) for the
  // element's displacement values u_local [um] (8, a = 2 i + c).
  Tensor<2, 3> axisymmetric_deformation_gradient(const AxisymmetricScratch &scratch, unsigned int q,
                                                 const dealii::Vector<double> &u_local);

  // Residual [mN] (and tangent [mN/um] when `tangent` is not null, 8 x 8) of one element.
  // `state_old` / `state_new` hold n_q_points consecutive material states. `cauchy_stress`
  // (n_q_points entries) receives sigma(F_bar) [GPa] in (r, theta, z) components. A point with
  // a non-positive hoop stretch, in-plane Jacobian or J returns invalid_deformation.
  materials::UpdateStatus axisymmetric_element_residual_and_tangent(
      const materials::MaterialModel &material, bool use_f_bar,
      const dealii::Vector<double> &u_local, std::span<const double> state_old,
      std::span<double> state_new, AxisymmetricScratch &scratch, dealii::Vector<double> &residual,
      dealii::FullMatrix<double> *tangent, std::vector<Tensor<2, 3>> *cauchy_stress = nullptr);
} // namespace indentsim::fem
