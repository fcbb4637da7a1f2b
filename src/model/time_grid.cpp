// SPDX-License-Identifier: GPL-3.0-or-later
#include "model/time_grid.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "common/errors.hpp"
#include "common/number_text.hpp"

namespace roifem::model {

void check_time_step(double dt, std::string_view who) {
  if (!(dt > 0) || !std::isfinite(dt))
    throw InputError(std::string(who) + ": time step dt = " + number_text(dt) + " s must be positive");
}

TimeGrid::TimeGrid(double t0, double dt, std::string_view who) : t0_(t0), dt_(dt), who_(who) { check_time_step(dt, who); }

long TimeGrid::index_of(double t, long from) const {
  const double steps = (t - t0_) / dt_;
  const long k = std::lround(steps);
  if (std::abs(steps - static_cast<double>(k)) > 1e-9 * std::max(1.0, std::abs(steps)) || k < from)
    throw InputError(std::string(who_) + ": t_out = " + number_text(t) + " s is not a later point of the grid t0 + k dt");
  return k;
}

long TimeGrid::last_at_or_before(double t) const { return static_cast<long>(std::floor((t - t0_) / dt_ + 1e-9)); }

}  // namespace roifem::model
