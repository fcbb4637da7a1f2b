// SPDX-License-Identifier: GPL-3.0-or-later
#include "serve/physics_loop.hpp"

#include <pthread.h>
#include <sched.h>
#include <time.h>

#include <algorithm>
#include <cmath>

#include "common/errors.hpp"
#include "common/format.hpp"
#include "common/timer.hpp"
#include "simulation/cuts/cut_event.hpp"

namespace roifem::serve {

namespace {

constexpr std::size_t most_queued_events = 64;
constexpr long slip_after_ticks = 20;

timespec plus_seconds(timespec t, double seconds) {
  const auto ns = static_cast<long long>(std::llround(seconds * 1e9)) + t.tv_nsec;
  t.tv_sec += static_cast<time_t>(ns / 1000000000LL);
  t.tv_nsec = static_cast<long>(ns % 1000000000LL);
  return t;
}

timespec now() {
  timespec t{};
  clock_gettime(CLOCK_MONOTONIC, &t);
  return t;
}

double seconds_between(const timespec& a, const timespec& b) {
  return static_cast<double>(b.tv_sec - a.tv_sec) + 1e-9 * static_cast<double>(b.tv_nsec - a.tv_nsec);
}

}  // namespace

PhysicsLoop::PhysicsLoop(LiveScene& scene, PhysicsSettings settings)
    : scene_(scene), settings_(settings), model_(scene.default_model()) {
  if (!(settings.hand_speed_mm_s > 0))
    throw InputError(format("serve: a hand speed of %g mm/s (it must be positive)", settings.hand_speed_mm_s));
  if (!(settings.reach_mm > 0)) throw InputError(format("serve: a reach of %g mm (it must be positive)", settings.reach_mm));
}

PhysicsLoop::~PhysicsLoop() { stop(); }

void PhysicsLoop::start() {
  if (thread_.joinable()) return;
  running_.store(true);
  thread_ = std::thread([this] { run(); });
}

void PhysicsLoop::stop() {
  running_.store(false);
  if (thread_.joinable()) thread_.join();
}

std::string PhysicsLoop::post(const HandMessage& message) {
  const std::lock_guard lock(inbox_mutex_);
  if (message.kind == HandKind::target) {
    target_ = message;
    target_fresh_ = true;
    return {};
  }
  if (events_.size() >= most_queued_events)
    return "refused: " + std::to_string(most_queued_events) + " picks, releases and switches already wait for the physics";
  events_.push_back(message);
  return {};
}

bool PhysicsLoop::take_snapshot(PhysicsSnapshot& out) {
  const std::lock_guard lock(snapshot_mutex_);
  if (!snapshot_fresh_) return false;
  std::swap(out, snapshot_);
  snapshot_fresh_ = false;
  return true;
}

std::vector<std::string> PhysicsLoop::take_notices() {
  const std::lock_guard lock(notice_mutex_);
  return std::exchange(notices_, {});
}

std::vector<LiveCut> PhysicsLoop::take_cuts() {
  const std::lock_guard lock(notice_mutex_);
  return std::exchange(cuts_, {});
}

void PhysicsLoop::say(std::string notice) {
  pending_notices_.push_back(std::move(notice));
  deliver();
}

void PhysicsLoop::deliver() {
  if (pending_notices_.empty() && pending_cuts_.empty()) return;
  const std::unique_lock lock(notice_mutex_, std::try_to_lock);
  if (!lock.owns_lock()) return;  // the next turn delivers them
  for (auto& n : pending_notices_) notices_.push_back(std::move(n));
  for (auto& c : pending_cuts_) cuts_.push_back(std::move(c));
  pending_notices_.clear();
  pending_cuts_.clear();
}

void PhysicsLoop::take_inbox() {
  HandMessage event;
  bool has_event = false, has_target = false;
  HandMessage target;
  {
    const std::unique_lock lock(inbox_mutex_, std::try_to_lock);
    if (!lock.owns_lock()) return;
    deliver();
    if (target_fresh_) {
      target = target_;
      target_fresh_ = false;
      has_target = true;
    }
    if (!events_.empty()) {
      event = events_.front();
      events_.pop_front();
      has_event = true;
    }
  }
  if (has_event) handle(event);
  if (has_target) {
    hand_sequence_ = std::max(hand_sequence_, target.sequence);
    if (holding_) aim(target.point_mm);
  }
}

void PhysicsLoop::handle(const HandMessage& event) {
  // A pick starts the page's count afresh (a new driver counts from 1).
  hand_sequence_ = event.kind == HandKind::pick ? event.sequence : std::max(hand_sequence_, event.sequence);
  switch (event.kind) {
    case HandKind::pick:
      pick(event);
      break;
    case HandKind::release:
      holding_ = false;
      target_g_ = Vec3::Zero();
      break;
    case HandKind::model:
      if (event.model >= scene_.models().size()) {
        say(format("refused: model %u (there are %zu)", event.model, scene_.models().size()));
        break;
      }
      model_ = event.model;
      attached_ = holding_ = false;
      failure_.clear();
      g_ = target_g_ = force_ = Vec3::Zero();
      state_ = {};
      say("model: " + scene_.models()[model_].name);
      break;
    case HandKind::cut:
      cut(event);
      break;
    case HandKind::whole:
      make_whole();
      break;
    case HandKind::target:
    case HandKind::save:
    case HandKind::compare:
      break;  // not queued: the server's
  }
}

void PhysicsLoop::pick(const HandMessage& event) {
  auto grip = scene_.grip(model_, event.point_mm);
  if (const auto* why = std::get_if<std::string>(&grip)) {
    say("refused pick: " + *why);
    return;
  }
  const Stopwatch clock;
  LiveModel& live = scene_.models()[model_];
  if (live.cuttable())
    for (const int n : std::get<Grip>(grip).nodes)
      if (live.physics.on_cut[static_cast<std::size_t>(n)]) {
        say(
            format("refused pick: node %d there lies on a cut (a tetrahedron at it was removed): the hand holds whole "
                   "tissue, pick beside the cut",
                   n));
        return;
      }
  std::string refactored;
  if (live.physics.haptic_stale) {  // cut between grabs: a fresh factor of the cut model
    live.physics.haptic = std::make_unique<integrators::HapticTrapezoid>(live.physics.model->system(), scene_.dt());
    live.physics.haptic_stale = false;
    refactored = format(" (its factor made afresh after the cuts: %.1f ms)", 1e3 * clock.seconds());
  }
  integrators::HapticTrapezoid& haptic = *live.physics.haptic;
  try {
    haptic.attach(std::get<Grip>(grip).dofs);
  } catch (const Error& e) {
    attached_ = holding_ = false;
    say(std::string("refused pick: ") + e.what());
    return;
  }
  grip_ = std::move(std::get<Grip>(grip));
  state_ = model::State::at_rest(scene_.models()[model_].physics.model->system().size());
  haptic.reset(state_);
  attached_ = holding_ = true;
  failure_.clear();
  g_ = target_g_ = force_ = Vec3::Zero();
  ++grab_;
  samples_.push(sample());
  say(format("grab %u: %zu node(s) at (%.1f, %.1f, %.1f) mm on the %s model, attached in %.1f ms%s", grab_, grip_.nodes.size(),
             grip_.center_mm.x(), grip_.center_mm.y(), grip_.center_mm.z(), scene_.models()[model_].name.c_str(),
             1e3 * clock.seconds(), refactored.c_str()));
}

void PhysicsLoop::make_whole() {
  LiveModel& live = scene_.models()[model_];
  if (!live.cuttable()) {
    say(format("refused: the %s model is not cut by the scalpel: it is whole", live.name.c_str()));
    return;
  }
  const Stopwatch clock;
  attached_ = holding_ = false;  // the grab ends: the next pick starts on the whole model
  g_ = target_g_ = force_ = Vec3::Zero();
  state_ = {};
  try {
    pending_cuts_.push_back({.model = model_, .whole = true, .fresh = scene_.make_whole(model_), .grab = grab_});
  } catch (const Error& e) {
    say(std::string("could not make the model whole again: ") + e.what());
    return;
  }
  say(format("whole again: the %s model built afresh in %.2f s (the other models were never cut)", live.name.c_str(),
             clock.seconds()));
}

void PhysicsLoop::cut(const HandMessage& event) {
  LiveModel& live = scene_.models()[model_];
  const Stopwatch clock;
  const LiveCutResult result =
      live.cut(event.crossed, attached_ ? &state_ : nullptr, attached_ ? grip_.nodes : std::vector<int>{});
  if (!result.taken) {
    say((result.refused ? "refused cut: " : "cut: ") + result.why_not);
    return;
  }
  const simulation::CutEvent& taken = *result.taken;
  if (!result.grab_ended_because.empty()) {
    attached_ = holding_ = false;
    say("the cut's correction failed, the grab ends: " + result.grab_ended_because);
  }
  std::string said =
      format("cut: %zu tetrahedra removed from the %s model %s in %.1f ms", taken.elements.size(), live.name.c_str(),
             attached_ ? format("at t = %.3f s of grab %u", state_.t, grab_).c_str() : "between grabs", 1e3 * clock.seconds());
  if (!taken.orphan_nodes.empty())
    said += format("; %zu node(s) left with no tetrahedron, held at rest", taken.orphan_nodes.size());
  for (const std::string& w : taken.warnings) said += "; " + w;
  pending_cuts_.push_back({.model = model_,
                           .grab = grab_,
                           .during = attached_,
                           .t = attached_ ? state_.t : 0.0,
                           .edge_from_mm = event.point_mm,
                           .edge_to_mm = event.edge_to_mm,
                           .move_mm = event.move_mm,
                           .elements = taken.elements});
  say(said);
}

void PhysicsLoop::aim(const Vec3& point_mm) {
  // Within the brain's box (widened by the reach: a spatula pulls tissue out of it), then within
  // the reach of where it picked.
  const Eigen::AlignedBox3d& box = scene_.box();
  const Vec3 reach = Vec3::Constant(settings_.reach_mm * mm);
  const Vec3 clamped = (point_mm * mm).cwiseMax(box.min() - reach).cwiseMin(box.max() + reach);
  Vec3 g = clamped - grip_.center_mm * mm;
  if (g.norm() > settings_.reach_mm * mm) g *= settings_.reach_mm * mm / g.norm();
  target_g_ = g;
}

Vec3 PhysicsLoop::next_g() const {
  const Vec3 step = target_g_ - g_;
  const double most = settings_.hand_speed_mm_s * mm * scene_.dt();
  return step.norm() <= most ? target_g_ : Vec3(g_ + step * (most / step.norm()));
}

HandSample PhysicsLoop::sample() const {
  return {.grab = grab_,
          .model = model_,
          .center_mm = grip_.center_mm,
          .grip_nodes = grip_.nodes.size(),
          .t = state_.t,
          .g = g_,
          .force = force_};
}

void PhysicsLoop::publish() {
  if (!snapshot_wanted_.load(std::memory_order_acquire)) return;
  const std::unique_lock lock(snapshot_mutex_, std::try_to_lock);
  if (!lock.owns_lock()) return;
  snapshot_.model = model_;
  snapshot_.grab = grab_;
  snapshot_.holding = holding_;
  snapshot_.t = state_.t;
  if (attached_)
    snapshot_.u = state_.u;  // the snapshot's vector keeps its size: no allocation after the first
  else
    snapshot_.u.resize(0);
  snapshot_.force = force_;
  snapshot_.g = g_;
  snapshot_.grip_center_mm = grip_.center_mm;
  snapshot_.grip_nodes = attached_ ? grip_.nodes.size() : 0;
  snapshot_.hand_sequence = hand_sequence_;
  snapshot_.ticks = ticks_;
  const LiveModel& live = scene_.models()[model_];
  snapshot_.newton_iterations = live.nonlinear() && attached_ ? live.physics.haptic->last_iterations() : 0;
  snapshot_.newton_residual = live.nonlinear() && attached_ ? live.physics.haptic->last_residual() : 0;
  snapshot_.failure = failure_;
  snapshot_fresh_ = true;
  snapshot_wanted_.store(false, std::memory_order_release);
}

void PhysicsLoop::run() {
  // The real-time class when the process may take it and another core is left for the rest (the
  // page's frames, the browser): the ticks then run before any ordinary thread. It sleeps between
  // ticks, so it takes its tick's share of one core.
  if (std::thread::hardware_concurrency() >= 2) {
    sched_param priority{};
    priority.sched_priority = 10;
    const int refused = pthread_setschedparam(pthread_self(), SCHED_FIFO, &priority);
    say(refused == 0 ? "physics thread: real-time priority (SCHED_FIFO 10)"
                     : "physics thread: ordinary priority (no permission for the real-time class)");
  }
  const double dt = scene_.dt();
  timespec start = now();
  long k = 0;  // ticks since `start`
  while (running_.load(std::memory_order_relaxed)) {
    take_inbox();
    if (!attached_) {  // idle: look at the inbox every tick's length
      publish();
      start = plus_seconds(now(), dt);
      k = 0;
      timespec wake = start;
      clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &wake, nullptr);
      continue;
    }
    try {
      const Stopwatch clock;
      g_ = next_g();
      force_ = scene_.models()[model_].physics.haptic->tick(g_, state_);
      tick_seconds_.push(static_cast<float>(clock.seconds()));
    } catch (const Error& e) {
      failure_ = format("the tick at t = %.4f s failed, the grab ended: %s", state_.t + dt, e.what());
      say(failure_);
      attached_ = holding_ = false;
      force_ = Vec3::Zero();
      continue;
    }
    ++ticks_;
    samples_.push(sample());
    publish();
    ++k;
    timespec due = plus_seconds(start, dt * static_cast<double>(k));
    const timespec current = now();
    if (seconds_between(due, current) > slip_after_ticks * dt) {  // far behind: the clock slips
      slips_.fetch_add(1, std::memory_order_relaxed);
      // and the thread rests a tick: at real-time priority it must never hold a core for good.
      start = plus_seconds(current, dt);
      k = 0;
      clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &start, nullptr);
      continue;
    }
    clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &due, nullptr);
  }
}

}  // namespace roifem::serve
