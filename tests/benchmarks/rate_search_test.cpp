// SPDX-License-Identifier: GPL-3.0-or-later
// The haptic search of the scale benchmark against probes whose answer is known: a step time that
// grows linearly with the ROI, so that the largest ROI within the rate is floor(limit / slope).
#include <gtest/gtest.h>

#include <cmath>

#include "scale/rate_search.hpp"

namespace roifem::bench {
namespace {

/// A probe whose step takes `slope_s` per ROI node; counts from `fails_from` on fail to measure.
RoiProbe linear_probe(double slope_s, long fails_from = 1L << 40) {
  return [=](long count) -> ProbeResult {
    if (count >= fails_from) return {std::nullopt, "killed (out of memory)"};
    ScaleMeasurement m;
    m.nodes = 100000;
    m.roi_nodes = count;
    m.system_dofs = 3 * count;
    m.interface_dofs = 40 * static_cast<long>(std::sqrt(static_cast<double>(count)));
    m.step_median_s = slope_s * static_cast<double>(count);
    return {m, ""};
  };
}

void expect_within_resolution(const RateSearch& r, long largest_that_holds, double resolution = 0.05) {
  EXPECT_LE(r.roi_nodes, largest_that_holds);
  EXPECT_GE(static_cast<double>(r.roi_nodes), static_cast<double>(largest_that_holds) / (1 + resolution));
  for (const auto& [count, result] : r.probes) {  // every probe judged right
    if (result.measurement && result.measurement->step_median_s <= 1e-3) {
      EXPECT_LE(count, r.roi_nodes);
    }
  }
}

TEST(RateSearch, DoublesThenBisectsToTheLargestRoiWithinTheRate) {
  const RateSearch r = largest_roi_at_rate(linear_probe(0.7e-6), 1e-3, 100000);
  expect_within_resolution(r, 1428);  // 1428 x 0.7 us = 0.9996 ms; 1429 -> 1.0003 ms
  EXPECT_EQ(r.nodes, 100000);
  EXPECT_EQ(r.system_dofs, 3 * r.roi_nodes);
  EXPECT_DOUBLE_EQ(r.step_median_s, 0.7e-6 * static_cast<double>(r.roi_nodes));
  EXPECT_LE(r.probes.size(), 8u);  // 1000, 2000, then bisection
}

TEST(RateSearch, HalvesDownWhenAThousandNodesAreAlreadyTooSlow) {
  expect_within_resolution(largest_roi_at_rate(linear_probe(4e-6), 1e-3, 100000), 250);
}

TEST(RateSearch, AFailedProbeCountsAsOneThatDoesNotHold) {
  // Holds up to 2000 nodes by time, but nothing from 1500 on can be built: the answer is below 1500.
  const RateSearch r = largest_roi_at_rate(linear_probe(0.5e-6, 1500), 1e-3, 100000);
  expect_within_resolution(r, 1499);
  long failed = 0;
  for (const auto& [count, result] : r.probes)
    if (!result.measurement) {
      ++failed;
      EXPECT_GE(count, 1500);
      EXPECT_EQ(result.failure, "killed (out of memory)");
    }
  EXPECT_GE(failed, 1);
}

TEST(RateSearch, AWholeBrainThatHoldsIsTheAnswer) {
  const RateSearch r = largest_roi_at_rate(linear_probe(1e-7), 1e-3, 684);
  EXPECT_EQ(r.roi_nodes, 684);
  ASSERT_EQ(r.probes.size(), 1u);
  EXPECT_EQ(r.probes[0].first, 684);
}

}  // namespace
}  // namespace roifem::bench
