// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// An energy-momentum method (Gonzalez 2000; Simo & Tarnow 1992 for its motivation): the implicit
/// midpoint rule with the internal force replaced by its discrete gradient
/// (model/internal_force.hpp, fem/discrete_gradient.hpp), fixed step:
///   u_{n+1} - u_n = dt/2 (v_n + v_{n+1}),
///   M (v_{n+1} - v_n) = dt [ (f_n + f_{n+1})/2 - C (v_n + v_{n+1})/2 - f_alg(u_n, u_{n+1}) ].
/// Multiplying the second by (v_n + v_{n+1})/2 gives, because f_alg . (u_{n+1} - u_n) is exactly
/// W(u_{n+1}) - W(u_n), the discrete energy balance
///   E_{n+1} - E_n = (f_n + f_{n+1})/2 . (u_{n+1} - u_n) - dt (v_mid^T C v_mid),   E = v^T M v / 2 + W(u),
/// so an undamped, unloaded run conserves E to the Newton tolerance, at any dt, on the nonlinear
/// problem where the trapezoidal rule does not (its balance holds only when f_int is linear).
/// Second order, unconditionally stable in energy. On a linear system f_alg = K (u_n + u_{n+1})/2
/// and it is the trapezoidal rule exactly.
///
/// With v_{n+1} eliminated, each step solves for u = u_{n+1}
///   R(u) = (4/dt^2 M + 2/dt C)(u - u_n) + 2 f_alg(u_n, u) - (f_n + f_{n+1}) - 4/dt M v_n = 0
/// by Newton on its exact Jacobian 4/dt^2 M + 2/dt C + 2 d f_alg/du (model/internal_force.hpp),
/// which is not symmetric: KLU (solvers/sparse_lu.hpp), the pattern analysed once, with a
/// backtracking line search (solvers/newton.hpp); from the predictor u_n + dt v_n, and once more
/// from u_n where that fails. The tangent at the midpoint, symmetric, is O(|u - u_n|) off the
/// exact Jacobian, and on the paper brain (lambda = 333 mu) Newton on it converged too slowly to
/// go on. With the exact one and Gonzalez's projection of the whole law it failed when the slit
/// was held open; with the volumetric part's own discrete gradient (fem/discrete_gradient.hpp) it
/// takes a few iterations a step (the figures: docs/design-figures.md).
#include <memory>
#include <vector>

#include "integrators/integrator.hpp"
#include "integrators/integrator_info.hpp"
#include "model/time_grid.hpp"
#include "solvers/newton.hpp"
#include "solvers/sparse_lu.hpp"
#include "solvers/sparse_positions.hpp"

namespace roifem::integrators {

/// The table's row of this method (integrator_table.hpp): energy-momentum.
std::vector<IntegratorInfo> energy_momentum_rows();

class EnergyMomentum final : public Integrator {
 public:
  explicit EnergyMomentum(double dt, solvers::NewtonOptions options = {});
  std::string_view name() const override { return "energy-momentum"; }
  bool takes_nonlinear() const override { return true; }
  Stats stats() const override { return stats_; }
  /// The load at t_n it carries, its grid (origin and index) and counters.
  std::optional<IntegratorCheckpoint> checkpoint() const override;
  bool restarts_exactly() const override { return true; }

 private:
  void restore(const model::State& state, const IntegratorCheckpoint& saved) override;
  void prepare(const model::SecondOrderSystem& system, const model::State& initial) override;
  void advance(double t_out, model::State& state) override;
  void step(model::State& state);
  /// f_alg(u_a, u_b): the discrete gradient, or K (u_a + u_b)/2 on a linear system.
  void algorithmic_force(const Vector& u_a, const Vector& u_b, Vector& f);
  /// R(u), and R with its Jacobian (above), with b_ the step's right-hand side.
  void residual(const Vector& u_n, const Vector& u, Vector& r);
  void residual_and_jacobian(const Vector& u_n, const Vector& u, Vector& r, SparseMatrix& J);
  /// r = 2 r + inertia u - b_, with r holding f_alg on entry.
  void residual_of_force(const Vector& u, Vector& r) const;

  double dt_;
  solvers::NewtonOptions options_;
  const model::SecondOrderSystem* system_ = nullptr;
  model::TimeGrid grid_{0.0, 1.0, "energy-momentum"};
  long k_ = 0;
  SparseMatrix inertia_;                  ///< 4/dt^2 M + 2/dt C
  SparseMatrix K_alg_;                    ///< d f_alg / du_{n+1}, in K's pattern
  solvers::PatternSum jacobian_pattern_;  ///< 2 K_alg + inertia, in the union of their patterns
  solvers::SparseLu jacobian_;
  Vector f_now_, f_next_, b_, u_next_, work_, inertia_u_;
  Stats stats_;
};

}  // namespace roifem::integrators
