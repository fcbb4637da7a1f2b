// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// The trapezoidal rule (Newmark beta = 1/4, gamma = 1/2, average acceleration: the recurrence of
/// model/average_acceleration.hpp), fixed step, as in Hansen & Larsen (1998). Unconditionally stable, second order, no numerical
/// damping: without C and f the discrete energy v^T M v / 2 + u^T K u / 2 is conserved exactly.
///   K_eff u_{n+1} = f_{n+1} + M (4/dt^2 u_n + 4/dt v_n + a_n) + C (2/dt u_n + v_n),
///   K_eff = K + 2/dt C + 4/dt^2 M  (factored once),
///   a_{n+1} = 4/dt^2 (u_{n+1} - u_n) - 4/dt v_n - a_n,   v_{n+1} = v_n + dt/2 (a_n + a_{n+1}).
/// Time levels are t_k = t_0 + k dt (never accumulated by t += dt).
///
/// K_eff is solved by one of the strategies of effective_stiffness.hpp: CHOLMOD ("trapezoid"; a
/// system's declared modal coordinates eliminated in closed form first: modal_elimination.hpp),
/// or, where its factor does not fit in memory, Jacobi-preconditioned conjugate gradients to a
/// relative residual of 1e-10 ("trapezoid-cg", started from the predictor u_n + dt v_n +
/// dt^2/2 a_n). Both give the same answer to ~1e-9 relative over hundreds of steps; the direct
/// solve is much faster where it fits (docs/design-figures.md). With C = alpha M (SecondOrderSystem::damping) the history
/// term folds C into M's product; a general C adds its own product to f.
///
/// A nonlinear system (model/internal_force.hpp) takes the same history and solves its implicit
/// equation by Newton instead of one solve (trapezoid_newton.hpp); its statistics count the Newton
/// iterations (nonlinear_iterations), the tangents assembled (jac_evals) and factorized
/// (lin_setups). A step whose Newton iteration does not converge, or that inverts an element, is an
/// error naming the step and time; nothing is extrapolated.
#include <memory>
#include <optional>
#include <vector>

#include "integrators/effective_stiffness.hpp"
#include "integrators/integrator.hpp"
#include "integrators/integrator_info.hpp"
#include "integrators/step_control.hpp"
#include "integrators/trapezoid_newton.hpp"
#include "model/average_acceleration.hpp"
#include "model/time_grid.hpp"
#include "solvers/jacobi_cg.hpp"

namespace roifem::integrators {

/// The factory's maker for the table's trapezoid rows (CG where the row's linear solver says so).
std::unique_ptr<Integrator> make_trapezoid(const IntegratorInfo& info, const StepControl& control);
/// The table's rows of this family (integrator_table.hpp): trapezoid, trapezoid-cg.
std::vector<IntegratorInfo> trapezoid_rows();

class Trapezoid final : public Integrator {
 public:
  explicit Trapezoid(double dt);
  /// The same rule with K_eff solved by conjugate gradients instead of a factorization.
  Trapezoid(double dt, solvers::CgSettings cg);
  std::string_view name() const override { return cg_ ? "trapezoid-cg" : "trapezoid"; }
  bool takes_nonlinear() const override { return !cg_; }
  Stats stats() const override { return stats_; }
  /// One step from the current state (the hot path a simulator calls each tick).
  void step(model::State& state);
  double dt() const { return rule_.dt(); }
  /// Whether the last reset eliminates the system's modal coordinates (modal_elimination.hpp).
  bool eliminates_modal_coordinates() const { return eliminates_modal_; }
  /// The acceleration a_n the recurrence carries, its grid (origin and index) and counters.
  std::optional<IntegratorCheckpoint> checkpoint() const override;
  bool restarts_exactly() const override { return true; }

 private:
  void restore(const model::State& state, const IntegratorCheckpoint& saved) override;
  void prepare(const model::SecondOrderSystem& system, const model::State& initial) override;
  /// t_out must lie on the grid t_0 + k dt (within 1e-9 dt).
  void advance(double t_out, model::State& state) override;
  /// A factored K_eff takes the change by a low-rank correction (EffectiveStiffnessSolver::update),
  /// and the acceleration is made consistent with the changed system at `state`; else a restart.
  bool absorb_change(const model::SecondOrderSystem& system, const model::SystemChange& change,
                     const model::State& state) override;
  model::AverageAcceleration rule_;  // the recurrence; K_eff_ solves its one linear system
  const model::SecondOrderSystem* system_ = nullptr;
  std::optional<solvers::CgSettings> cg_;  // set: K_eff is solved iteratively
  std::unique_ptr<EffectiveStiffnessSolver> K_eff_;
  std::unique_ptr<TrapezoidNewton> newton_;  // a nonlinear system's implicit equation (K_eff_ then unused)
  bool eliminates_modal_ = false;
  model::TimeGrid grid_{0.0, 1.0, "trapezoid"};  ///< t_k = t_0 + k dt from the last reset
  long k_ = 0;
  long iterations_before_ = 0;  ///< an iterative K_eff's iterations counted before a restore
  void solve_nonlinear(const model::State& s);
  Vector a_, f_, u_next_, work_;
  Stats stats_;
};

}  // namespace roifem::integrators
