// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// The scale benchmark's haptic question: the largest ROI whose condensed step holds a rate.
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "scale/scale_model.hpp"

namespace roifem::bench {

/// One probe's answer: the condensed model of a ROI measured, or the reason it could not be.
struct ProbeResult {
  std::optional<ScaleMeasurement> measurement;
  std::string failure;
};
/// Measures the condensed model of a `count`-node ROI.
using RoiProbe = std::function<ProbeResult(long count)>;

struct RateSearch {
  long nodes = 0;                                           ///< of the brain (from the probes)
  long roi_nodes = 0, system_dofs = 0, interface_dofs = 0;  ///< of the largest ROI that holds
  double step_median_s = 0;
  std::vector<std::pair<long, ProbeResult>> probes;  ///< in probing order
};

/// The largest ROI (nodes nearest the target) whose condensed step holds `max_step_s` (median),
/// found by doubling from 1,000 nodes (at most `free_nodes`) and then bisection to within
/// `resolution` (relative). A failed probe counts as one that does not hold.
RateSearch largest_roi_at_rate(const RoiProbe& probe, double max_step_s, long free_nodes, double resolution = 0.05);

}  // namespace roifem::bench
