// SPDX-License-Identifier: GPL-3.0-or-later
#include "serve/compare_loop.hpp"

#include <chrono>

#include "common/errors.hpp"

namespace roifem::serve {

CompareLoop::CompareLoop(LiveScene& scene, std::size_t reference) : scene_(scene), reference_(reference) {
  if (reference >= scene.models().size()) throw Error("internal: compare: no model " + std::to_string(reference));
}

CompareLoop::~CompareLoop() { stop(); }

void CompareLoop::start() {
  if (thread_.joinable()) return;
  running_.store(true);
  thread_ = std::thread([this] { run(); });
}

void CompareLoop::stop() {
  running_.store(false);
  if (thread_.joinable()) thread_.join();
}

std::string CompareLoop::failure() const {
  const std::lock_guard lock(failure_mutex_);
  return failure_;
}

void CompareLoop::run() {
  std::unique_ptr<integrators::HapticTrapezoid> haptic;
  model::State state;
  std::uint32_t grab = 0;
  bool following = false;  // attached to the current grab
  std::vector<HandSample> batch;
  try {
    const model::SecondOrderSystem& system = scene_.models()[reference_].model->system();
    haptic = std::make_unique<integrators::HapticTrapezoid>(system, scene_.dt());
    while (running_.load(std::memory_order_relaxed)) {
      batch.clear();
      if (samples_.drain(batch) == 0) {
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
        continue;
      }
      for (const HandSample& s : batch) {
        if (s.grab != grab) {  // a new grab: the same footprint, from rest
          grab = s.grab;
          following = false;
          if (s.model == reference_) continue;  // the reference against itself: nothing to compare
          const auto grip = scene_.grip(reference_, s.center_mm);
          if (!std::holds_alternative<Grip>(grip)) continue;
          haptic->attach(std::get<Grip>(grip).dofs);
          state = model::State::at_rest(system.size());
          haptic->reset(state);
          following = true;
          continue;  // the grab's first sample is its start, t = 0
        }
        if (!following) continue;
        const Vec3 force = haptic->tick(s.g, state);
        results_.push({.grab = grab, .t = state.t, .force = force});
      }
    }
  } catch (const std::exception& e) {
    const std::lock_guard lock(failure_mutex_);
    failure_ = e.what();
  }
}

}  // namespace roifem::serve
