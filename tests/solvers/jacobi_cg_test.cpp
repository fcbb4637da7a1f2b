// SPDX-License-Identifier: GPL-3.0-or-later
#include "solvers/jacobi_cg.hpp"

#include <gtest/gtest.h>

#include "common/errors.hpp"
#include "mesh/gmsh_reader.hpp"
#include "model/fem_model.hpp"
#include "solvers/cholesky.hpp"

namespace roifem::solvers {
namespace {

/// The trapezoidal rule's K + 2/dt C + 4/dt^2 M of the shipped brain (paper material, nearly
/// incompressible, base fixed, dt = 0.05 s): the matrix trapezoid-cg solves.
SparseMatrix brain_K_eff() {
  static const mesh::TetMesh mesh = mesh::read_mesh(std::string(ROIFEM_MESH_DIR) + "/brain-800.msh");
  const auto sys = model::build_fem_model(mesh, fem::material_preset("paper"), {"base"}, {}).system;
  const double dt = 0.05;
  return sys.K + (2.0 / dt) * sys.C + (4.0 / (dt * dt)) * sys.M;
}

Vector smooth_load(Index n) {
  Vector b(n);
  for (Index i = 0; i < n; ++i) b[i] = std::sin(0.01 * static_cast<double>(i)) + 0.3 * std::cos(0.7 * static_cast<double>(i));
  return b;
}

TEST(JacobiCg, MatchesTheCholeskySolveFromZeroAndFromAGuess) {
  const SparseMatrix A = brain_K_eff();
  const Vector b = smooth_load(A.rows());
  Cholesky direct;
  direct.compute(A);
  const Vector exact = direct.solve(b);
  JacobiCg cg;
  cg.compute(A);
  Vector x = Vector::Zero(A.rows());
  const long from_zero = cg.solve(b, x);
  const double residual = (b - A * x).norm() / b.norm();
  const double error = (x - exact).norm() / exact.norm();
  std::printf("from zero: %ld iterations, residual %.2e, error against CHOLMOD %.2e\n", from_zero, residual, error);
  EXPECT_LE(residual, 1e-10);
  EXPECT_LT(error, 1e-8);
  // A guess near the answer takes fewer iterations to the same residual.
  Vector guess = exact + 1e-3 * exact.norm() / std::sqrt(static_cast<double>(A.rows())) * smooth_load(A.rows()).reverse();
  const long from_guess = cg.solve(b, guess);
  EXPECT_LT(from_guess, from_zero);
  EXPECT_LT((guess - exact).norm() / exact.norm(), 1e-8);
  // A zero load gives zero, whatever the guess.
  Vector y = Vector::Ones(A.rows());
  EXPECT_EQ(cg.solve(Vector::Zero(A.rows()), y), 0);
  EXPECT_EQ(y.norm(), 0.0);
}

TEST(JacobiCg, StopsWithAMessageWhenIterationsRunOut) {
  JacobiCg cg(CgSettings{.tolerance = 1e-10, .max_iterations = 3});
  cg.compute(brain_K_eff());
  Vector x = Vector::Zero(cg.size());
  try {
    cg.solve(smooth_load(cg.size()), x);
    FAIL() << "expected SolverError";
  } catch (const SolverError& e) {
    EXPECT_NE(std::string(e.what()).find("did not converge in 3 iterations (relative residual"), std::string::npos) << e.what();
  }
}

TEST(JacobiCg, RefusesANonPositiveDiagonalAndBadSettings) {
  SparseMatrix A(3, 3);
  A.insert(0, 0) = 2;
  A.insert(1, 1) = -1;
  A.insert(2, 2) = 1;
  JacobiCg cg;
  try {
    cg.compute(A);
    FAIL() << "expected SolverError";
  } catch (const SolverError& e) {
    EXPECT_NE(std::string(e.what()).find("diagonal entry 1 is -1"), std::string::npos) << e.what();
  }
  EXPECT_THROW(JacobiCg(CgSettings{.tolerance = 0}), InputError);
  EXPECT_THROW(JacobiCg(CgSettings{.tolerance = 1e-8, .max_iterations = 0}), InputError);
}

}  // namespace
}  // namespace roifem::solvers
