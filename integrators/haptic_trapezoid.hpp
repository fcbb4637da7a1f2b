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
///
/// On a nonlinear model (the hybrid ROI: model/hyperelastic_force.hpp) the step's equation is
///   R(u) = K_eff u + g(u) - (f + M w) = 0   under H u = G,
/// with g(u) = f_int(u) - K u what the law adds to the linear model, formed element by element on
/// the law's elements alone (InternalForce::excess_force: no product by the hybrid's dense K~). A
/// tick solves it by modified Newton from the previous state on the fixed tangent K_eff (the
/// linear model's, already factored), with a fixed, stated budget of N iterations:
///   u^1 = the constrained solve of K_eff u = f + M w - g(u_n)        (the linear tick's cost),
///   u^k+1 = u^k + d,  d the constrained solve of K_eff d = -(g(u^k) - g(u^k-1)),
/// each iteration one solve with the same factor and W, Z (so that H u = G holds throughout) and
/// one excess force; g(u_n) is the last tick's final evaluation. The residual on the free dofs
/// is exactly g(u^N) - g(u^N-1) (K_eff u^N = f + M w - g(u^N-1) there), so it is measured without
/// a product by K~, relative to g(u^N)'s largest free entry: the share of the law's correction
/// that the budget leaves unresolved. A linear
/// model is the case g = 0: the first iteration is the exact linear step. The force is
/// f_int - f summed over the held nodes, K u by the held rows of K plus g there. A tick costs
/// the linear tick plus, per iteration, an excess force, and per iteration after the first, a
/// solve.
#include <Eigen/Cholesky>
#include <array>
#include <memory>
#include <vector>

#include "integrators/effective_stiffness.hpp"
#include "model/average_acceleration.hpp"
#include "model/system_change.hpp"

namespace roifem::integrators {

/// A nonlinear model's modified-Newton iterations per tick, the first the linear tick's solve:
/// `iterations` exactly (a fixed budget), or fewer once the residual is within `tolerance` of the
/// law's excess force (0: never: the budget holds).
struct HapticNewton {
  int iterations = 2;
  double tolerance = 0;
};

class HapticTrapezoid {
 public:
  /// Factors K_eff = K + 2/dt C + 4/dt^2 M. Throws SolverError when it is not positive definite.
  HapticTrapezoid(const model::SecondOrderSystem& system, double dt, HapticNewton newton = {});
  HapticTrapezoid(const HapticTrapezoid&) = delete;
  HapticTrapezoid& operator=(const HapticTrapezoid&) = delete;

  /// The tool's nodes, as their (x, y, z) dofs in the system. Computes W's factor and Z (3m
  /// solves with the step's factor) and the tool's rows of K. Throws InputError for no node, a
  /// dof outside the system or held twice.
  void attach(const std::vector<std::array<Index, 3>>& node_dofs);
  /// Starts from `initial` (the held nodes where the tool is), acceleration consistent with it.
  void reset(const model::State& initial);
  /// The system has been changed in place (a cut: model/system_change.hpp) after the last tick,
  /// at `state`: K_eff's factor takes the change by Woodbury's correction (DirectSolve::update),
  /// the tool's compliance follows by the same identity from attach's Z, with no solve:
  ///   Z = Z_0 - Z_U T,   Z_U = K_0^-1 U,   T = (I + B U^T Z_U)^-1 B U^T Z_0,   W = H Z,
  /// formed at the held rows alone (O(r^2 m)); a tick applies Z through Z_0 and Z_U (tick()),
  /// and the acceleration is made consistent with the changed system at the free dofs (the held
  /// dofs' stays the tool's). InputError when the change reaches a held dof (the tool's rows of
  /// K would change), on a nonlinear model or with a mass that is not diagonal.
  void take_change(const model::SystemChange& change, const model::State& state);
  /// Solves ahead for the dofs a coming change will touch (a blade's next tetrahedra), between
  /// ticks: take_change then needs no solve for them, only the small capacitance and the products.
  void prefetch_change(const std::vector<Index>& dofs) { K_eff_.prefetch(dofs); }
  /// Factors K_eff afresh in a second thread as changes come (solvers/background_refactorization.hpp):
  /// each new factor, with the changes taken while it was made held in its correction, is swapped
  /// in at the start of a tick, so that the correction's rank (every tick's O(n r), every change's
  /// capacitance) stays small and this thread never waits on a factorization. The trajectory is
  /// the same to round-off whichever factor a tick uses. Call after attach, before any change.
  /// The BLAS runs on one thread while the loop lives (the two threads take a core each).
  void refactor_in_background();
  /// The dofs the coming changes will touch (a blade's next tetrahedra): with a background
  /// refactorization, each new factor comes with their columns, so that a change taken on it needs
  /// no solve on this thread (replaces the dofs given before). Without one: nothing (prefetch_change
  /// solves them here).
  void expect_change(std::vector<Index> dofs);
  /// Waits for the background's factor of every change taken so far and swaps it in: a known point
  /// (tests, replays). Nothing without a background refactorization or a change since the last.
  void wait_for_background();
  /// Factors swapped in from the background, and the last swap's time on this thread (s).
  long background_factors() const { return swaps_; }
  double swap_seconds() const { return swap_s_; }
  /// One tick: the tool at g (m) at t_{n+1} = t_0 + (n + 1) dt; advances `state` and returns the
  /// tool's force on the tissue (N). Allocates nothing.
  Vec3 tick(const Vec3& g, model::State& state);

