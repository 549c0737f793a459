// Verification of the axisymmetric finite-strain quadrilateral (fem/AxisymmetricElement.h): its
// geometry against FEValues and Pappus, its kinematics against the Cartesian field of the ring,
// its tangent against finite differences of its residual, and homogeneous states against the
// closed-form nodal forces of a uniform stress on the element's boundary. Units: um, mN, GPa.
#include "case/Case.h"
#include "fem/AxisymmetricElement.h"
#include "fem/FiniteStrainElement.h"
#include "materials/MaterialFactory.h"

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace dealii;
using namespace indentsim;

namespace
{
  using Vertices = std::array<Point<2>, 4>; // deal.II vertex order, (R, Z) [um]

  // An axis-parallel rectangle [R1, R2] x [Z1, Z2].
  Vertices rectangle(double R1, double R2, double Z1, double Z2)
  {
    return {{Point<2>(R1, Z1), Point<2>(R2, Z1), Point<2>(R1, Z2), Point<2>(R2, Z2)}};
  }
  // A distorted quadrilateral away from the axis and one with an edge on it (R = 0 at vertices
  // 0 and 2).
  const Vertices away_from_axis = {
      {Point<2>(1.0, 0.2), Point<2>(3.1, -0.1), Point<2>(1.3, 1.9), Point<2>(2.8, 2.2)}};
  const Vertices touching_axis = {
      {Point<2>(0.0, 0.0), Point<2>(1.1, 0.15), Point<2>(0.0, 1.0), Point<2>(0.9, 1.2)}};

  io::MaterialParameters paper_material(const std::string &model)
  {
    io::MaterialParameters m;
    m.model = model;
    return m; // Table 1: E 69 GPa, nu 0.26, sigma_y0 0.305 GPa, H 0.5 GPa
  }

  std::vector<double> virgin_states(const materials::MaterialModel &material, unsigned int n_q)
  {
    const unsigned int  n_state = material.n_state_variables();
    std::vector<double> states(n_q * n_state);
    for (unsigned int q = 0; q < n_q; ++q)
      material.initial_state(std::span<double>(states).subspan(q * n_state, n_state));
    return states;
  }

  fem::AxisymmetricScratch
  scratch_on(const Vertices     &vertices,
             fem::FBarDilatation dilatation = fem::FBarDilatation::element_mean)
  {
    fem::AxisymmetricScratch scratch;
    scratch.dilatation = dilatation;
    fem::reinit_axisymmetric(scratch, vertices);
    return scratch;
  }

  // Nodal values of u_r = a R, u_z = b Z + c.
  Vector<double> homogeneous_displacement(const Vertices &vertices, double a, double b, double c)
  {
    Vector<double> u(8);
    for (unsigned int i = 0; i < 4; ++i)
      {
        u[2 * i] = a * vertices[i][0];
        u[2 * i + 1] = b * vertices[i][1] + c;
      }
    return u;
  }

  // The nodal forces of a uniform first Piola stress P on the element's boundary, written from
  // the definition f_(i,c) = sum over edges of integral N_i (P N)_c 2 pi R ds: on the straight
  // edge from vertex A to vertex B (length L, outward normal N = (N_R, 0, N_Z)) N_A = 1 - s,
  // N_B = s and R = R_A + s (R_B - R_A), s in [0, 1], so that the integral of N_A R is
  // L (2 R_A + R_B)/6 and that of N_B R is L (R_A + 2 R_B)/6 (exact).
  Vector<double> boundary_nodal_forces(const Vertices &v, const Tensor<2, 3> &P)
  {
    const std::array<std::array<unsigned int, 2>, 4> edges = {
        {{{0, 1}}, {{1, 3}}, {{3, 2}}, {{2, 0}}}};
    const Point<2> centroid = 0.25 * (v[0] + v[1] + v[2] + v[3]);
    Vector<double> f(8);
    for (const auto &[A, B] : edges)
      {
        const Tensor<1, 2> t = v[B] - v[A];
        const double       L = t.norm();
        Tensor<1, 2>       n({t[1] / L, -t[0] / L});
        if (n * (0.5 * (v[A] + v[B]) - centroid) < 0)
          n = -n;
        const double traction_r = P[0][0] * n[0] + P[0][2] * n[1],
                     traction_z = P[2][0] * n[0] + P[2][2] * n[1];
        const double ring_A = 2 * numbers::PI * L * (2 * v[A][0] + v[B][0]) / 6,
                     ring_B = 2 * numbers::PI * L * (v[A][0] + 2 * v[B][0]) / 6;
        f[2 * A] += traction_r * ring_A;
        f[2 * A + 1] += traction_z * ring_A;
        f[2 * B] += traction_r * ring_B;
        f[2 * B + 1] += traction_z * ring_B;
      }
    return f;
  }

