// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// A nonlinear internal force in place of K u (model/second_order_system.hpp):
///   M u'' + C u' + f_int(t, u) = f(t),
/// with its tangent K_t(t, u) = df_int/du (symmetric, in the pattern of the system's K) and its
/// strain energy W(t, u) (f_int = dW/du). A linear system has none and is integrated exactly as it
/// always was; the system's K is then the tangent at u = 0, for patterns and linear estimates.
/// The shape of MFEM's HyperelasticOperator (examples/ex10.cpp): Mult is the force, GetGradient
/// the tangent, and every method that takes it takes it unchanged.
///
/// The force depends on t only where tools move nodes of its elements (has_motion()): the tools'
/// paths g(t) then strain them. The system's load keeps the linear elimination's -K_fp G(t)
/// (model/prescribed_motion.hpp), so that its linearization at rest, loads included, is the
/// linear model's; f_int holds the rest.
#include <memory>
#include <string>

#include "common/types.hpp"
#include "model/load_history.hpp"

namespace roifem::model {

class InternalForce {
 public:
  virtual ~InternalForce() = default;
  /// f_int(t, u) over the system's dofs (f sized by the caller). Throws ModelError when the state
  /// is not admissible (an element inverted), naming where.
  virtual void force(double t, const Vector& u, Vector& f) const = 0;
  /// f_int(t, u) and K_t(t, u) (K_t's values overwritten in the system's K pattern).
  virtual void force_and_tangent(double t, const Vector& u, Vector& f, SparseMatrix& K_t) const = 0;
  /// What the law adds to the linear model, f_int(u) - K u with K the system's K (the tangent at
  /// rest), formed element by element from the law's elements alone, with no product by K (a
  /// hybrid ROI's K~ has a dense interface block): what a haptic tick iterates on
  /// (integrators/haptic_trapezoid.hpp). A force without motion only; throws InputError else.
  virtual void excess_force(const Vector& u, Vector& g) const = 0;
  /// Gonzalez's discrete gradient between two states (fem/discrete_gradient.hpp): a force f_alg
  /// with f_alg . (u_b - u_a) = W(u_b) - W(u_a) exactly, f_alg(u, u) = f_int(u), and second-order
  /// close to f_int((u_a + u_b)/2). What integrators/energy_momentum.hpp conserves energy by.
  /// A force without motion only (the tools' work would need its own discrete gradient).
  virtual void discrete_gradient(const Vector& u_a, const Vector& u_b, Vector& f_alg) const = 0;
  /// f_alg and its derivative in the second state, K_alg = df_alg/du_b (not symmetric; at u_a = u_b
  /// it is K_t / 2), in the system's K pattern.
  virtual void discrete_gradient_and_tangent(const Vector& u_a, const Vector& u_b, Vector& f_alg, SparseMatrix& K_alg) const = 0;
  /// W(t, u), J: the potential of f_int. With tools, the tissue's strain energy less the linear
  /// coupling energy that model::ToolSet::coupling_energy adds back (model/energy.hpp).
  virtual double energy(double t, const Vector& u) const = 0;
  /// Whether discrete_gradient is formed (not by the nodal-pressure element at finite strain).
  virtual bool has_discrete_gradient() const { return true; }
  /// Whether tools move nodes of its elements, so that it depends on t.
  virtual bool has_motion() const { return false; }
  /// The tools' forces beyond the linear ones of their model::ToolSet (3 per tool, N): what the
  /// law's elements at the tools' nodes give beyond their linear stiffness. Empty without motion.
  virtual Vector tool_force_correction(double /*t*/, const Vector& /*u*/) const { return {}; }
  /// The same force with the tools' paths on `ramp` (as ToolSet::with_ramp); without motion, the same.
  virtual std::shared_ptr<const InternalForce> with_ramp(const Ramp& ramp) const = 0;
  /// One line for reports: the law and where it holds ("neo-hookean, every element").
  virtual std::string describe() const = 0;
};

}  // namespace roifem::model
