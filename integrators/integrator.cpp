// SPDX-License-Identifier: GPL-3.0-or-later
#include "integrators/integrator.hpp"

#include <cmath>
#include <limits>

#include "common/errors.hpp"
#include "common/format.hpp"
#include "common/number_text.hpp"
#include "integrators/callback_guard.hpp"
#include "integrators/stability_watch.hpp"
#include "model/internal_force.hpp"

namespace roifem::integrators {

IntegratorCheckpoint IntegratorCheckpoint::on_grid(const Vector& vector, double t0, long k, const Stats& stats) {
  IntegratorCheckpoint saved{.vectors = {vector}, .numbers = {t0, static_cast<double>(k)}};
  const std::vector<double> counters = stats.counters();
  saved.numbers.insert(saved.numbers.end(), counters.begin(), counters.end());
  return saved;
}

IntegratorCheckpoint::OnGrid IntegratorCheckpoint::read_on_grid(std::string_view method, Index unknowns) const {
  if (vectors.size() != 1 || vectors[0].size() != unknowns || numbers.size() != 2 + stats_fields().size())
    throw InputError(std::string(method) + ": the checkpoint does not fit this model (" + std::to_string(vectors.size()) +
                     " vectors, " + std::to_string(numbers.size()) + " numbers)");
  return {.vector = vectors[0], .t0 = numbers[0], .k = static_cast<long>(numbers[1]), .stats = Stats::from_counters(numbers, 2)};
}

Integrator::Integrator() = default;
Integrator::~Integrator() = default;
Integrator::Integrator(Integrator&&) noexcept = default;
Integrator& Integrator::operator=(Integrator&&) noexcept = default;

void Integrator::watch_stability(const IntegratorInfo& method, double dt) {
  watch_ = std::make_unique<StabilityWatch>(method, dt);
}

void Integrator::reset(const model::SecondOrderSystem& system, const model::State& initial) {
  bound_.reset();
  if (system.is_nonlinear() && !takes_nonlinear())
    throw InputError(std::string(name()) + " does not take a nonlinear model (" + system.internal_force->describe() +
                     "): the methods that do are marked 'nonlinear' in `roifem run --help`; or give [material] model = "
                     "\"linear\"");
  prepare(system, initial);
  bound_.emplace(system, initial);
  system_ = &system;
}

void Integrator::advance_to(double t_out, model::State& state) {
  if (!bound_) throw Error("internal: " + std::string(name()) + ": advance_to before reset");
  const double* u_storage = state.u.data();
  const double* v_storage = state.v.data();
  {
    const TimeLimitScope limit(deadline_, std::string(name()));
    advance(t_out, state);
  }
  if (state.u.data() != u_storage || state.v.data() != v_storage)
    throw SolverError(std::string(name()) + ": the state's storage moved during the step to t = " + number_text(t_out) +
                      " s, step " + std::to_string(stats().steps) + " (a bug in the integrator: it must write into u and v)");
  check_bounded(state);
  if (watch_) watch_->check(name(), *system_, state, stats().steps);
}

bool Integrator::take_change(const model::SecondOrderSystem& system, const model::SystemChange& change,
                             const model::State& state) {
  if (!bound_) throw Error("internal: " + std::string(name()) + ": take_change before reset");
  const bool restarted = absorb_change(system, change, state);
  bound_.emplace(system, state);
  system_ = &system;
  return restarted;
}

void Integrator::resume(const model::SecondOrderSystem& system, const model::State& state,
                        const std::optional<IntegratorCheckpoint>& saved) {
  if (!saved || !restarts_exactly()) return reset(system, state);
  if (!bound_ || system_ != &system) throw Error("internal: " + std::string(name()) + ": resume before reset");
  restore(state, *saved);
  bound_.emplace(system, state);
}

void Integrator::restore(const model::State&, const IntegratorCheckpoint&) {
  throw Error("internal: " + std::string(name()) + " keeps no checkpoint to restore");
}

bool Integrator::absorb_change(const model::SecondOrderSystem& system, const model::SystemChange&, const model::State& state) {
  prepare(system, state);
  return true;
}

void Integrator::set_time_limit(double seconds) {
  if (!(seconds >= 0)) throw InputError(std::string(name()) + ": a time limit must be 0 or more, not " + number_text(seconds));
  deadline_ = std::chrono::steady_clock::now() +
              std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(seconds));
}

double Integrator::smallest_stability_limit() const {
  return watch_ ? watch_->smallest_limit() : std::numeric_limits<double>::infinity();
}

void Integrator::check_bounded(const model::State& state) {
  const double norm = bound_->velocity_norm(state);
  const double bound = bound_->velocity_norm_bound(state.t);
  const bool finite = std::isfinite(norm) && state.u.allFinite();
  if (finite && norm <= divergence_factor * bound) return;
  const std::string why =
      finite
          ? format(
                "its kinetic energy, %.3g J, is %.2g times the most the loads can have given the exact solution by then, %.3g J",
                0.5 * norm * norm, norm * norm / (bound * bound), 0.5 * bound * bound)
          : std::string("non-finite values");
  throw SolverError(
      std::string(name()) + ": the solution diverged (" + why + ") by t = " + number_text(state.t) + " s, step " +
      std::to_string(stats().steps) +
      "; an explicit method's step beyond its stability limit does this: a smaller time.dt_s, or an implicit method");
}

}  // namespace roifem::integrators