  double max_abs(const Vector<double> &v)
  {
    return v.linfty_norm();
  }
} // namespace

// The shape values, gradients, radii and ring weights that reinit_axisymmetric computes from the
// vertices equal deal.II's FEValues (MappingQ1) with dV = 2 pi R JxW, at the Gauss points and
// at the centre, on a distorted cell and on one touching the axis.
TEST(AxisymmetricElement, ScratchMatchesFEValues)
{
  for (const Vertices &vertices : {away_from_axis, touching_axis})
    {
      Triangulation<2> tria;
      GridGenerator::general_cell(tria, std::vector<Point<2>>(vertices.begin(), vertices.end()));
      const FE_Q<2> fe(1);
      FEValues<2>   fe_values(fe, QGauss<2>(2),
                              update_values | update_gradients | update_JxW_values |
                                  update_quadrature_points);
      FEValues<2>   fe_centre(fe, QGauss<2>(1),
                              update_values | update_gradients | update_quadrature_points);
      fe_values.reinit(tria.begin_active());
      fe_centre.reinit(tria.begin_active());
      const fem::AxisymmetricScratch s = scratch_on(vertices);
      double                         error = 0;
      for (unsigned int q = 0; q < 4; ++q)
        {
          const double R = fe_values.quadrature_point(q)[0];
          EXPECT_GT(R, 0);
          EXPECT_NEAR(s.radius[q], R, 1e-14);
          EXPECT_NEAR(s.dV[q], 2 * numbers::PI * R * fe_values.JxW(q), 1e-13 * s.dV[q]);
          for (unsigned int i = 0; i < 4; ++i)
            {
              error = std::max(error, std::abs(s.values[q][i] - fe_values.shape_value(i, q)));
              error = std::max(error, (s.grad[q][i] - fe_values.shape_grad(i, q)).norm());
            }
        }
      EXPECT_NEAR(s.radius0, fe_centre.quadrature_point(0)[0], 1e-14);
      for (unsigned int i = 0; i < 4; ++i)
        {
          error = std::max(error, std::abs(s.values0[i] - fe_centre.shape_value(i, 0)));
          error = std::max(error, (s.grad0[i] - fe_centre.shape_grad(i, 0)).norm());
        }
      EXPECT_LT(error, 1e-13);
    }
}

// The kernel refuses a displacement element with another dof numbering, cells with a vertex at
// R < 0 and inverted cells, and any number of Gauss points that is not k x k.
TEST(AxisymmetricElement, RefusesOtherElementsAndBadCells)
{
  EXPECT_NO_THROW(fem::require_axisymmetric_dof_layout(FESystem<2>(FE_Q<2>(1), 2)));
  EXPECT_THROW(fem::require_axisymmetric_dof_layout(FESystem<2>(FE_Q<2>(2), 2)),
               std::invalid_argument);
  EXPECT_THROW(fem::require_axisymmetric_dof_layout(FESystem<2>(FE_Q<2>(1), 3)),
               std::invalid_argument);
  EXPECT_THROW(fem::require_axisymmetric_dof_layout(FE_Q<2>(1)), std::invalid_argument);
  fem::AxisymmetricScratch s;
  EXPECT_THROW(fem::reinit_axisymmetric(s, rectangle(-1.0, 0.5, 0, 1)), std::invalid_argument);
  EXPECT_THROW(fem::reinit_axisymmetric(s, rectangle(2.0, 1.0, 0, 1)), std::invalid_argument);
  EXPECT_THROW(fem::AxisymmetricScratch(5), std::invalid_argument);
  EXPECT_NO_THROW(fem::reinit_axisymmetric(s, rectangle(0.0, 1.0, 0, 1)));
}

