// SPDX-License-Identifier: GPL-3.0-or-later
// A grab on the live loop, replayed by `roifem run` (simulation::run_scenario): the same force.
#include <gtest/gtest.h>

#include <chrono>
#include <sstream>
#include <thread>

#include "common/errors.hpp"
#include "h5_read.hpp"
#include "serve/compare_loop.hpp"
#include "serve/hand_recording.hpp"
#include "serve/physics_loop.hpp"
#include "serve_test_support.hpp"
#include "simulation/scenario_run.hpp"
#include "test_support.hpp"

namespace roifem::serve {
namespace {

using namespace std::chrono_literals;

/// Drives a grab on model k through the threaded loop: pick, a hand path of targets posted in
/// real time, a release and the ease back. Returns its samples.
GrabRecord live_grab(LiveScene& scene, std::size_t k, const Vec3& point_mm) {
  PhysicsLoop loop(scene, {.hand_speed_mm_s = 40, .reach_mm = 20});
  loop.start();
  std::uint32_t sequence = 0;
  loop.post({.kind = HandKind::model, .sequence = ++sequence, .point_mm = Vec3::Zero(), .model = static_cast<std::uint32_t>(k)});
  loop.post({.kind = HandKind::pick, .sequence = ++sequence, .point_mm = point_mm, .model = 0});
  for (int step = 1; step <= 12; ++step) {  // 2 mm out and a little sideways over 0.24 s
    loop.post({.kind = HandKind::target,
               .sequence = ++sequence,
               .point_mm = point_mm + Vec3(0.1 * step, -0.15 * step, 0.05 * step * (step % 3)),
               .model = 0});
    std::this_thread::sleep_for(20ms);
  }
  loop.post({.kind = HandKind::release, .sequence = ++sequence, .point_mm = Vec3::Zero(), .model = 0});
  std::this_thread::sleep_for(60ms);
  loop.stop();
  std::vector<HandSample> samples;
  loop.drain_samples(samples);
  GrabRecord grab;
  for (const HandSample& s : samples) {
    if (s.grab != grab.grab)
      grab = {.grab = s.grab, .model = s.model, .center_mm = s.center_mm, .grip_nodes = s.grip_nodes, .samples = {}};
    grab.samples.push_back(s);
  }
  return grab;
}

TEST(ServeReplay, AGrabReplayedByRoifemRunFeelsTheLiveForceOnEveryModel) {
  const auto scene = test::paper_scene();
  const Vec3 point = test::pickable_point(*scene);
  for (std::size_t k = 0; k < scene->models().size(); ++k) {
    SCOPED_TRACE(scene->models()[k].name);
    const GrabRecord grab = live_grab(*scene, k, point);
    ASSERT_EQ(grab.model, k);
    ASSERT_GT(grab.samples.size(), 100U);  // about 300 ticks at 1 kHz
    roifem::test::TempDir dir;
    const auto toml = write_replay(*scene, grab, dir.path(), "grab");
    std::ostringstream log;
    const auto summary = simulation::run_scenario(scenario::read_scenario(toml), dir / "replay", log);
    ASSERT_EQ(summary.steps + 1, static_cast<long>(grab.samples.size()));
    const auto force = roifem::test::read_h5(dir / "replay/results.h5", "tools/hand/force_N");
    const auto time = roifem::test::read_h5(dir / "replay/results.h5", "time_s");
    ASSERT_EQ(force.size(), 3 * grab.samples.size());
    double largest = 0, difference = 0, tool_moved = 0;
    for (std::size_t i = 1; i < grab.samples.size(); ++i) {
      const HandSample& s = grab.samples[i];
      EXPECT_NEAR(time[i], s.t, 1e-12);
      const Vec3 replayed(force[3 * i], force[3 * i + 1], force[3 * i + 2]);
      largest = std::max(largest, s.force.norm());
      difference = std::max(difference, (replayed - s.force).norm());
      tool_moved = std::max(tool_moved, s.g.norm());
    }
    EXPECT_GT(tool_moved, 1.5e-3);  // the hand went out about 2 mm
    EXPECT_GT(largest, 1e-3);       // and felt at least a millinewton
    EXPECT_LT(difference, 1e-9 * largest) << "largest force " << largest << " N";
    std::printf("[ figures ] %-18s %zu ticks, largest force %.4g N, replayed within %.2e of it\n",
                scene->models()[k].name.c_str(), grab.samples.size() - 1, largest, difference / largest);
  }
}

TEST(ServeCompare, TheFullModelOnTheLiveHandFeelsWhatRoifemRunsFullReplayFeels) {
  const auto scene = test::paper_scene();
  const Vec3 point = test::pickable_point(*scene);
  const GrabRecord grab = live_grab(*scene, 1, point);  // on the static model
  ASSERT_EQ(scene->models()[1].name, "static");
  CompareLoop compare(*scene, 0);
  compare.start();
  for (const HandSample& s : grab.samples) ASSERT_TRUE(compare.feed(s));
  std::vector<CompareSample> compared;
  for (int wait = 0; wait < 1000 && compared.size() + 1 < grab.samples.size(); ++wait) {
    compare.drain(compared);
    std::this_thread::sleep_for(5ms);
  }
  compare.stop();
  ASSERT_TRUE(compare.failure().empty()) << compare.failure();
  ASSERT_EQ(compared.size() + 1, grab.samples.size());
  // The same hand replayed on the full model by roifem run: the grab written as the full model's.
  GrabRecord on_full = grab;
  on_full.model = 0;
  roifem::test::TempDir dir;
  const auto toml = write_replay(*scene, on_full, dir.path(), "full");
  std::ostringstream log;
  simulation::run_scenario(scenario::read_scenario(toml), dir / "replay", log);
  const auto force = roifem::test::read_h5(dir / "replay/results.h5", "tools/hand/force_N");
  double largest = 0, difference = 0, roi_error = 0;
  for (std::size_t i = 0; i < compared.size(); ++i) {
    const Vec3 replayed(force[3 * (i + 1)], force[3 * (i + 1) + 1], force[3 * (i + 1) + 2]);
    EXPECT_EQ(compared[i].grab, grab.grab);
    EXPECT_NEAR(compared[i].t, grab.samples[i + 1].t, 1e-12);
    largest = std::max(largest, replayed.norm());
    difference = std::max(difference, (compared[i].force - replayed).norm());
    roi_error = std::max(roi_error, (grab.samples[i + 1].force - replayed).norm());
  }
  EXPECT_LT(difference, 1e-9 * largest);
  // The static condensation's force differs from the full model's (the reduction error the page
  // plots), but not by much on the paper's ROI.
  EXPECT_GT(roi_error, 1e-6 * largest);
  EXPECT_LT(roi_error, 0.5 * largest);
  std::printf("[ figures ] compare: the full model's force %.4g N at most, replayed within %.2e; static's error %.3g of it\n",
              largest, difference / largest, roi_error / largest);
}

TEST(ServeReplay, AReplayNeedsTicks) {
  const auto scene = test::paper_scene();
  roifem::test::TempDir dir;
  GrabRecord empty{.grab = 7, .model = 0, .center_mm = Vec3::Zero(), .grip_nodes = 3, .samples = {HandSample{}}};
  EXPECT_THROW(write_replay(*scene, empty, dir.path(), "grab"), InputError);
  EXPECT_FALSE(std::filesystem::exists(dir / "grab.toml"));
}

}  // namespace
}  // namespace roifem::serve
