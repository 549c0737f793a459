// Helpers shared by the material-point unit tests: random rotations and deformations, and the
// finite-difference check of a model's tangent dP/dF. Units: GPa.
#pragma once

#include "materials/MaterialModel.h"

#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace indentsim::testing
{
  using dealii::Tensor;
  using materials::MaterialModel;
  using materials::MaterialPointResponse;
  using materials::UpdateStatus;

  inline void report(const std::string &what, const double value)
  {
    std::cout << "[ measured ] " << what << " = " << value << std::endl;
  }

  inline Tensor<2, 3> identity()
  {
    return dealii::unit_symmetric_tensor<3>();
  }

  // A rotation from a random unit quaternion (orthogonal to round-off, unlike Gram-Schmidt).
  inline Tensor<2, 3> random_rotation(std::mt19937 &generator)
  {
    std::normal_distribution<double> normal(0.0, 1.0);
    double                           q[4], norm = 0.0;
    for (double &component : q)
      {
        component = normal(generator);
        norm += component * component;
      }
    norm = std::sqrt(norm);
    const double a = q[0] / norm, b = q[1] / norm, c = q[2] / norm, d = q[3] / norm;
    Tensor<2, 3> Q;
    Q[0][0] = a * a + b * b - c * c - d * d;
    Q[0][1] = 2 * (b * c - a * d);
    Q[0][2] = 2 * (b * d + a * c);
    Q[1][0] = 2 * (b * c + a * d);
    Q[1][1] = a * a - b * b + c * c - d * d;
    Q[1][2] = 2 * (c * d - a * b);
    Q[2][0] = 2 * (b * d - a * c);
    Q[2][1] = 2 * (c * d + a * b);
    Q[2][2] = a * a - b * b - c * c + d * d;
    return Q;
  }

  // F = I + amplitude * (uniform random in [-1, 1]), redrawn until det F > 0.2.
  inline Tensor<2, 3> random_deformation(std::mt19937 &generator, const double amplitude)
  {
    std::uniform_real_distribution<double> uniform(-1.0, 1.0);
    while (true)
      {
        Tensor<2, 3> F = identity();
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = 0; j < 3; ++j)
            F[i][j] += amplitude * uniform(generator);
        if (dealii::determinant(F) > 0.2)
          return F;
      }
  }

  // A plastic state of a crystal (or any oriented model) turned by `rotation`: 4/5 of the way to
  // F_target, in four increments from the virgin state.
  inline std::vector<double> plastic_state(const MaterialModel &model, const Tensor<2, 3> &rotation,
                                           const Tensor<2, 3> &F_target)
  {
    std::vector<double> state(model.n_state_variables());
    model.oriented_initial_state(state, rotation);
    MaterialPointResponse response;
    for (unsigned int step = 1; step <= 4; ++step)
      {
        const Tensor<2, 3>  F = identity() + (F_target - identity()) * (step / 5.0);
        std::vector<double> state_new(state.size());
        EXPECT_EQ(model.update(F, state, response, state_new, false), UpdateStatus::success);
        state = state_new;
      }
    return state;
  }

  inline Tensor<2, 3> diagonal(const double a, const double b, const double c)
  {
    Tensor<2, 3> F;
    F[0][0] = a;
    F[1][1] = b;
    F[2][2] = c;
    return F;
  }

  // The virgin state of `model` in the orientation g.
  inline std::vector<double> oriented_state(const MaterialModel &model, const Tensor<2, 3> &g)
  {
    std::vector<double> state(model.n_state_variables());
    model.oriented_initial_state(state, g);
    return state;
  }

  // `state` after loading from the identity towards F_target in `steps` equal increments of
  // F_target / (steps + 1) (so F_target itself is one increment further); fails the test if an
  // update fails.
  inline void load_towards(const MaterialModel &model, const Tensor<2, 3> &F_target,
                           const unsigned int steps, std::vector<double> &state)
  {
    MaterialPointResponse response;
    for (unsigned int step = 1; step <= steps; ++step)
      {
        std::vector<double> state_new(state.size());
        const Tensor<2, 3>  F = identity() + (F_target - identity()) * (step / (steps + 1.0));
        EXPECT_EQ(model.update(F, state, response, state_new, false), UpdateStatus::success);
        state = state_new;
      }
  }

  // Central finite differences of P(F) with the old state held fixed (each perturbed update
  // re-runs the whole return mapping from state_old), compared with the model's dP/dF:
  // returns |dP/dF_FD - dP/dF| / |dP/dF| (Frobenius norms).
  inline double tangent_error(const MaterialModel &model, const Tensor<2, 3> &F,
                              const std::vector<double> &state_old, const double step = 1e-6)
  {
    MaterialPointResponse response;
    std::vector<double>   state_new(state_old.size());
    EXPECT_EQ(model.update(F, state_old, response, state_new, true), UpdateStatus::success);

    Tensor<4, 3> finite_difference;
    for (unsigned int k = 0; k < 3; ++k)
      for (unsigned int L = 0; L < 3; ++L)
        {
          Tensor<2, 3> F_plus = F, F_minus = F;
          F_plus[k][L] += step;
          F_minus[k][L] -= step;
          MaterialPointResponse plus, minus;
          std::vector<double>   scratch(state_old.size());
          EXPECT_EQ(model.update(F_plus, state_old, plus, scratch, false), UpdateStatus::success);
          EXPECT_EQ(model.update(F_minus, state_old, minus, scratch, false), UpdateStatus::success);
          for (unsigned int i = 0; i < 3; ++i)
            for (unsigned int J = 0; J < 3; ++J)
              finite_difference[i][J][k][L] = (plus.P[i][J] - minus.P[i][J]) / (2.0 * step);
        }
    return (finite_difference - response.dP_dF).norm() / response.dP_dF.norm();
  }

  // One row of tests/unit/data/j2_uniaxial_reference*.csv, written by the independent
  // python/reference_j2_uniaxial.py: uniaxial J2 tension (Table 1) at a logarithmic strain.
  struct J2UniaxialReferenceRow
  {
    double log_strain, cauchy_stress, lateral_stretch, alpha;
  };

  inline std::vector<J2UniaxialReferenceRow>
  read_j2_uniaxial_reference(const std::string &file_name)
  {
    const std::string path = std::string(INDENTSIM_TEST_DATA_DIR) + "/unit/data/" + file_name;
    std::ifstream     file(path);
    EXPECT_TRUE(file) << "cannot open " << path;
    std::vector<J2UniaxialReferenceRow> rows;
    std::string                         line;
    while (std::getline(file, line))
      {
        if (line.empty() || line[0] == '#' || line.rfind("log_strain", 0) == 0)
          continue;
        std::istringstream     stream(line);
        J2UniaxialReferenceRow row;
        char                   comma;
        stream >> row.log_strain >> comma >> row.cauchy_stress >> comma >> row.lateral_stretch >>
            comma >> row.alpha;
        EXPECT_FALSE(stream.fail()) << "bad line in " << path << ": " << line;
        rows.push_back(row);
      }
    return rows;
  }

  // The root of g(x) = 0 by the secant method from x_0 and x_0 (1 + 1e-4), to |g| <= 1e-13 (the
  // uniaxial tests' vanishing lateral stress as a function of the lateral stretch); more than
  // 100 iterations fail the test.
  template <typename Function>
  double secant_root(const Function &g, const double x_start)
  {
    double       x_0 = x_start, x_1 = x_start * (1.0 + 1e-4);
    double       g_0 = g(x_0), g_1 = g(x_1);
    unsigned int iteration = 0;
    for (; iteration < 100 && std::abs(g_1) > 1e-13; ++iteration)
      {
        const double x_2 = x_1 - g_1 * (x_1 - x_0) / (g_1 - g_0);
        x_0 = x_1;
        g_0 = g_1;
        x_1 = x_2;
        g_1 = g(x_1);
      }
    EXPECT_LT(iteration, 100u) << "secant search did not converge";
    return x_1;
  }
} // namespace indentsim::testing