// The element's volume is the whole ring's: pi (R2^2 - R1^2)(Z2 - Z1) for a rectangle, and by
// Pappus' theorem 2 pi R_centroid A (area and centroid of the polygon by the shoelace formula)
// for distorted cells, with and without an edge on the axis.
TEST(AxisymmetricElement, RingVolumeIsExact)
{
  const auto volume = [](const Vertices &v) {
    const fem::AxisymmetricScratch s = scratch_on(v);
    return s.dV[0] + s.dV[1] + s.dV[2] + s.dV[3];
  };
  EXPECT_NEAR(volume(rectangle(1.5, 4.0, -1, 2)), numbers::PI * (16 - 2.25) * 3,
              1e-14 * numbers::PI * (16 - 2.25) * 3);
  for (const Vertices &v : {away_from_axis, touching_axis})
    {
      const std::array<Point<2>, 4> polygon = {{v[0], v[1], v[3], v[2]}}; // counter-clockwise
      double                        area = 0, moment_R = 0;
      for (unsigned int k = 0; k < 4; ++k)
        {
          const Point<2> &p = polygon[k], &n = polygon[(k + 1) % 4];
          const double    cross = p[0] * n[1] - n[0] * p[1];
          area += cross / 2;
          moment_R += (p[0] + n[0]) * cross / 6;
        }
      const double pappus = 2 * numbers::PI * moment_R; // 2 pi (moment_R / area) area
      EXPECT_GT(area, 0);
      EXPECT_NEAR(volume(v), pappus, 1e-13 * pappus);
    }
}

// F at the Gauss points is the deformation gradient of the 3D ring field
// x = (R + u_r) e_r(phi) + (Z + u_z) e_z, computed by central differences in Cartesian
// components and rotated into (e_r, e_theta, e_z): the hoop stretch 1 + u_r/R included.
TEST(AxisymmetricElement, DeformationGradientIsTheRingsCartesianGradient)
{
  const FE_Q<2>   bilinear(1);
  const QGauss<2> gauss(2);
  for (const Vertices &v : {away_from_axis, touching_axis})
    {
      const fem::AxisymmetricScratch s = scratch_on(v);
      Vector<double>                 u(8);
      for (unsigned int a = 0; a < 8; ++a)
        u[a] = 0.1 * std::sin(1.3 * a + 0.4);
      // Reference and current position of the ring's point (xi, eta, phi).
      const auto position = [&](const Point<2> &xi, double phi, bool deformed) {
        double R = 0, Z = 0;
        for (unsigned int i = 0; i < 4; ++i)
          {
            const double N = bilinear.shape_value(i, xi);
            R += N * (v[i][0] + (deformed ? u[2 * i] : 0.));
            Z += N * (v[i][1] + (deformed ? u[2 * i + 1] : 0.));
          }
        return Tensor<1, 3>({R * std::cos(phi), R * std::sin(phi), Z});
      };
      const double phi = 0.7, step = 1e-5;
      for (unsigned int q = 0; q < 4; ++q)
        {
          // dx/d(xi, eta, phi) and dX/d(xi, eta, phi) by central differences.
          Tensor<2, 3> dx, dX;
          for (unsigned int k = 0; k < 3; ++k)
            for (const bool deformed : {false, true})
              {
                Point<2> xi_plus = gauss.point(q), xi_minus = gauss.point(q);
                double   phi_plus = phi, phi_minus = phi;
                (k < 2 ? xi_plus[k] : phi_plus) += step;
                (k < 2 ? xi_minus[k] : phi_minus) -= step;
                const Tensor<1, 3> column = (position(xi_plus, phi_plus, deformed) -
                                             position(xi_minus, phi_minus, deformed)) /
                                            (2 * step);
                for (unsigned int m = 0; m < 3; ++m)
                  (deformed ? dx : dX)[m][k] = column[m];
              }
          const Tensor<2, 3> F_cartesian = dx * invert(dX);
          Tensor<2, 3>       Q; // columns e_r, e_theta, e_z
          Q[0][0] = std::cos(phi), Q[1][0] = std::sin(phi);
          Q[0][1] = -std::sin(phi), Q[1][1] = std::cos(phi);
          Q[2][2] = 1;
          const Tensor<2, 3> expected = transpose(Q) * F_cartesian * Q;
          const Tensor<2, 3> F = fem::axisymmetric_deformation_gradient(s, q, u);
          EXPECT_LT((F - expected).norm(), 1e-8) << "q " << q;
          EXPECT_GT(std::abs(F[1][1] - 1), 1e-3); // the hoop stretch is exercised
        }
    }
}

