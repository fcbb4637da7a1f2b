// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// What the server sends the page. Binary frames (little-endian) for the bulk, JSON text for the
/// rest (written here, read by the page; the server reads no JSON).
///   mesh   "RFMS", uint32 V, uint32 T, uint32 0; float32 3V rest positions (mm); uint32 3T
///          vertex indices; uint8 V flags (bit 0 fixed, bit 1 + k in model k's ROI), zero-padded to 4
///   frame  "RFFR", uint32 V, uint32 the last hand message applied, uint32 model, float64 t (s);
///          float32 3V displacements (mm)
///   hello, state, notice, role: JSON objects with "type" (make_* below say what each holds)
#include <cstdint>
#include <string>
#include <vector>

#include "serve/live_scene.hpp"
#include "serve/physics_loop.hpp"

namespace roifem::serve {

/// The physics rate as the page shows it, over the last 10,000 ticks.
struct TickFigures {
  double median_ms = 0, p99_ms = 0, late_per_10k = 0, rate_hz = 0;
  long count = 0, slips = 0;
};

/// Keeps the last 10,000 tick durations and the ticks of the last second.
class TickWindow {
 public:
  explicit TickWindow(double deadline_s) : deadline_s_(deadline_s) {}
  /// Adds durations that arrived at `now_s` (a steady clock's seconds).
  void add(const std::vector<float>& seconds, double now_s);
  TickFigures figures(long slips) const;

 private:
  double deadline_s_;
  std::vector<float> window_;  ///< a ring of the last `capacity` durations
  std::size_t next_ = 0;
  long count_ = 0;
  std::vector<std::pair<double, std::size_t>> arrivals_;  ///< (time, how many) over the last second
  static constexpr std::size_t capacity = 10000;
};

/// A surface as the page draws it (LiveScene::surface(k)).
std::string mesh_message(const LiveScene& scene, const SurfaceView& surface);
std::string frame_message(const PhysicsSnapshot& snapshot, const std::vector<float>& displacement_mm);
std::string hello_message(const LiveScene& scene, std::size_t model, bool driver);
/// What a frame cost the server (ms): building it, and the static part's last recovery.
struct FrameFigures {
  double build_ms = 0, recovery_ms = 0;
};

/// Compare: the full model's force on the same hand at the latest tick it reached (N), the live
/// model's error against it there, the largest error and force of the grab so far, how far behind.
struct CompareFigures {
  bool on = false;
  std::string reference;  ///< the grab's reference model (empty: none for its model)
  double t = 0;
  Vec3 reference_force = Vec3::Zero(), error = Vec3::Zero();
  double largest_error = 0, largest_force = 0, behind_s = 0;
};

std::string state_message(const LiveScene& scene, const PhysicsSnapshot& snapshot, const TickFigures& ticks,
                          const FrameFigures& frame, const CompareFigures& compare, bool recording);
std::string notice_message(const std::string& text);
std::string role_message(bool driver);
/// text as a JSON string literal (quotes, backslashes and control characters escaped).
std::string json_string(const std::string& text);

}  // namespace roifem::serve
