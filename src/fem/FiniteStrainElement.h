// Total-Lagrangian finite-strain hexahedron kernel with an optional F-bar modification.
// Units: stresses in GPa, lengths in um, element forces in mN.
//
// Pointwise physics only: the kernel receives the reference gradients g_i = grad_X N_i of the
// eight nodal shape functions at the quadrature points and at the element centre, the element's
// displacement values and the material, and returns the element residual, tangent and updated
// material states. It knows nothing about meshes, constraints or MPI. Element dof a is
// component c(a) of node i(a) (deal.II's FESystem(FE_Q(1), 3) numbering, a = 3 i + c), so
// G_a = dF/du_a = e_c (x) g_i has one non-zero row; the kernel works with g_i directly and never
// forms G_a (a third of the flops of the dense form).
//
// F-bar (de Souza Neto et al. 1996, in the variationally consistent total-Lagrangian form):
//   F_bar = theta F,  theta = (J_0 / J)^(1/3),  J_0 = det F at the element centre.
// The residual is R_a = sum_q P(F_bar) : dF_bar/du_a w_q with
//   dF_bar/du_a = B_a = theta [G_a + 1/3 F c_a],  c_a = tr(F_0^-1 G0_a) - tr(F^-1 G_a)
//                                                    = (F_0^-T g0_i)_c - (F^-T g_i)_c,
// and the tangent K_ab = B_a : A : B_b + P : dB_a/du_b, which is symmetric whenever the material
// tangent A = dP/dF is. Without F-bar, theta = 1 and B_a = G_a (plain displacement element).
#pragma once

#include "materials/MaterialModel.h"

#include <deal.II/base/tensor.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <array>
#include <span>
#include <vector>

namespace indentsim::fem
{
  using dealii::Tensor;

  // One quadrature point's factors of the tangent (hexahedron: 8 nodes, 24 DOFs), laid out
  // for the vectorized accumulation in FiniteStrainElement.cc: arrays over the nodes j last.
  struct PointTangentTerms
  {
    alignas(64) double gT[3][8];            // g_jL
    alignas(64) double YT[4][3][8];         // F-bar factors Y_k of DOF (j, d)
    alignas(64) double hT[3][8], h0T[3][8]; // (F^-T g_j)_c, (F_0^-T g0_j)_c
    double P[24][3][3];                     // theta^2 w g_iJ A_cJdL of row a = 3 i + c
    double X[24][4];                        // F-bar factors X_k of row a
    double h[8][3], h0[8][3];
    double weighted_geometric_p = 0; // w theta / 3 P : F
    bool   f_bar = false;
  };

  struct ElementScratch
  {
    explicit ElementScratch(unsigned int n_nodes = 8, unsigned int n_q_points = 8);
    unsigned int                           n_nodes, n_dofs, n_q_points;
    std::vector<std::vector<Tensor<1, 3>>> grad;  // [q][i] grad_X N_i at quadrature point q
    std::vector<Tensor<1, 3>>              grad0; // [i] grad_X N_i at the element centre
    std::vector<double>                    JxW;   // [q] reference volume weights
    // Work arrays (allocated once).
    std::vector<Tensor<1, 3>> h, h0, Pg; // [i]
    std::vector<double>       c, beta;   // [a]
    PointTangentTerms         point;
    // The element tangent with its columns ordered by component (row a, column d 8 + j),
    // copied into deal.II's order at the end of the element.
    std::vector<double> K_columns_by_component;
  };

  // F = 1 + sum_i u_i (x) g_i at quadrature point q (q = n_q_points: the element centre).
  Tensor<2, 3> deformation_gradient(const ElementScratch &scratch, unsigned int q,
                                    const dealii::Vector<double> &u_local);

  // Computes residual (and tangent when `tangent` is not null) for one element.
  // `state_old` / `state_new` hold n_q_points consecutive material states.
  materials::UpdateStatus element_residual_and_tangent(
      const materials::MaterialModel &material, bool use_f_bar,
      const dealii::Vector<double> &u_local, std::span<const double> state_old,
      std::span<double> state_new, ElementScratch &scratch, dealii::Vector<double> &residual,
      dealii::FullMatrix<double> *tangent, std::vector<Tensor<2, 3>> *cauchy_stress = nullptr);
} // namespace indentsim::fem