namespace
{
  // Largest entry-wise difference between the element tangent and central differences of the
  // element residual, relative to the largest tangent entry, at the displacement `u` from the
  // states `state_old`.
  double tangent_error(const materials::MaterialModel &material, bool f_bar,
                       fem::AxisymmetricScratch &s, const Vector<double> &u,
                       const std::vector<double> &state_old)
  {
    std::vector<double> state_new(state_old);
    Vector<double>      r(8), r_plus(8), r_minus(8);
    FullMatrix<double>  K(8, 8);
    EXPECT_EQ(fem::axisymmetric_element_residual_and_tangent(material, f_bar, u, state_old,
                                                             state_new, s, r, &K),
              materials::UpdateStatus::success);
    double       error = 0, scale = 0;
    const double step = 1e-7;
    for (unsigned int b = 0; b < 8; ++b)
      {
        Vector<double> up(u), um(u);
        up[b] += step;
        um[b] -= step;
        fem::axisymmetric_element_residual_and_tangent(material, f_bar, up, state_old, state_new, s,
                                                       r_plus, nullptr);
        fem::axisymmetric_element_residual_and_tangent(material, f_bar, um, state_old, state_new, s,
                                                       r_minus, nullptr);
        for (unsigned int a = 0; a < 8; ++a)
          {
            error = std::max(error, std::abs(K(a, b) - (r_plus[a] - r_minus[a]) / (2 * step)));
            scale = std::max(scale, std::abs(K(a, b)));
          }
      }
    // K_ab = B_a : A : B_b + P : dB_a/du_b is symmetric whenever A is.
    if (material.symmetric_tangent())
      {
        double asymmetry = 0;
        for (unsigned int a = 0; a < 8; ++a)
          for (unsigned int b = 0; b < a; ++b)
            asymmetry = std::max(asymmetry, std::abs(K(a, b) - K(b, a)));
        EXPECT_LT(asymmetry, 1e-12 * scale);
      }
    return error / scale;
  }

  // A compressive displacement with a random part; u_r = 0 on the axis as the problem imposes.
  Vector<double> loading_displacement(const Vertices &v, double scale, unsigned int seed)
  {
    std::mt19937                           rng(seed);
    std::uniform_real_distribution<double> dist(-0.3, 0.3);
    Vector<double>                         u = homogeneous_displacement(v, 0.01, -0.04, 0.);
    for (auto &value : u)
      value = scale * (value + 0.05 * dist(rng));
    for (unsigned int i = 0; i < 4; ++i)
      if (v[i][0] == 0)
        u[2 * i] = 0;
    return u;
  }
} // namespace

// The element tangent is the exact derivative of the element residual for neo-Hookean
// material, with and without F-bar (both dilatations), away from the axis and touching it, and
// symmetric (the material tangent is).
TEST(AxisymmetricElement, TangentMatchesFiniteDifferencesNeoHookean)
{
  const auto material = materials::create_material(paper_material("neo_hookean"));
  for (const Vertices &v : {away_from_axis, touching_axis})
    for (const auto dilatation :
         {fem::FBarDilatation::element_mean, fem::FBarDilatation::element_centre})
      for (const bool f_bar : {false, true})
        {
          fem::AxisymmetricScratch               s = scratch_on(v, dilatation);
          std::mt19937                           rng(3);
          std::uniform_real_distribution<double> dist(-0.15, 0.15);
          Vector<double>                         u(8);
          for (auto &value : u)
            value = dist(rng);
          for (unsigned int i = 0; i < 4; ++i)
            if (v[i][0] == 0)
              u[2 * i] = 0;
          const double error = tangent_error(*material, f_bar, s, u, virgin_states(*material, 4));
          EXPECT_LT(error, 1e-6) << "axis " << (v[0][0] == 0) << " f_bar " << f_bar << " centre "
                                 << (dilatation == fem::FBarDilatation::element_centre);
          std::cout << "[ measured ] neo-Hookean axis " << (v[0][0] == 0) << " f_bar " << f_bar
                    << " centre " << (dilatation == fem::FBarDilatation::element_centre)
                    << " relative tangent error " << error << "\n";
        }
}

