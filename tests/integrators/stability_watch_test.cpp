// SPDX-License-Identifier: GPL-3.0-or-later
// The stability watch (integrators/stability_watch.hpp): an explicit method at a fixed step on a
// nonlinear model is held to the limit that the tangent at each output gives.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "common/errors.hpp"
#include "integrators/factory.hpp"
#include "integrators/integrator_table.hpp"
#include "integrators/neo_hookean_cantilever.hpp"
#include "integrators/stability.hpp"
#include "model/spectrum.hpp"

namespace roifem::integrators {
namespace {

using testing::bending_force;
using testing::NeoHookeanCantilever;
using testing::run_until;

/// The time a SolverError's message names ("t = X s"), or -1.
double time_named(const std::string& what) {
  const auto at = what.find("t = ");
  return at == std::string::npos ? -1.0 : std::stod(what.substr(at + 4));
}

TEST(StabilityWatch, AStepStableAtRestButNotWhereTheTangentStiffensIsRefusedBeforeItDiverges) {
  // The cantilever bent three times as far as the other tests bend it: its tangent's highest
  // frequency rises along the run, so ERK4's limit falls from its value at rest to about 0.8 of
  // it. At 0.9 of the rest limit the step is stable at first and unstable later.
  const NeoHookeanCantilever c(2.0, 3 * bending_force, 0.3, fem::MaterialModel::neo_hookean, model::Ramp::Shape::smooth);
  const IntegratorInfo& info = integrator_info("arkode-erk4");
  const double rest = predicted_stability_limit(info, Vector{{0.0, model::highest_frequency(c.sys())}}, 2.0);
  const double dt = 0.9 * rest;
  auto error_of = [&](bool watch) {
    auto method = make_integrator(info, {.dt = dt, .watch_stability = watch});
    try {
      run_until(c.sys(), *method, 0.6, 0.02);
    } catch (const Error& e) {  // SolverError from a watch or a divergence, ModelError from an inverted element
      return std::string(e.what());
    }
    return std::string("<no error>");
  };
  const std::string watched = error_of(true), unwatched = error_of(false);
  std::printf("watched: %s\nunwatched: %s\n", watched.c_str(), unwatched.c_str());
  EXPECT_NE(watched.find("arkode-erk4: the step"), std::string::npos) << watched;
  EXPECT_NE(watched.find("is beyond the stability limit"), std::string::npos) << watched;
  // Without the watch the same run blows up (its elements invert, or the seam's energy check
  // trips): the limit was real, and the watch named it no later.
  EXPECT_TRUE(unwatched.find("diverged") != std::string::npos || unwatched.find("has inverted") != std::string::npos)
      << unwatched;
  EXPECT_GT(time_named(watched), 0.02) << "stable at rest: refused only where the tangent has stiffened";
  EXPECT_LE(time_named(watched), time_named(unwatched));
}

TEST(StabilityWatch, AStepBelowEveryLimitAlongTheRunIsLeftToRun) {
  const NeoHookeanCantilever c(2.0, 3 * bending_force, 0.3, fem::MaterialModel::neo_hookean, model::Ramp::Shape::smooth);
  const IntegratorInfo& info = integrator_info("arkode-erk4");
  const double rest = predicted_stability_limit(info, Vector{{0.0, model::highest_frequency(c.sys())}}, 2.0);
  auto method = make_integrator(info, {.dt = 0.7 * rest});
  const model::State s = run_until(c.sys(), *method, 0.6, 0.02);
  std::printf(
      "ERK4 limit at rest %.4e s, smallest along the run %.4e s (%.3f of it); the run at 0.7 of it ends with a %.2f mm drop\n",
      rest, method->smallest_stability_limit(), method->smallest_stability_limit() / rest, c.tip_drop(s) * 1e3);
  EXPECT_LT(method->smallest_stability_limit(), 0.9 * rest);
  EXPECT_GT(method->smallest_stability_limit(), 0.7 * rest);
  // A linear model's limit does not move: no watch is needed there, and none is asked for.
  const NeoHookeanCantilever linear(2.0, 3 * bending_force, 0.3, fem::MaterialModel::linear, model::Ramp::Shape::smooth);
  auto on_linear = make_integrator(info, {.dt = 0.7 * rest});
  run_until(linear.sys(), *on_linear, 0.1, 0.02);
  EXPECT_TRUE(std::isinf(on_linear->smallest_stability_limit()));
}

}  // namespace
}  // namespace roifem::integrators
