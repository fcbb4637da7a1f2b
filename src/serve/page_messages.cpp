// SPDX-License-Identifier: GPL-3.0-or-later
#include "serve/page_messages.hpp"

#include <algorithm>
#include <cstring>

#include "common/format.hpp"

namespace roifem::serve {

namespace {

template <class T>
void append(std::string& out, const T& value) {
  const auto* bytes = reinterpret_cast<const char*>(&value);
  out.append(bytes, sizeof(T));
}

std::string vec3(const Vec3& v) { return format("[%.6g,%.6g,%.6g]", v.x(), v.y(), v.z()); }

}  // namespace

void TickWindow::add(const std::vector<float>& seconds, double now_s) {
  for (const float s : seconds) {
    if (window_.size() < capacity)
      window_.push_back(s);
    else
      window_[next_] = s;
    next_ = (next_ + 1) % capacity;
  }
  count_ += static_cast<long>(seconds.size());
  arrivals_.emplace_back(now_s, seconds.size());
  while (!arrivals_.empty() && arrivals_.front().first < now_s - 1.0) arrivals_.erase(arrivals_.begin());
}

TickFigures TickWindow::figures(long slips) const {
  TickFigures f;
  f.count = count_;
  f.slips = slips;
  if (window_.empty()) return f;
  std::vector<float> sorted = window_;
  std::sort(sorted.begin(), sorted.end());
  const auto at = [&](double q) {
    return 1e3 * sorted[std::min(sorted.size() - 1, static_cast<std::size_t>(q * static_cast<double>(sorted.size())))];
  };
  f.median_ms = at(0.5);
  f.p99_ms = at(0.99);
  const auto late = std::count_if(sorted.begin(), sorted.end(), [&](float s) { return s > deadline_s_; });
  f.late_per_10k = 1e4 * static_cast<double>(late) / static_cast<double>(sorted.size());
  std::size_t recent = 0;
  for (const auto& [t, n] : arrivals_) recent += n;
  f.rate_hz = static_cast<double>(recent);  // ticks that arrived within the last second
  return f;
}

std::string mesh_message(const LiveScene& scene, const SurfaceView& s) {
  const auto V = static_cast<std::uint32_t>(s.nodes.size()), T = static_cast<std::uint32_t>(s.triangles.size());
  std::string out = "RFMS";
  append(out, V);
  append(out, T);
  append(out, std::uint32_t{0});
  for (const int n : s.nodes)
    for (int c = 0; c < 3; ++c) append(out, static_cast<float>(scene.mesh().node(n)[c] / mm));
  for (const auto& t : s.triangles)
    for (const int v : t) append(out, static_cast<std::uint32_t>(v));
  out.append(reinterpret_cast<const char*>(s.flags.data()), s.flags.size());
  out.append((4 - out.size() % 4) % 4, '\0');
  return out;
}

std::string frame_message(const PhysicsSnapshot& snapshot, const std::vector<float>& displacement_mm) {
  std::string out = "RFFR";
  append(out, static_cast<std::uint32_t>(displacement_mm.size() / 3));
  append(out, snapshot.hand_sequence);
  append(out, static_cast<std::uint32_t>(snapshot.model));
  append(out, snapshot.t);
  out.append(reinterpret_cast<const char*>(displacement_mm.data()), displacement_mm.size() * sizeof(float));
  return out;
}

std::string hello_message(const LiveScene& scene, std::size_t model, bool driver) {
  std::string models;
  for (const LiveModel& m : scene.models()) {
    if (!models.empty()) models += ",";
    models += format("{\"name\":%s,\"description\":%s,\"unknowns\":%ld,\"roi_nodes\":%zu,\"nonlinear\":%s,\"cut\":%s}",
                     json_string(m.name).c_str(), json_string(m.description).c_str(), static_cast<long>(m.unknowns), m.roi_size,
                     m.nonlinear() ? "true" : "false", m.cuttable() ? "true" : "false");
  }
  const auto& box = scene.box();
  return format(
      "{\"type\":\"hello\",\"scenario\":%s,\"models\":[%s],\"model\":%zu,\"role\":\"%s\",\"rate_hz\":%.6g,\"radius_mm\":%.6g,"
      "\"box_mm\":[%s,%s],\"vertices\":%zu,\"loads\":%s,\"hand\":%s}",
      json_string(scene.scenario().file.filename().string()).c_str(), models.c_str(), model, driver ? "driver" : "watcher",
      1.0 / scene.dt(), scene.radius_mm(), vec3(box.min() / mm).c_str(), vec3(box.max() / mm).c_str(),
      scene.surface().nodes.size(), json_string(scene.loads_said()).c_str(), hand_protocol_json().c_str());
}

std::string state_message(const LiveScene& scene, const PhysicsSnapshot& s, const TickFigures& ticks, const FrameFigures& frame,
                          const CompareFigures& compare, bool recording) {
  const std::string comparison =
      compare.on ? format(
                       ",\"compare\":{\"reference\":%s,\"t\":%.6f,\"full_force_mN\":%s,\"error_mN\":%s,\"largest_error_mN\":%.6g,"
                       "\"largest_full_force_mN\":%.6g,\"behind_s\":%.4f}",
                       compare.reference.empty() ? "null" : json_string(compare.reference).c_str(), compare.t,
                       vec3(1e3 * compare.reference_force).c_str(), vec3(1e3 * compare.error).c_str(),
                       1e3 * compare.largest_error, 1e3 * compare.largest_force, compare.behind_s)
                 : std::string();
  const std::string newton = scene.models()[s.model].nonlinear() ? format(",\"newton\":{\"iterations\":%d,\"residual\":%.3g}",
                                                                          s.newton_iterations, s.newton_residual)
                                                                 : std::string();
  return format(
      "{\"type\":\"state\",\"t\":%.6f,\"model\":%zu,\"model_name\":%s,\"grab\":%u,\"holding\":%s,\"grip_nodes\":%zu,"
      "\"force_mN\":%s,\"tool_mm\":%s,\"g_mm\":%s,\"seq\":%u,\"recording\":%s,"
      "\"ticks\":{\"median_ms\":%.4f,\"p99_ms\":%.4f,\"late_per_10k\":%.2f,\"rate_hz\":%.1f,\"count\":%ld,\"slips\":%ld},"
      "\"frame\":{\"build_ms\":%.3f,\"recovery_ms\":%.3f},\"failure\":%s%s%s}",
      s.t, s.model, json_string(scene.models()[s.model].name).c_str(), s.grab, s.holding ? "true" : "false", s.grip_nodes,
      vec3(1e3 * s.force).c_str(), vec3(s.grip_center_mm + s.g / mm).c_str(), vec3(s.g / mm).c_str(), s.hand_sequence,
      recording ? "true" : "false", ticks.median_ms, ticks.p99_ms, ticks.late_per_10k, ticks.rate_hz, ticks.count, ticks.slips,
      frame.build_ms, frame.recovery_ms, s.failure.empty() ? "null" : json_string(s.failure).c_str(), comparison.c_str(),
      newton.c_str());
}

std::string notice_message(const std::string& text) { return "{\"type\":\"notice\",\"text\":" + json_string(text) + "}"; }

std::string role_message(bool driver) {
  return std::string("{\"type\":\"role\",\"role\":\"") + (driver ? "driver" : "watcher") + "\"}";
}

std::string json_string(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      out += format("\\u%04x", static_cast<unsigned>(static_cast<unsigned char>(c)));
    } else {
      out += c;
    }
  }
  return out + "\"";
}

}  // namespace roifem::serve
