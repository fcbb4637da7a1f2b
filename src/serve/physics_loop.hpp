// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// The haptic loop of `roifem serve`, in its own thread: one tick of the current model's
/// HapticTrapezoid every dt of wall time (1 ms at 1 kHz), paced by an absolute sleep.
///
/// A grab: a pick attaches the hand to the footprint it names (LiveScene::grip) and starts the
/// model from rest at t = 0, so that every grab is a run `roifem run` replays (hand_recording.hpp).
/// The tool then follows the page's target at most `hand_speed` per second (a mouse jumps; a
/// hand does not), within `reach` of where it picked and within the brain's box. A release (or
/// the driver's disconnection) eases the tool back to where it picked, at the same speed, and
/// holds it there. Switching the model ends the grab; the next pick starts one on that model.
///
/// Nothing here waits on another thread: the page's messages are taken with try_lock at the
/// start of a tick (a busy inbox waits for the next tick), the state is copied for the display
/// only when asked and only with try_lock, and the tick's durations and the hand's samples leave
/// through lock-free rings. A pick's attach (3m solves) and a cut run between two ticks and are
/// reported apart from them.
#include <atomic>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "serve/hand_message.hpp"
#include "serve/live_scene.hpp"
#include "serve/spsc_ring.hpp"

namespace roifem::serve {

struct PhysicsSettings {
  double hand_speed_mm_s = 50;  ///< the tool's fastest motion towards the page's target
  double reach_mm = 20;         ///< the farthest the tool goes from where it picked
};

/// One tick of a grab: the hand's place and the force it felt.
struct HandSample {
  std::uint32_t grab = 0;
  std::size_t model = 0;  ///< the grab's model, footprint centre and size
  Vec3 center_mm = Vec3::Zero();
  std::size_t grip_nodes = 0;
  double t = 0;               ///< s, from the grab's start
  Vec3 g = Vec3::Zero();      ///< m: the tool's displacement
  Vec3 force = Vec3::Zero();  ///< N: on the tissue (the surgeon feels its opposite)
};

/// A scalpel's stroke the loop took on a cut model (LiveModel::cuts), between two ticks; or the
/// model made whole again (`whole`: between grabs, with the fresh model for the display).
struct LiveCut {
  std::size_t model = 0;
  bool whole = false;
  std::shared_ptr<simulation::ScenarioModel> fresh;  ///< whole: the model as made again
  std::uint32_t grab = 0;                            ///< the loop's last grab when it was taken
  bool during = false;  ///< during that grab (on this model), after its tick at t; else between grabs
  double t = 0;         ///< s: the grab's state time when taken (0 between grabs)
  Vec3 edge_from_mm = Vec3::Zero(), edge_to_mm = Vec3::Zero(), move_mm = Vec3::Zero();  ///< the stroke, as sent
  std::vector<Index> elements;                                                          ///< the tetrahedra removed, ascending
};

/// The loop's state as the display last asked for it.
struct PhysicsSnapshot {
  std::size_t model = 0;
  std::uint32_t grab = 0;  ///< 0: none since the model was chosen
  bool holding = false;    ///< the hand follows the page (false: easing back, or no grab)
  double t = 0;
  Vector u;  ///< the model's unknowns (empty: at rest, no grab)
  Vec3 force = Vec3::Zero(), g = Vec3::Zero();
  Vec3 grip_center_mm = Vec3::Zero();
  std::size_t grip_nodes = 0;
  std::uint32_t hand_sequence = 0;  ///< the last page message applied
  long ticks = 0;                   ///< since the loop started
  /// A neo-Hookean model's last tick: its Newton iterations and the residual they left (relative
  /// to the law's correction; integrators/haptic_trapezoid.hpp). 0 on a linear model.
  int newton_iterations = 0;
  double newton_residual = 0;
  /// Why this grab's last tick failed (empty: none): the page shows it where the force was, not a
  /// frozen force beside "0 Newton iterations". Cleared by the next pick or model.
  std::string failure;
};

class PhysicsLoop {
 public:
  PhysicsLoop(LiveScene& scene, PhysicsSettings settings);
  ~PhysicsLoop();
  PhysicsLoop(const PhysicsLoop&) = delete;
  PhysicsLoop& operator=(const PhysicsLoop&) = delete;

