// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// The highest angular eigenfrequency of M u'' + K u = 0, w_max = sqrt(lambda_max(M^-1 K)): what
/// limits an explicit integrator's step (dt <= c / w_max for a method-dependent c). Lanczos
/// (Spectra's implicitly restarted SymEigsSolver) on the symmetric M^-1/2 K M^-1/2, so that it
/// costs a few dozen products with K at any size, where a dense eigensolver stops at a few
/// thousand dofs.
#include <functional>

#include "model/second_order_system.hpp"
#include "solvers/cholesky.hpp"

namespace roifem::model {

/// Eigenpairs K phi = w^2 M phi, ascending in w; the modes are M-orthonormal (phi^T M phi = I).
struct Modes {
  Vector omega;        ///< rad/s
  DenseMatrix shapes;  ///< n x count
};

/// The `count` lowest modes of (K, M) for a diagonal positive M (given by its diagonal), by
/// Lanczos in shift-invert form: the largest eigenvalues of M^1/2 K^-1 M^1/2, with K's Cholesky
/// factor (already computed, as static condensation has it) doing the inverse; dense from half the
/// spectrum up. Throws SolverError when Lanczos does not converge, InputError for a count outside [1, n].
/// `solve_K(b, x)` sets x = K^-1 b.
using SolveK = std::function<void(const Vector& b, Vector& x)>;
Modes lowest_modes(const Vector& mass_diagonal, const SolveK& solve_K, Index count, double tolerance = 1e-10);
Modes lowest_modes(const Vector& mass_diagonal, solvers::Cholesky& K_factor, Index count, double tolerance = 1e-10);
/// The modes below `cutoff` rad/s (at most n): lowest_modes with a growing count.
Modes modes_below(const Vector& mass_diagonal, const SolveK& solve_K, double cutoff, double tolerance = 1e-10);

/// A full M (Guyan, Craig-Bampton) takes the generalized form, with M^-1 by Cholesky. Throws
/// SolverError when Lanczos does not converge.
double highest_frequency(const SecondOrderSystem& system, double tolerance = 1e-10);
/// The same with the stiffness K in place of the system's (a nonlinear system's tangent K_t(u)).
double highest_frequency(const SecondOrderSystem& system, const SparseMatrix& K, double tolerance = 1e-10);

}  // namespace roifem::model
