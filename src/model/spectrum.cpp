// SPDX-License-Identifier: GPL-3.0-or-later
#include "model/spectrum.hpp"

#include <Spectra/SymEigsSolver.h>
#include <Spectra/SymGEigsSolver.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <functional>

#include "common/errors.hpp"
#include "model/mass_inverse.hpp"

namespace roifem::model {

namespace {

/// y = D A D x for a diagonal D and an operator A (y = A x by `apply`): the symmetric form Spectra
/// iterates with. D K D with D = M^-1/2 gives w^2; D K^-1 D with D = M^1/2 gives 1 / w^2.
class Scaled {
 public:
  using Scalar = double;
  using Apply = std::function<void(const Vector&, Vector&)>;
  Scaled(Apply apply, Vector scale) : apply_(std::move(apply)), scale_(std::move(scale)), x_(scale_.size()), y_(scale_.size()) {}
  Index rows() const { return scale_.size(); }
  Index cols() const { return scale_.size(); }
  void perform_op(const double* in, double* out) const {
    x_ = scale_.cwiseProduct(Eigen::Map<const Vector>(in, rows()));
    apply_(x_, y_);
    Eigen::Map<Vector>(out, rows()) = scale_.cwiseProduct(y_);
  }

 private:
  Apply apply_;
  Vector scale_;
  mutable Vector x_, y_;
};

/// y = K x, and the mass operator of Spectra's regular-inverse mode (y = M x, y = M^-1 x): the
/// generalized problem for a full M (Guyan, Craig-Bampton).
class Stiffness {
 public:
  using Scalar = double;
  explicit Stiffness(const SecondOrderSystem& system) : system_(system) {}
  Index rows() const { return system_.size(); }
  Index cols() const { return system_.size(); }
  void perform_op(const double* in, double* out) const {
    system_.apply_stiffness(Eigen::Map<const Vector>(in, rows()), Eigen::Map<Vector>(out, rows()));
  }

 private:
  const SecondOrderSystem& system_;
};

class Mass {
 public:
  using Scalar = double;
  explicit Mass(const SparseMatrix& M) : M_(M), inverse_(M) {}
  Index rows() const { return M_.rows(); }
  Index cols() const { return M_.cols(); }
  void perform_op(const double* in, double* out) const {
    Eigen::Map<Vector>(out, rows()).noalias() = M_ * Eigen::Map<const Vector>(in, rows());
  }
  void solve(const double* in, double* out) const {
    inverse_.apply(Eigen::Map<const Vector>(in, rows()), Eigen::Map<Vector>(out, rows()));
  }

