// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// What the serve tests share: the paper's setup 1 as a live scene, and a point on its surface
/// that every model's hand may pick.
#include <algorithm>
#include <sstream>
#include <variant>

#include "scenario/scenario.hpp"
#include "serve/live_scene.hpp"

namespace roifem::serve::test {

inline std::unique_ptr<LiveScene> paper_scene(const std::vector<std::string>& models = {},
                                              integrators::HapticNewton newton = {}) {
  std::ostringstream log;
  return std::make_unique<LiveScene>(scenario::read_scenario(ROIFEM_SCENARIO_DIR "/paper-setup1.toml"), 1000, 5.0, models, log,
                                     newton);
}

/// The surface node nearest the ROI's target whose footprint every model can hold (mm).
inline Vec3 pickable_point(const LiveScene& scene) {
  std::vector<int> nodes = scene.surface().nodes;
  const Vec3 target = scene.scenario().roi->center;
  std::sort(nodes.begin(), nodes.end(),
            [&](int a, int b) { return (scene.mesh().node(a) - target).norm() < (scene.mesh().node(b) - target).norm(); });
  for (const int n : nodes) {
    const Vec3 point = scene.mesh().node(n) / mm;
    bool every = true;
    for (std::size_t k = 0; k < scene.models().size() && every; ++k) every = std::holds_alternative<Grip>(scene.grip(k, point));
    if (every) return point;
  }
  throw std::runtime_error("no surface point every model can pick");
}

}  // namespace roifem::serve::test
