// SPDX-License-Identifier: GPL-3.0-or-later
#include "serve/compare_loop.hpp"

#include <chrono>
#include <map>

#include "common/errors.hpp"

namespace roifem::serve {

CompareLoop::CompareLoop(LiveScene& scene) : scene_(scene) {}

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
  std::map<std::size_t, std::unique_ptr<integrators::HapticTrapezoid>> references;
  integrators::HapticTrapezoid* haptic = nullptr;  // the current grab's reference
  model::State state;
  std::uint32_t grab = 0;
  bool following = false;  // attached to the current grab
  std::vector<HandSample> batch;
  try {
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
          const auto reference = scene_.reference_of(s.model);
          if (!reference) continue;  // a full model, or no full model with its law: nothing to compare
          const auto grip = scene_.grip(*reference, s.center_mm);
          if (!std::holds_alternative<Grip>(grip)) continue;
          auto& made = references[*reference];
          const model::SecondOrderSystem& system = scene_.models()[*reference].physics.model->system();
          if (!made)
            made = std::make_unique<integrators::HapticTrapezoid>(
                system, scene_.dt(), integrators::HapticNewton{.iterations = 200, .tolerance = 1e-12});
          haptic = made.get();
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