 private:
  const SparseMatrix& M_;
  MassInverse inverse_;
};

}  // namespace

Modes lowest_modes(const Vector& mass_diagonal, const SolveK& solve_K, Index count, double tolerance) {
  const Index n = mass_diagonal.size();
  if (count < 1 || count > n)
    throw InputError("lowest modes: asked for " + std::to_string(count) + " modes of a system with " + std::to_string(n) +
                     " dofs (1 to " + std::to_string(n) + ")");
  if (mass_diagonal.minCoeff() <= 0) throw InputError("lowest modes: the mass matrix must be positive");
  const Vector scale = mass_diagonal.cwiseSqrt();
  Modes modes;
  if (2 * count >= n) {  // half the spectrum or more: dense
    DenseMatrix A(n, n);
    Vector e = Vector::Zero(n), column(n);
    for (Index j = 0; j < n; ++j) {  // M^1/2 K^-1 M^1/2, a column at a time
      e[j] = scale[j];
      solve_K(e, column);
      A.col(j) = scale.cwiseProduct(column);
      e[j] = 0;
    }
    const Eigen::SelfAdjointEigenSolver<DenseMatrix> dense(0.5 * (A + A.transpose()));
    // Ascending 1/w^2: the lowest w are the last columns.
    modes.omega = dense.eigenvalues().reverse().head(count).cwiseInverse().cwiseSqrt();
    modes.shapes = scale.cwiseInverse().asDiagonal() * dense.eigenvectors().rowwise().reverse().leftCols(count);
    return modes;
  }
  Scaled op(solve_K, scale);
  Spectra::SymEigsSolver<Scaled> lanczos(op, count, std::min<Index>(n, std::max<Index>(2 * count + 1, 20)));
  lanczos.init();
  lanczos.compute(Spectra::SortRule::LargestAlge, 1000, tolerance);
  if (lanczos.info() != Spectra::CompInfo::Successful)
    throw SolverError("lowest modes: Lanczos did not converge for " + std::to_string(count) + " modes");
  // Spectra returns the largest 1/w^2 first: the lowest w first.
  modes.omega = lanczos.eigenvalues().cwiseInverse().cwiseSqrt();
  modes.shapes = scale.cwiseInverse().asDiagonal() * lanczos.eigenvectors();  // phi = M^-1/2 psi
  return modes;
}

Modes modes_below(const Vector& mass_diagonal, const SolveK& solve_K, double cutoff, double tolerance) {
  const Index n = mass_diagonal.size();
  for (Index count = std::min<Index>(10, n);; count = std::min<Index>(2 * count, n)) {
    Modes modes = lowest_modes(mass_diagonal, solve_K, count, tolerance);
    const Index below = static_cast<Index>((modes.omega.array() < cutoff).count());
    if (below < count || count == n) {
      modes.omega.conservativeResize(below);
      modes.shapes.conservativeResize(Eigen::NoChange, below);
      return modes;
    }
  }
}

Modes lowest_modes(const Vector& mass_diagonal, solvers::Cholesky& K_factor, Index count, double tolerance) {
  if (mass_diagonal.size() != K_factor.size()) throw Error("internal: lowest_modes: M and K differ in size");
  return lowest_modes(
      mass_diagonal, [&](const Vector& b, Vector& x) { K_factor.solve(b, x); }, count, tolerance);
}

double highest_frequency(const SecondOrderSystem& system, const SparseMatrix& K, double tolerance) {
  SecondOrderSystem with_K;
  with_K.M = system.M;
  with_K.K = K;
  return highest_frequency(with_K, tolerance);
}

double highest_frequency(const SecondOrderSystem& system, double tolerance) {
  const Index n = system.size();
  const SparseMatrix& M = system.M;
  if (n == 0) throw InputError("highest frequency: the system has no dofs");
  if (!is_diagonal(M)) {  // full M: K phi = lambda M phi in Spectra's regular-inverse mode
    Stiffness op(system);
    Mass mass(M);
    Spectra::SymGEigsSolver<Stiffness, Mass, Spectra::GEigsMode::RegularInverse> lanczos(op, mass, 1, std::min<Index>(n, 20));
    lanczos.init();
    lanczos.compute(Spectra::SortRule::LargestAlge, 1000, tolerance);
    if (lanczos.info() != Spectra::CompInfo::Successful)
      throw SolverError("highest frequency: Lanczos (generalized) did not converge in 1000 restarts");
    return std::sqrt(std::max(0.0, lanczos.eigenvalues()[0]));
  }
  if (Vector(M.diagonal()).minCoeff() <= 0) throw InputError("highest frequency: the mass matrix must be positive");
  const Vector scale = Vector(M.diagonal()).cwiseSqrt().cwiseInverse();
  if (n <= 20) {  // too small for a Krylov space: dense
    const DenseMatrix A = scale.asDiagonal() * DenseMatrix(system.K) * scale.asDiagonal();
    return std::sqrt(
        std::max(0.0, Eigen::SelfAdjointEigenSolver<DenseMatrix>(A, Eigen::EigenvaluesOnly).eigenvalues().maxCoeff()));
  }
  Scaled op([&](const Vector& x, Vector& y) { system.apply_stiffness(x, y); }, scale);
  Spectra::SymEigsSolver<Scaled> lanczos(op, 1, std::min<Index>(n, 20));
  lanczos.init();
  lanczos.compute(Spectra::SortRule::LargestAlge, 1000, tolerance);
  if (lanczos.info() != Spectra::CompInfo::Successful)
    throw SolverError("highest frequency: Lanczos did not converge in 1000 restarts (" +
                      std::to_string(lanczos.num_operations()) + " products with K)");
  return std::sqrt(std::max(0.0, lanczos.eigenvalues()[0]));
}

}  // namespace roifem::model
