// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// The trapezoidal rule for a tool steered live (a surgeon's haptic device): each tick takes the
/// tool's new position and returns the force it applies to the tissue.
///
/// The tool holds m nodes of the system (all three components, bilateral); their dofs stay
/// unknowns, and the constraint H u_{n+1} = G(g_{n+1}) (every held dof at its tool component) is
/// imposed on the unconstrained step through the tool's compliance:
///   K_eff u* = f_{n+1} + M w_n                  (the plain step: trapezoid.hpp)
///   W = H K_eff^-1 H^T  (3m x 3m),   Z = K_eff^-1 H^T  (n x 3m),
///   lambda = W^-1 (H u* - G),        u_{n+1} = u* - Z lambda,
/// then a_{n+1} and v_{n+1} from u_{n+1} as usual. W's factor and Z come from the step's own factor
/// of K_eff, once per node set (attach), so that a tick costs the plain step plus a 3m x 3m solve
/// and an n x 3m product. The discrete solution is the one elimination gives
/// (model/prescribed_motion.hpp) with M and C lumped, and the returned force is the same
/// quantity: the residual K u - f summed over the held nodes (tools.hpp; their own inertia moves
/// with the tool).
#include <Eigen/Cholesky>
#include <array>
#include <vector>

#include "integrators/effective_stiffness.hpp"
#include "model/average_acceleration.hpp"

namespace roifem::integrators {

class HapticTrapezoid {
 public:
  /// Factors K_eff = K + 2/dt C + 4/dt^2 M. Throws SolverError when it is not positive definite.
  HapticTrapezoid(const model::SecondOrderSystem& system, double dt);
  HapticTrapezoid(const HapticTrapezoid&) = delete;
  HapticTrapezoid& operator=(const HapticTrapezoid&) = delete;

  /// The tool's nodes, as their (x, y, z) dofs in the system. Computes W's factor and Z (3m
  /// solves with the step's factor) and the tool's rows of K. Throws InputError for no node, a
  /// dof outside the system or held twice.
  void attach(const std::vector<std::array<Index, 3>>& node_dofs);
  /// Starts from `initial` (the held nodes where the tool is), acceleration consistent with it.
  void reset(const model::State& initial);
  /// One tick: the tool at g (m) at t_{n+1} = t_0 + (n + 1) dt; advances `state` and returns the
  /// tool's force on the tissue (N). Allocates nothing.
  Vec3 tick(const Vec3& g, model::State& state);

  /// W = H K_eff^-1 H^T (m/N), rows and columns the held dofs in attach's order.
  const DenseMatrix& compliance() const { return W_; }
  double dt() const { return rule_.dt(); }
  double attach_seconds() const { return attach_s_; }

 private:
  const model::SecondOrderSystem& system_;
  model::AverageAcceleration rule_;
  DirectSolve K_eff_;
  std::vector<Index> held_;  // 3m dofs, x, y, z of each node in turn
  DenseMatrix W_, Z_;
  Eigen::LLT<DenseMatrix> W_factor_;
  Eigen::SparseMatrix<double, Eigen::RowMajor> rows_;  // 3 x n: the held dofs' rows of K summed per component
  double attach_s_ = 0, t0_ = 0;
  long k_ = 0;
  Vector a_, f_, w_, u_next_, work_, gap_;
};

}  // namespace roifem::integrators
