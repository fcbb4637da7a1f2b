// SPDX-License-Identifier: GPL-3.0-or-later
#include "solvers/jacobi_cg.hpp"

#include <cmath>
#include <string>

#include "common/errors.hpp"
#include "common/number_text.hpp"

namespace roifem::solvers {

JacobiCg::JacobiCg(CgSettings settings) : settings_(settings) {
  if (!(settings.tolerance > 0 && settings.tolerance < 1))
    throw InputError("conjugate gradients: tolerance " + number_text(settings.tolerance) + " must lie in (0, 1)");
  if (settings.max_iterations < 1) throw InputError("conjugate gradients: max_iterations must be positive");
}

void JacobiCg::compute(SparseMatrix A) {
  if (A.rows() != A.cols()) throw Error("internal: conjugate gradients on a non-square matrix");
  inverse_diagonal_ = A.diagonal();
  A_ = A.triangularView<Eigen::Lower>();  // half the memory, and products 1.2x faster (measured at 100k)
  A.resize(0, 0);
  A_.makeCompressed();
  for (Index i = 0; i < inverse_diagonal_.size(); ++i) {
    if (!(inverse_diagonal_[i] > 0) || !std::isfinite(inverse_diagonal_[i]))
      throw SolverError("conjugate gradients: the matrix is not positive definite (diagonal entry " + std::to_string(i) + " is " +
                        number_text(inverse_diagonal_[i]) + ")");
    inverse_diagonal_[i] = 1.0 / inverse_diagonal_[i];
  }
  const Index n = A_.rows();
  r_.resize(n);
  z_.resize(n);
  p_.resize(n);
  q_.resize(n);
}

long JacobiCg::solve(const Eigen::Ref<const Vector>& b, Eigen::Ref<Vector> x) {
  if (b.size() != A_.rows() || x.size() != A_.rows()) throw Error("internal: conjugate gradients: size mismatch");
  const double target = settings_.tolerance * b.norm();
  if (target == 0) {  // b = 0
    x.setZero();
    return 0;
  }
  long iterations = 0;
  // Restarted from the true residual whenever the recursive one claims convergence, so rounding in
  // the recursion can never stop the solve early.
  while (true) {
    r_ = b;
    r_.noalias() -= A_.selfadjointView<Eigen::Lower>() * x;
    if (r_.norm() <= target) return iterations;
    z_ = inverse_diagonal_.cwiseProduct(r_);
    p_ = z_;
    double rz = r_.dot(z_);
    while (r_.norm() > target) {
      if (iterations == settings_.max_iterations)
        throw SolverError("conjugate gradients did not converge in " + std::to_string(iterations) +
                          " iterations (relative residual " + number_text(r_.norm() / b.norm()) + ", tolerance " +
                          number_text(settings_.tolerance) + ")");
      q_.noalias() = A_.selfadjointView<Eigen::Lower>() * p_;
      const double pq = p_.dot(q_);
      if (!(pq > 0))
        throw SolverError("conjugate gradients: the matrix is not positive definite (p^T A p = " + number_text(pq) + ")");
      const double step = rz / pq;
      x += step * p_;
      r_ -= step * q_;
      z_ = inverse_diagonal_.cwiseProduct(r_);
      const double rz_next = r_.dot(z_);
      p_ = z_ + (rz_next / rz) * p_;
      rz = rz_next;
      ++iterations;
    }
  }
}

}  // namespace roifem::solvers
