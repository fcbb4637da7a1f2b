// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Conjugate gradients with a Jacobi (diagonal) preconditioner, for a symmetric positive definite
/// matrix whose Cholesky factor does not fit in memory (the full brain at 300k nodes: more than
/// 2^31 entries in L). It keeps A's lower triangle and five vectors, nothing else.
///
/// Why Jacobi: on the brain's K + 2/dt C + 4/dt^2 M (nearly incompressible, nu = 0.4985) it was the
/// fastest preconditioner measured at 20k nodes: its iterations are cheap enough to beat incomplete
/// Cholesky's and BoomerAMG's fewer ones, and 3x3 node blocks did not cut their number
/// (docs/design-figures.md). It is still far slower than one CHOLMOD solve; use it where memory,
/// not time, is the limit.
///
/// Stops when the true residual |b - A x| <= tolerance |b| (the recursive residual is checked
/// against the true one before stopping); throws SolverError when max_iterations pass first.
#include "common/types.hpp"

namespace roifem::solvers {

struct CgSettings {
  double tolerance = 1e-10;     ///< relative residual |b - A x| / |b|
  long max_iterations = 20000;  ///< a solve that needs more throws
};

class JacobiCg {
 public:
  explicit JacobiCg(CgSettings settings = {});
  /// Keeps A's lower triangle (A: full symmetric storage, both triangles; taken by value so that a
  /// caller can hand it over) and its inverse diagonal. Throws SolverError naming a non-positive
  /// diagonal entry.
  void compute(SparseMatrix A);
  /// Solves A x = b, starting from the guess in x; returns the iterations taken.
  long solve(const Eigen::Ref<const Vector>& b, Eigen::Ref<Vector> x);
  Index size() const { return A_.rows(); }
  const CgSettings& settings() const { return settings_; }

 private:
  CgSettings settings_;
  SparseMatrix A_;  // lower triangle
  Vector inverse_diagonal_, r_, z_, p_, q_;
};

}  // namespace roifem::solvers
