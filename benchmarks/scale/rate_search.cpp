// SPDX-License-Identifier: GPL-3.0-or-later
#include "scale/rate_search.hpp"

#include <algorithm>

namespace roifem::bench {

RateSearch largest_roi_at_rate(const RoiProbe& probe, double max_step_s, long free_nodes, double resolution) {
  RateSearch r;
  auto holds = [&](long count) {
    ProbeResult result = probe(count);
    const auto& m = result.measurement;
    const bool ok = m && m->step_median_s <= max_step_s;
    if (m) r.nodes = m->nodes;
    if (ok && count > r.roi_nodes) {
      r.roi_nodes = count;
      r.system_dofs = m->system_dofs;
      r.interface_dofs = m->interface_dofs;
      r.step_median_s = m->step_median_s;
    }
    r.probes.emplace_back(count, std::move(result));
    return ok;
  };
  long lo = 0, hi = 0;  // largest count known to hold, smallest known to fail
  for (long count = 1000;; count *= 2) {
    count = std::min(count, free_nodes);
    if (!holds(count)) {
      hi = count;
      break;
    }
    lo = count;
    if (count == free_nodes) return r;
  }
  if (lo == 0)  // 1000 already fails: halve down
    for (long count = hi / 2; count >= 10; count /= 2) {
      if (holds(count)) {
        lo = count;
        break;
      }
      hi = count;
    }
  while (lo > 0 && static_cast<double>(hi - lo) > resolution * static_cast<double>(lo)) {
    const long mid = (lo + hi) / 2;
    (holds(mid) ? lo : hi) = mid;
  }
  return r;
}

}  // namespace roifem::bench