// The same for J2 in plastic flow: every Gauss point is first driven plastic by one increment,
// and the tangent is checked (and its symmetry) in a further plastic increment from that state.
TEST(AxisymmetricElement, TangentMatchesFiniteDifferencesJ2Plastic)
{
  const auto         material = materials::create_material(paper_material("j2"));
  const unsigned int n_state = material->n_state_variables();
  for (const Vertices &v : {away_from_axis, touching_axis})
    for (const auto dilatation :
         {fem::FBarDilatation::element_mean, fem::FBarDilatation::element_centre})
      for (const bool f_bar : {false, true})
        {
          fem::AxisymmetricScratch s = scratch_on(v, dilatation);
          std::vector<double>      state_old = virgin_states(*material, 4), state_new(state_old);
          Vector<double>           r(8);
          const Vector<double>     u1 = loading_displacement(v, 1.0, 5);
          ASSERT_EQ(fem::axisymmetric_element_residual_and_tangent(*material, f_bar, u1, state_old,
                                                                   state_new, s, r, nullptr),
                    materials::UpdateStatus::success);
          std::vector<double>  plastic_start = state_new;
          const Vector<double> u2 = loading_displacement(v, 1.5, 6);
          state_new = plastic_start;
          ASSERT_EQ(fem::axisymmetric_element_residual_and_tangent(
                        *material, f_bar, u2, plastic_start, state_new, s, r, nullptr),
                    materials::UpdateStatus::success);
          for (unsigned int q = 0; q < 4; ++q)
            {
              const double ep_1 = material->equivalent_plastic_strain(
                               std::span<const double>(plastic_start)
                                   .subspan(q * n_state, n_state)),
                           ep_2 = material->equivalent_plastic_strain(
                               std::span<const double>(state_new).subspan(q * n_state, n_state));
              ASSERT_GT(ep_1, 0) << "q " << q << ": not plastic after the first increment";
              ASSERT_GT(ep_2, ep_1) << "q " << q << ": no plastic flow in the checked increment";
            }
          const double error = tangent_error(*material, f_bar, s, u2, plastic_start);
          EXPECT_LT(error, 1e-6) << "axis " << (v[0][0] == 0) << " f_bar " << f_bar << " centre "
                                 << (dilatation == fem::FBarDilatation::element_centre);
          std::cout << "[ measured ] J2 axis " << (v[0][0] == 0) << " f_bar " << f_bar << " centre "
                    << (dilatation == fem::FBarDilatation::element_centre)
                    << " relative tangent error " << error << "\n";
        }
}

namespace
{
  // Largest difference between the element residual of the homogeneous state u_r = a R,
  // u_z = b Z and the boundary nodal forces of its uniform stress, relative to the largest
  // force; checks on the way that F = diag(1 + a, 1 + a, 1 + b) at every Gauss point and the
  // centre.
  double homogeneous_residual_error(const materials::MaterialModel &material, bool f_bar,
                                    const Vertices &v, fem::FBarDilatation dilatation,
                                    Vector<double> *difference = nullptr)
  {
    const double             a = 0.02, b = -0.03;
    fem::AxisymmetricScratch s = scratch_on(v, dilatation);
    const Vector<double>     u = homogeneous_displacement(v, a, b, 0.);
    Tensor<2, 3>             F_expected;
    F_expected[0][0] = F_expected[1][1] = 1 + a;
    F_expected[2][2] = 1 + b;
    for (unsigned int q = 0; q <= 4; ++q)
      EXPECT_LT((fem::axisymmetric_deformation_gradient(s, q, u) - F_expected).norm(), 1e-15)
          << "q " << q;

    std::vector<double> state_old = virgin_states(material, 4), state_new(state_old),
                        point_state(state_old.begin(),
                                    state_old.begin() + material.n_state_variables());
    materials::MaterialPointResponse response;
    material.update(F_expected, std::span<const double>(point_state), response,
                    std::span<double>(point_state), false);
    Vector<double> r(8);
    EXPECT_EQ(fem::axisymmetric_element_residual_and_tangent(material, f_bar, u, state_old,
                                                             state_new, s, r, nullptr),
              materials::UpdateStatus::success);
    const Vector<double> f = boundary_nodal_forces(v, response.P);
    Vector<double>       d(r);
    d -= f;
    if (difference)
      *difference = d;
    return max_abs(d) / max_abs(f);
  }
} // namespace