  /// W = H K_eff^-1 H^T (m/N), rows and columns the held dofs in attach's order.
  const DenseMatrix& compliance() const { return W_; }
  /// A nonlinear model: the last tick's iterations and its residual after them (relative to the
  /// law's excess force).
  int last_iterations() const { return last_iterations_; }
  double last_residual() const { return last_residual_; }
  double dt() const { return rule_.dt(); }
  double attach_seconds() const { return attach_s_; }
  /// The last take_change's time (s): the factor's correction and the compliance's.
  double change_seconds() const { return change_s_; }
  /// Columns K_eff^-1 e_d the last take_change solved (those not ahead: 0 for a change fully foreseen).
  Index change_solves() const { return K_eff_.correction() ? K_eff_.correction()->last_solved() : 0; }

 private:
  const model::SecondOrderSystem& system_;
  model::AverageAcceleration rule_;
  DirectSolve K_eff_;
  std::vector<Index> held_;  // 3m dofs, x, y, z of each node in turn
  DenseMatrix W_;
  DenseMatrix Z0_;        ///< Z = K_eff^-1 H^T with the factored K_eff (n x 3m)
  DenseMatrix T_;         ///< the changes' coefficients for Z0_'s columns (r x 3m): Z = Z0_ - Z_U T_
  DenseMatrix Z_U_held_;  ///< the correction's Z_U at the held rows (3m x r)
  Vector coefficients_;   ///< a tick's correction coefficients (r)
  Eigen::LLT<DenseMatrix> W_factor_;
  Eigen::SparseMatrix<double, Eigen::RowMajor> rows_;  // 3 x n: the held dofs' rows of K summed per component
  double attach_s_ = 0, change_s_ = 0, swap_s_ = 0, t0_ = 0;
  std::unique_ptr<solvers::BackgroundRefactorization> background_;
  long swaps_ = 0;
  long k_ = 0;
  Vector a_, f_, w_, u_next_, work_, gap_;
  // A nonlinear model's modified Newton.
  HapticNewton newton_;
  std::vector<bool> is_held_;
  Vector excess_;       ///< g at the last iterate evaluated: u_n's at the start of a tick
  Vector excess_used_;  ///< g in the last solve's right-hand side
  Vector rhs_, zero_, step_;
  int last_iterations_ = 0;
  double last_residual_ = 0;
  /// W, its factor and what a tick needs of the changes taken (T_, Z_U_held_), after a change.
  void compliance_with_changes(const char* after);
  /// Holds a factor the background made (none: nothing), adding the changes taken since it read the log.
  void swap_in(std::unique_ptr<solvers::RefreshedFactor> fresh);
  /// The acceleration consistent with the system `change` made, at the change's dofs (take_change).
  void follow_the_change(const model::SystemChange& change, const model::State& state);
  /// u: the solve of K_eff u = rhs + M w (the changes taken included) under the tool's constraint H u = G(g).
  void constrained_solve(const Vector& rhs, const Vector& w, const Vec3& g, Vector& u);
  /// u_next_ from u^1 to the budget's answer; excess_ at it.
  void iterate_nonlinear();
};

}  // namespace roifem::integrators
