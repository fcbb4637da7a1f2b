// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// The integrator seam: every time integrator advances the same second-order system
///   M u'' + C u' + K u = f(t)
/// from a State, converting it to whatever form its method needs. Output, energy and error are
/// observers of the run loop, never code inside an integrator.
///
/// The seam checks every method's answer the same way: after each advance_to, a state that is
/// not finite, or whose kinetic energy exceeds 100 times the most the loads can have given the
/// exact solution by then (model/energy_bound.hpp), is a divergence, a SolverError naming the
/// method, the time and its step. An explicit method past its stability limit trips it within a
/// few steps, long before its numbers overflow; no family checks this on its own. On a nonlinear
/// model an explicit method at a fixed step is also held to the stability limit of the tangent
/// at each output (integrators/stability_watch.hpp).
#include <chrono>
#include <memory>
#include <optional>
#include <string_view>
#include <vector>

#include "integrators/stats.hpp"
#include "model/energy_bound.hpp"
#include "model/second_order_system.hpp"
#include "model/system_change.hpp"

namespace roifem::integrators {

struct IntegratorInfo;
class StabilityWatch;

/// What a method carries from one step to the next beyond the state (u, v, t): its own vectors
/// (the trapezoidal rule's acceleration) and numbers (its grid's origin and step index, its
/// counters). A restart that restores it goes on bit for bit as the run that never stopped.
struct IntegratorCheckpoint {
  std::vector<Vector> vectors;
  std::vector<double> numbers;

  /// A method on a fixed time grid (the trapezoidal rule, energy-momentum): its one vector, the
  /// grid's origin t0 and step index k, its counters.
  struct OnGrid {
    Vector vector;
    double t0 = 0;
    long k = 0;
    Stats stats;
  };
  static IntegratorCheckpoint on_grid(const Vector& vector, double t0, long k, const Stats& stats);
  /// Reads an on_grid point back; InputError naming `method` unless it holds one vector of
  /// `unknowns` entries, the grid and every counter.
  OnGrid read_on_grid(std::string_view method, Index unknowns) const;
};

/// What a method that holds the tools' constraints itself (the DAE forms) says of them now.
struct ConstraintReport {
  Vector forces;              ///< each tool's force on the tissue from its multipliers (3 per tool, N)
  double position_drift = 0;  ///< max |H u - G| (m)
  double velocity_drift = 0;  ///< max |H v - G'| (m/s)
};

class Integrator {
 public:
  /// ||v||_M beyond this factor of the exact solution's bound is a divergence (kinetic energy 100x).
  static constexpr double divergence_factor = 10;

  Integrator();
  virtual ~Integrator();
  Integrator(Integrator&&) noexcept;
  Integrator& operator=(Integrator&&) noexcept;
  virtual std::string_view name() const = 0;
  /// Prepares for `system` from `initial` (factorizations, solver memory). The system must outlive
  /// the integrator's use of it.
  void reset(const model::SecondOrderSystem& system, const model::State& initial);
  /// Advances `state` to t_out; throws SolverError naming the method, t and step on failure or
  /// divergence (above). The state's storage is the caller's: a method writes into u and v, never
  /// swaps or resizes them, so that views of them (the Python module's arrays) stay valid.
  void advance_to(double t_out, model::State& state);
  virtual Stats stats() const = 0;
  /// The system has been changed in place at `state` (a cut: model/system_change.hpp), whose time is
  /// on the method's grid: it goes on from there. A method that can update what it holds does so
  /// (the trapezoidal rule's factor, by a low-rank correction: Stats::system_changes counts these);
  /// the others restart from `state`, as reset() does. Returns whether its counters started again
  /// (the caller then keeps the old ones). The divergence check's bound starts afresh from `state`.
  bool take_change(const model::SecondOrderSystem& system, const model::SystemChange& change, const model::State& state);
  /// Whether it integrates a nonlinear system (model/internal_force.hpp); the table's `nonlinear`
  /// says the same (a test holds the two together). reset() refuses a nonlinear system otherwise.
  virtual bool takes_nonlinear() const { return false; }
  /// The constraints' report after the last advance_to, from methods that hold constraints (else none).
  virtual std::optional<ConstraintReport> constraints() const { return std::nullopt; }
  /// An explicit method at a fixed step: after each advance_to on a nonlinear model, the step is
  /// checked against the stability limit of the tangent there (the factory attaches it).
  void watch_stability(const IntegratorInfo& method, double dt);
  /// The smallest stability limit the watch has found (s; infinity without a watch or a check).
  double smallest_stability_limit() const;
  /// A checkpoint of the method after the last advance_to, for a restart that continues exactly;
  /// none for a method that restarts afresh from the state alone (ARKODE, IDA, GSL: their step
  /// sizes and histories are the libraries' own). The table's `restarts_exactly` says the same.
  virtual std::optional<IntegratorCheckpoint> checkpoint() const { return std::nullopt; }
  /// Whether checkpoint() gives one (and restore() takes it).
  virtual bool restarts_exactly() const { return false; }
  /// Goes on from `state` on `system`, as the run that took `saved` there would: the method must
  /// be reset() on the same system and have taken the same changes since (a restart replays the
  /// cuts before it). Without `saved` (or for a method without checkpoints): reset(system, state),
  /// a fresh start from the state alone.
  void resume(const model::SecondOrderSystem& system, const model::State& state,
              const std::optional<IntegratorCheckpoint>& saved);
  /// A wall-clock limit on the run from now (compare's and energy's --max-run-seconds): past it,
  /// advance_to throws OverTime (common/errors.hpp) from within the library's call, heard in every
  /// callback and between a stepper's own steps (callback_guard.hpp: TimeLimitScope), with the
  /// model time reached. None by default.
  void set_time_limit(double seconds);

 private:
  /// What each method implements: reset() and advance_to() without the divergence check.
  virtual void prepare(const model::SecondOrderSystem& system, const model::State& initial) = 0;
  virtual void advance(double t_out, model::State& state) = 0;
  /// resume() with a checkpoint this method took (checkpoint() returned one): its own state back.
  virtual void restore(const model::State& state, const IntegratorCheckpoint& saved);
  /// take_change() without the bound: by default a restart (prepare); returns whether the counters restarted.
  virtual bool absorb_change(const model::SecondOrderSystem& system, const model::SystemChange& change,
                             const model::State& state);
  /// SolverError when `state` has diverged.
  void check_bounded(const model::State& state);

  std::optional<model::EnergyBound> bound_;
  std::unique_ptr<StabilityWatch> watch_;
  std::optional<std::chrono::steady_clock::time_point> deadline_;
  const model::SecondOrderSystem* system_ = nullptr;
};

}  // namespace roifem::integrators