// A homogeneous state u_r = a R, u_z = b Z has F = diag(1 + a, 1 + a, 1 + b) exactly at every
// point, and the element residual equals the nodal forces of its uniform stress on the element
// boundary (so interior nodes are in exact equilibrium), elastic and plastic, without F-bar and
// with the mean-dilatation F-bar, on a rectangle, a distorted cell and a cell on the axis.
TEST(AxisymmetricElement, HomogeneousStateGivesTheBoundaryForcesOfItsStress)
{
  for (const std::string model : {"neo_hookean", "j2"})
    {
      const auto material = materials::create_material(paper_material(model));
      for (const Vertices &v : {rectangle(0.5, 2.5, 1, 2), away_from_axis, touching_axis})
        for (const bool f_bar : {false, true})
          {
            const double error =
                homogeneous_residual_error(*material, f_bar, v, fem::FBarDilatation::element_mean);
            EXPECT_LT(error, 1e-13) << model << " f_bar " << f_bar;
            std::cout << "[ measured ] " << model << " f_bar " << f_bar << " R0 " << v[0][0]
                      << " relative residual error " << error << "\n";
          }
    }
}

// The reason the F-bar element takes the mean dilatation: with J_0 = det F at the centre, the
// homogeneous state of a rectangle of radial half-width h leaves the spurious force
// (p/3) sum_q c_a dV_q = (p/3) 2 pi h^2 / (3 (1 + b)) (-1, +1, +1, -1) on the u_z dofs of
// vertices 0..3 (p = P : F), derived by hand from the exact integrals of dN_i/dZ 2 pi R; the
// u_r dofs stay exact.
TEST(AxisymmetricElement, CentreDilatationLeavesTheClosedFormSpuriousForce)
{
  const auto     material = materials::create_material(paper_material("neo_hookean"));
  const double   R1 = 0.5, R2 = 2.5, h = (R2 - R1) / 2, a = 0.02, b = -0.03;
  Vector<double> d(8);
  homogeneous_residual_error(*material, true, rectangle(R1, R2, 1, 2),
                             fem::FBarDilatation::element_centre, &d);
  Tensor<2, 3> F;
  F[0][0] = F[1][1] = 1 + a;
  F[2][2] = 1 + b;
  std::vector<double>              state = virgin_states(*material, 1);
  materials::MaterialPointResponse response;
  material->update(F, std::span<const double>(state), response, std::span<double>(state), false);
  const double                p = scalar_product(response.P, F);
  const double                magnitude = p / 3 * 2 * numbers::PI * h * h / (3 * (1 + b));
  const std::array<double, 4> sign = {{-1, 1, 1, -1}};
  for (unsigned int i = 0; i < 4; ++i)
    {
      EXPECT_NEAR(d[2 * i], 0, 1e-13 * std::abs(magnitude));
      EXPECT_NEAR(d[2 * i + 1], sign[i] * magnitude, 1e-12 * std::abs(magnitude));
    }
  EXPECT_GT(std::abs(magnitude), 1e-3); // mN: the spurious force is not round-off
  std::cout << "[ measured ] centre dilatation: spurious u_z force " << magnitude
            << " mN, relative to the largest nodal force "
            << homogeneous_residual_error(*material, true, rectangle(R1, R2, 1, 2),
                                          fem::FBarDilatation::element_centre)
            << "\n";
}

