// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// A grab on the page, kept so that `roifem run` replays it: the hand's path as a tool trajectory
/// (t_s,x_mm,y_mm,z_mm, the format [[tool]] trajectory reads), the force the live loop felt, and
/// the scenario that replays it: the served scenario with one footprint tool ("hand") at the
/// grab's centre and radius following the trajectory, the model's ROI and reduction, the
/// trapezoidal rule at the haptic dt for as many steps as the grab ticked. The replay's tool is
/// eliminated where the live loop constrained it: the same discrete solution (haptic_trapezoid.hpp),
/// so its tools/hand/force_N equals the live force to round-off.
/// A cut model's cuts become [[cut]] tables, each stroke's blade sweeping within half a step so
/// that `roifem run` removes the same tetrahedra at the start of the same step: one taken between
/// grabs from start_s = 0 (before the first step), one taken after the live tick at t_n from
/// t_n + dt/2 (the start of the step from t_n), each over dt/2.
/// A "nearest" ROI counts free nodes, and the replay's tool nodes are not free: it asks for as
/// many fewer as the tool holds, which selects the same nodes.
#include <filesystem>
#include <string>
#include <vector>

#include "serve/live_scene.hpp"
#include "serve/physics_loop.hpp"

namespace roifem::serve {

struct GrabRecord {
  std::uint32_t grab = 0;
  std::size_t model = 0;
  Vec3 center_mm = Vec3::Zero();
  std::size_t grip_nodes = 0;
  std::vector<HandSample> samples;  ///< the first at t = 0, g = 0
  /// A cut model's: the cuts taken before the grab and during it (before its last tick), in order.
  std::vector<LiveCut> cuts;
};

/// The cuts of `grab`'s model that its replay takes, from the loop's record of every cut (in
/// order): those taken before the grab since its model was last made whole, and those during it
/// before its last tick.
std::vector<LiveCut> cuts_of_grab(const std::vector<LiveCut>& record, const GrabRecord& grab);

/// Writes DIR/NAME.csv (the path), DIR/NAME-force.csv (t_s,fx_N,fy_N,fz_N: the live force per
/// tick) and DIR/NAME.toml (the replay), each atomically. Returns the scenario's path.
std::filesystem::path write_replay(const LiveScene& scene, const GrabRecord& grab, const std::filesystem::path& directory,
                                   const std::string& name);

}  // namespace roifem::serve