  /// Starts the thread (once).
  void start();
  /// Stops it and waits for the tick in progress.
  void stop();

  /// From any thread: a target replaces the one before; a pick, a release or a model switch
  /// waits in a queue (64 at most: beyond, refused with the reason returned; empty: taken).
  std::string post(const HandMessage& message);
  /// Asks for a copy of the state at the next tick's end (or the next idle turn).
  void request_snapshot() { snapshot_wanted_.store(true, std::memory_order_release); }
  /// The latest copy, if one came since the last call.
  bool take_snapshot(PhysicsSnapshot& out);
  /// Tick durations (s) and the hand's samples since the last call (display thread alone).
  std::size_t drain_tick_seconds(std::vector<float>& out) { return tick_seconds_.drain(out); }
  std::size_t drain_samples(std::vector<HandSample>& out) { return samples_.drain(out); }
  /// What the loop said since the last call (a refused pick, an attach's time), for log and page.
  std::vector<std::string> take_notices();
  /// The cuts the loop took since the last call, in order.
  std::vector<LiveCut> take_cuts();
  /// Times the loop fell more than 20 ticks behind and let its clock slip.
  long slips() const { return slips_.load(std::memory_order_relaxed); }

 private:
  LiveScene& scene_;
  PhysicsSettings settings_;
  std::thread thread_;
  std::atomic<bool> running_{false};

  // The inbox (the network's side holds the lock briefly; the loop only tries it).
  std::mutex inbox_mutex_;
  bool target_fresh_ = false;
  HandMessage target_;
  std::deque<HandMessage> events_;

  // The outbox.
  std::atomic<bool> snapshot_wanted_{false};
  std::mutex snapshot_mutex_;
  bool snapshot_fresh_ = false;
  PhysicsSnapshot snapshot_;
  SpscRing<float> tick_seconds_{1 << 15};
  SpscRing<HandSample> samples_{1 << 16};
  std::mutex notice_mutex_;
  std::vector<std::string> notices_;
  std::vector<LiveCut> cuts_;
  std::atomic<long> slips_{0};

  // The loop's own (its thread alone).
  std::size_t model_ = 0;
  std::uint32_t grab_ = 0, hand_sequence_ = 0;
  bool attached_ = false, holding_ = false;
  std::string failure_;  ///< PhysicsSnapshot::failure
  Grip grip_;
  model::State state_;
  Vec3 g_ = Vec3::Zero(), target_g_ = Vec3::Zero(), force_ = Vec3::Zero();
  long ticks_ = 0;
  std::vector<std::string> pending_notices_;
  std::vector<LiveCut> pending_cuts_;

  void run();
  /// Takes what the page sent (try_lock); one queued event per turn.
  void take_inbox();
  void handle(const HandMessage& event);
  void pick(const HandMessage& event);
  /// A scalpel's stroke on the current model (a cut model): the tetrahedra it crosses that are
  /// still there removed between two ticks (taken by the haptic loop's correction during a grab,
  /// by a fresh factor at the next pick between grabs), or refused with the reason: a model that
  /// is not cut, a tetrahedron at the static part or at the hand's nodes, nothing left to move.
  void cut(const HandMessage& event);
  /// The current model made whole again (a cut model: built afresh, the grab ended), or refused.
  void make_whole();
  void aim(const Vec3& point_mm);
  /// The tool's next displacement: towards the target by at most hand_speed dt.
  Vec3 next_g() const;
  void publish();
  HandSample sample() const;
  void say(std::string notice);
  /// Hands the notices and cuts waiting to the display (try_lock: the next turn when busy).
  void deliver();
};

}  // namespace roifem::serve
