// SPDX-License-Identifier: GPL-3.0-or-later
#include "integrators/stability_watch.hpp"

#include <cmath>
#include <string>

#include "common/errors.hpp"
#include "common/format.hpp"
#include "common/number_text.hpp"
#include "integrators/stability.hpp"
#include "model/internal_force.hpp"
#include "model/spectrum.hpp"

namespace roifem::integrators {

void StabilityWatch::check(std::string_view name, const model::SecondOrderSystem& system, const model::State& state, long steps) {
  if (!system.is_nonlinear()) return;
  if (K_t_.rows() != system.size()) {  // the first check: what does not move with the state
    K_t_ = system.K;
    f_.resize(system.size());
    alpha_ = model::mass_proportional_damping(system);
    if (!std::isfinite(alpha_)) alpha_ = 0;
  }
  system.internal_force->force_and_tangent(state.t, state.u, f_, K_t_);
  const double omega = model::highest_frequency(system, K_t_, 1e-6);
  const double limit = predicted_stability_limit(method_, Vector{{0.0, omega}}, alpha_);
  smallest_limit_ = std::min(smallest_limit_, limit);
  if (dt_ <= limit) return;
  throw SolverError(
      format("%s: the step %s s is beyond the stability limit %s s that the tangent gives at t = %s s, "
             "step %ld (its highest frequency %.4g rad/s, the model's at rest %.4g): a smaller time.dt_s, "
             "or an implicit method",
             std::string(name).c_str(), number_text(dt_).c_str(), number_text(limit).c_str(), number_text(state.t).c_str(), steps,
             omega, model::highest_frequency(system, 1e-6)));
}

}  // namespace roifem::integrators