// Interior equilibrium on a graded patch of 3 x 2 cells from the axis outwards (radial widths
// about 0.5, 1, 2 um; heights 1, 2 um; the interior row of nodes shifted radially, so that the
// cells are trapezoids): under u_r = a R, u_z = b Z the assembled residual vanishes at every
// interior dof (the axis node's u_z included), without F-bar and with the mean-dilatation
// F-bar, and not with the centre dilatation.
TEST(AxisymmetricElement, GradedPatchIsInInteriorEquilibrium)
{
  const auto material = materials::create_material(paper_material("j2"));
  // R of the nodes [row j][column i], Z of the rows.
  const std::array<std::array<double, 4>, 3> R = {
      {{{0, 0.5, 1.5, 3.5}}, {{0, 0.6, 1.3, 3.5}}, {{0, 0.5, 1.5, 3.5}}}};
  const std::array<double, 3> Z = {{0, 1, 3}};
  for (const auto dilatation :
       {fem::FBarDilatation::element_mean, fem::FBarDilatation::element_centre})
    for (const bool f_bar : {false, true})
      {
        std::vector<double> global(2 * 4 * 3, 0.);
        const auto          node = [](unsigned int i, unsigned int j) { return j * 4 + i; };
        double              scale = 0;
        for (unsigned int j = 0; j < 2; ++j)
          for (unsigned int i = 0; i < 3; ++i)
            {
              const Vertices           v = {{Point<2>(R[j][i], Z[j]), Point<2>(R[j][i + 1], Z[j]),
                                             Point<2>(R[j + 1][i], Z[j + 1]),
                                             Point<2>(R[j + 1][i + 1], Z[j + 1])}};
              fem::AxisymmetricScratch s = scratch_on(v, dilatation);
              std::vector<double> state_old = virgin_states(*material, 4), state_new(state_old);
              Vector<double>      r(8);
              ASSERT_EQ(fem::axisymmetric_element_residual_and_tangent(
                            *material, f_bar, homogeneous_displacement(v, 0.02, -0.03, 0.1),
                            state_old, state_new, s, r, nullptr),
                        materials::UpdateStatus::success);
              const std::array<unsigned int, 4> nodes = {
                  {node(i, j), node(i + 1, j), node(i, j + 1), node(i + 1, j + 1)}};
              for (unsigned int k = 0; k < 4; ++k)
                for (unsigned int c = 0; c < 2; ++c)
                  global[2 * nodes[k] + c] += r[2 * k + c];
              scale = std::max(scale, max_abs(r));
            }
        double interior = 0;
        for (unsigned int i = 0; i < 3; ++i) // R = 3.5 is the outer face
          {
            const unsigned int n = node(i, 1); // Z = 1 is the only interior row
            if (i > 0)
              interior = std::max(interior, std::abs(global[2 * n]));
            interior = std::max(interior, std::abs(global[2 * n + 1]));
          }
        const bool centre = dilatation == fem::FBarDilatation::element_centre;
        if (centre && f_bar)
          EXPECT_GT(interior / scale, 1e-4); // the centre dilatation fails on graded meshes
        else
          EXPECT_LT(interior / scale, 1e-12);
        std::cout << "[ measured ] graded patch f_bar " << f_bar << " centre " << centre
                  << " interior residual / largest nodal force " << interior / scale << "\n";
      }
}

// A rigid translation u_z = c leaves the element stress-free: zero residual with and without
// F-bar, on and off the axis.
TEST(AxisymmetricElement, RigidTranslationAlongTheAxisIsStressFree)
{
  for (const std::string model : {"neo_hookean", "j2"})
    {
      const auto material = materials::create_material(paper_material(model));
      for (const Vertices &v : {away_from_axis, touching_axis})
        for (const bool f_bar : {false, true})
          {
            fem::AxisymmetricScratch s = scratch_on(v);
            std::vector<double>      state_old = virgin_states(*material, 4), state_new(state_old);
            Vector<double>           r(8);
            ASSERT_EQ(fem::axisymmetric_element_residual_and_tangent(
                          *material, f_bar, homogeneous_displacement(v, 0, 0, 0.37), state_old,
                          state_new, s, r, nullptr),
                      materials::UpdateStatus::success);
            // Round-off: 1e-16 in F times E = 69 GPa and 2 pi R L ~ 25 um^2 is ~ 2e-13 mN; a
            // strain of 1 % gives nodal forces of several mN.
            EXPECT_LT(max_abs(r), 1e-12) << model << " f_bar " << f_bar;
          }
    }
}

