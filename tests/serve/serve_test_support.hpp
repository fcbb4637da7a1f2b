// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// What the serve tests share: the paper's setup 1 as a live scene, a point on its surface that
/// every model's hand may pick, scalpel strokes beside it, and `roifem run`'s replay of a grab.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <variant>

#include "h5_read.hpp"
#include "scenario/scenario.hpp"
#include "serve/hand_message.hpp"
#include "serve/hand_recording.hpp"
#include "serve/live_scene.hpp"
#include "serve/scalpel.hpp"
#include "simulation/scenario_run.hpp"
#include "test_support.hpp"

namespace roifem::serve::test {

inline std::unique_ptr<LiveScene> paper_scene(const std::vector<std::string>& models = {},
                                              integrators::HapticNewton newton = {}) {
  std::ostringstream log;
  return std::make_unique<LiveScene>(scenario::read_scenario(ROIFEM_SCENARIO_DIR "/paper-setup1.toml"), 1000, 5.0, models, log,
                                     newton);
}

/// The force of `roifem run`'s replay of `grab` (its model, its cuts), per tick (N).
inline std::vector<Vec3> replayed_force(const LiveScene& scene, const GrabRecord& grab) {
  roifem::test::TempDir dir;
  const auto toml = write_replay(scene, grab, dir.path(), "grab");
  std::ostringstream log;
  simulation::run_scenario(scenario::read_scenario(toml), dir / "replay", log);
  const auto force = roifem::test::read_h5(dir / "replay/results.h5", "tools/hand/force_N");
  std::vector<Vec3> out;
  for (std::size_t i = 0; i + 2 < force.size(); i += 3) out.emplace_back(force[i], force[i + 1], force[i + 2]);
  return out;
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

/// A stroke as the page sends it, with the tetrahedra the server finds its blade crosses.
inline HandMessage stroke(const LiveScene& scene, const Vec3& from_mm, const Vec3& to_mm, const Vec3& move_mm) {
  HandMessage m{.kind = HandKind::cut, .sequence = 0, .point_mm = from_mm, .model = 0, .edge_to_mm = to_mm, .move_mm = move_mm};
  m.crossed = crossed_tetrahedra(scalpel_blade("scalpel", from_mm, to_mm, move_mm, 0, 1), scene.mesh());
  return m;
}

/// A vertical stroke (its edge along z from 3 mm above `point_mm`'s height to 6 mm below) beside
/// `point_mm` within model k's ROI, its tetrahedra's nodes farther than `clear_mm` from it: the first
/// of a ring of places 10 to 16 mm away.
inline HandMessage stroke_beside(const LiveScene& scene, std::size_t k, const Vec3& point_mm, double clear_mm) {
  const LiveModel& live = scene.models()[k];
  const mesh::TetMesh& mesh = scene.mesh();
  for (const double distance : {10.0, 13.0, 16.0})
    for (int direction = 0; direction < 8; ++direction) {
      const double angle = direction * std::numbers::pi / 4;
      const Vec3 offset(distance * std::cos(angle), distance * std::sin(angle), 0);
      const Vec3 top = point_mm + offset + Vec3(0, 0, 3);
      HandMessage m = stroke(scene, top, top - Vec3(0, 0, 9), Vec3(-std::sin(angle), std::cos(angle), 0) * 3.0);
      bool fits = m.crossed.size() >= 2;
      for (const Index e : m.crossed)
        for (const int n : mesh.tets[static_cast<std::size_t>(e)])
          fits = fits && live.in_roi[static_cast<std::size_t>(n)] && (mesh.node(n) / mm - point_mm).norm() > clear_mm;
      if (fits) return m;
    }
  throw std::runtime_error("no stroke fits beside the pick");
}

}  // namespace roifem::serve::test
