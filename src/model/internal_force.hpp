// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// A nonlinear internal force in place of K u (model/second_order_system.hpp):
///   M u'' + C u' + f_int(u) = f(t),
/// with its tangent K_t(u) = df_int/du (symmetric, in the pattern of the system's K) and its
/// strain energy W(u) (f_int = dW/du). A linear system has none and is integrated exactly as it
/// always was; the system's K is then the tangent at u = 0, for patterns and linear estimates.
/// The shape of MFEM's HyperelasticOperator (examples/ex10.cpp): Mult is the force, GetGradient
/// the tangent, and every method that takes it takes it unchanged.
#include <string>

#include "common/types.hpp"

namespace roifem::model {

class InternalForce {
 public:
  virtual ~InternalForce() = default;
  /// f_int(u) over the system's dofs (f sized by the caller). Throws ModelError when the state is
  /// not admissible (an element inverted), naming where.
  virtual void force(const Vector& u, Vector& f) const = 0;
  /// f_int(u) and K_t(u) (K_t's values overwritten in the system's K pattern).
  virtual void force_and_tangent(const Vector& u, Vector& f, SparseMatrix& K_t) const = 0;
  /// Gonzalez's discrete gradient between two states (fem/discrete_gradient.hpp): a force f_alg
  /// with f_alg . (u_b - u_a) = W(u_b) - W(u_a) exactly, f_alg(u, u) = f_int(u), and second-order
  /// close to f_int((u_a + u_b)/2). What integrators/energy_momentum.hpp conserves energy by.
  virtual void discrete_gradient(const Vector& u_a, const Vector& u_b, Vector& f_alg) const = 0;
  /// f_alg and its derivative in the second state, K_alg = df_alg/du_b (not symmetric; at u_a = u_b
  /// it is K_t / 2), in the system's K pattern.
  virtual void discrete_gradient_and_tangent(const Vector& u_a, const Vector& u_b, Vector& f_alg, SparseMatrix& K_alg) const = 0;
  /// W(u), J.
  virtual double energy(const Vector& u) const = 0;
  /// One line for reports: the law and where it holds ("neo-hookean, every element").
  virtual std::string describe() const = 0;
};

}  // namespace roifem::model