// The Cauchy stress output of a homogeneous plastic state is the material's sigma(F) = tau/J
// for F = diag(1 + a, 1 + a, 1 + b) in (r, theta, z) components, and equals the 3D hexahedron
// kernel's Cauchy stress for the same homogeneous F (J2, F-bar on).
TEST(AxisymmetricElement, CauchyStressOfAHomogeneousStateMatchesMaterialAndHexahedron)
{
  const auto   material = materials::create_material(paper_material("j2"));
  const double a = 0.02, b = -0.03;
  Tensor<2, 3> F;
  F[0][0] = F[1][1] = 1 + a;
  F[2][2] = 1 + b;
  std::vector<double>              state = virgin_states(*material, 1);
  materials::MaterialPointResponse response;
  material->update(F, std::span<const double>(state), response, std::span<double>(state), false);
  const Tensor<2, 3> sigma = response.tau / determinant(F);
  ASSERT_GT(material->equivalent_plastic_strain(state), 0);

  // The 3D kernel on the unit cube with u = (F - 1) X.
  Triangulation<3> cube;
  GridGenerator::hyper_cube(cube);
  const FESystem<3> fe3(FE_Q<3>(1), 3);
  FEValues<3>       fe_values(fe3, QGauss<3>(2), update_gradients | update_JxW_values);
  FEValues<3>       fe_centre(fe3, QGauss<3>(1), update_gradients);
  fe_values.reinit(cube.begin_active());
  fe_centre.reinit(cube.begin_active());
  fem::ElementScratch s3(8, 8);
  for (unsigned int q = 0; q < 8; ++q)
    {
      s3.JxW[q] = fe_values.JxW(q);
      for (unsigned int i = 0; i < 8; ++i)
        s3.grad[q][i] = fe_values.shape_grad_component(3 * i, q, 0);
    }
  for (unsigned int i = 0; i < 8; ++i)
    s3.grad0[i] = fe_centre.shape_grad_component(3 * i, 0, 0);
  Vector<double> u3(24), r3(24);
  for (unsigned int i = 0; i < 8; ++i)
    for (unsigned int c = 0; c < 3; ++c)
      u3[3 * i + c] = (F[c][c] - 1) * cube.begin_active()->vertex(i)[c];
  std::vector<double>       states3 = virgin_states(*material, 8), states3_new(states3);
  std::vector<Tensor<2, 3>> sigma3(8);
  ASSERT_EQ(fem::element_residual_and_tangent(*material, true, u3, states3, states3_new, s3, r3,
                                              nullptr, &sigma3),
            materials::UpdateStatus::success);

  for (const Vertices &v : {away_from_axis, touching_axis})
    {
      fem::AxisymmetricScratch  s = scratch_on(v);
      std::vector<double>       state_old = virgin_states(*material, 4), state_new(state_old);
      std::vector<Tensor<2, 3>> cauchy(4);
      Vector<double>            r(8);
      ASSERT_EQ(fem::axisymmetric_element_residual_and_tangent(
                    *material, true, homogeneous_displacement(v, a, b, 0.), state_old, state_new, s,
                    r, nullptr, &cauchy),
                materials::UpdateStatus::success);
      for (unsigned int q = 0; q < 4; ++q)
        {
          EXPECT_LT((cauchy[q] - sigma).norm(), 1e-12 * sigma.norm()) << "q " << q;
          EXPECT_LT((cauchy[q] - sigma3[q]).norm(), 1e-12 * sigma.norm()) << "q " << q;
        }
    }
}

// A negative hoop stretch (u_r < -R) is reported as invalid_deformation even where J > 0
// because the (r, z) section is folded as well.
TEST(AxisymmetricElement, NegativeHoopStretchIsAnInvalidDeformation)
{
  const auto               material = materials::create_material(paper_material("neo_hookean"));
  const Vertices           v = rectangle(1, 2, 0, 1);
  fem::AxisymmetricScratch s = scratch_on(v);
  // u_r = -3 R, u_z = Z: F = diag(-2, -2, 2), J = 8 > 0 with F_tt = -2.
  const Vector<double> u = homogeneous_displacement(v, -3, 1, 0);
  ASSERT_GT(determinant(fem::axisymmetric_deformation_gradient(s, 0, u)), 0);
  for (const bool f_bar : {false, true})
    {
      std::vector<double> state_old = virgin_states(*material, 4), state_new(state_old);
      Vector<double>      r(8);
      EXPECT_EQ(fem::axisymmetric_element_residual_and_tangent(*material, f_bar, u, state_old,
                                                               state_new, s, r, nullptr),
                materials::UpdateStatus::invalid_deformation);
    }
}
