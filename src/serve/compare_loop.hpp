// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// "Compare": the reference model (the full dynamic model with the live model's law:
/// LiveScene::reference_of) on the hand's path, in a thread of its own, behind the live loop as far
/// as the machine makes it. It takes the live loop's samples (the tool's displacement per tick,
/// from each grab's start) and ticks its own haptic loop (its own factor of the reference model:
/// the live loop may tick that model too) with the same grip and the same displacements, so that
/// its force at each tick is what the full model would have felt on the same hand. A neo-Hookean
/// reference is solved to convergence every tick (modified Newton to 1e-12 of the law's
/// correction), whatever the live loop's budget. The page plots the live model's force error
/// against it.
/// The thread runs at ordinary priority and sleeps a millisecond whenever it has caught up.
#include <atomic>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "serve/live_scene.hpp"
#include "serve/physics_loop.hpp"
#include "serve/spsc_ring.hpp"

namespace roifem::serve {

struct CompareSample {
  std::uint32_t grab = 0;
  double t = 0;
  Vec3 force = Vec3::Zero();  ///< N, the reference model's
};

class CompareLoop {
 public:
  /// Factors its own haptic loop of each reference in the thread, when a grab first needs it.
  explicit CompareLoop(LiveScene& scene);
  ~CompareLoop();
  CompareLoop(const CompareLoop&) = delete;
  CompareLoop& operator=(const CompareLoop&) = delete;

  void start();
  void stop();
  /// The live loop's samples, in order (one thread feeds). False when the ring is full (the
  /// reference fell more than 65,536 ticks behind: the comparison of that grab stops).
  bool feed(const HandSample& sample) { return samples_.push(sample); }
  std::size_t drain(std::vector<CompareSample>& out) { return results_.drain(out); }
  /// Why the reference stopped comparing (empty: it did not), for the log.
  std::string failure() const;

 private:
  LiveScene& scene_;
  std::thread thread_;
  std::atomic<bool> running_{false};
  SpscRing<HandSample> samples_{1 << 16};
  SpscRing<CompareSample> results_{1 << 16};
  mutable std::mutex failure_mutex_;
  std::string failure_;

  void run();
};

}  // namespace roifem::serve
