// SPDX-License-Identifier: GPL-3.0-or-later
// A grab on the live loop, replayed by `roifem run` (simulation::run_scenario): the same force.
#include <gtest/gtest.h>

#include <chrono>
#include <sstream>
#include <stdexcept>
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

/// Waits until the loop has ticked `n` times more: the hand's path is laid out in ticks, so that a
/// loaded machine (ctest -j2) slows the loop, not the path.
void wait_ticks(PhysicsLoop& loop, long n) {
  PhysicsSnapshot s;
  long start = -1;
  for (int wait = 0; wait < 60000; ++wait) {
    loop.request_snapshot();
    std::this_thread::sleep_for(1ms);
    if (!loop.take_snapshot(s)) continue;
    if (start < 0)
      start = s.ticks;
    else if (s.ticks >= start + n)
      return;
  }
  throw std::runtime_error("the physics loop did not tick for a minute");
}

/// Drives a grab on model k through the threaded loop: pick, a hand path of `steps` targets posted
/// 20 ticks apart, a release and the ease back (60 ticks). Returns its samples.
GrabRecord live_grab(LiveScene& scene, std::size_t k, const Vec3& point_mm, int steps = 12) {
  PhysicsLoop loop(scene, {.hand_speed_mm_s = 40, .reach_mm = 20});
  loop.start();
  std::uint32_t sequence = 0;
  loop.post({.kind = HandKind::model, .sequence = ++sequence, .point_mm = Vec3::Zero(), .model = static_cast<std::uint32_t>(k)});
  loop.post({.kind = HandKind::pick, .sequence = ++sequence, .point_mm = point_mm, .model = 0});
  for (int step = 1; step <= steps; ++step) {  // 0.2 mm out and a little sideways per step
    loop.post({.kind = HandKind::target,
               .sequence = ++sequence,
               .point_mm = point_mm + Vec3(0.1 * step, -0.15 * step, 0.05 * step * (step % 3)),
               .model = 0});
    wait_ticks(loop, 20);
  }
  loop.post({.kind = HandKind::release, .sequence = ++sequence, .point_mm = Vec3::Zero(), .model = 0});
  wait_ticks(loop, 60);
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

/// The force of `roifem run`'s replay of `grab` written as model `k`'s, per tick (N).
std::vector<Vec3> replayed_force(const LiveScene& scene, GrabRecord grab, std::size_t k) {
  grab.model = k;
  return test::replayed_force(scene, grab);
}

double largest_norm(const std::vector<Vec3>& forces) {
  double largest = 0;
  for (const Vec3& f : forces) largest = std::max(largest, f.norm());
  return largest;
}

/// Compare's reference forces on `grab`, one per tick after its start (fewer if Compare failed or
/// fell behind for `wait` seconds: the caller checks the count).
std::vector<CompareSample> compared_forces(LiveScene& scene, const GrabRecord& grab, double wait) {
  CompareLoop compare(scene);
  compare.start();
  for (const HandSample& s : grab.samples) EXPECT_TRUE(compare.feed(s));
  std::vector<CompareSample> compared;
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(wait);
  while (compared.size() + 1 < grab.samples.size() && std::chrono::steady_clock::now() < until) {
    compare.drain(compared);
    std::this_thread::sleep_for(5ms);
  }
  compare.stop();
  EXPECT_TRUE(compare.failure().empty()) << compare.failure();
  return compared;
}

TEST(ServeReplay, AGrabReplayedByRoifemRunFeelsTheLiveForceOnEveryModel) {
  // The default models (the linear ones and the hybrid ROI); the neo-Hookean model's ticks iterated
  // to convergence, as roifem run's Newton solves every step.
  const auto scene = test::paper_scene({}, {.iterations = 200, .tolerance = 1e-12});
  ASSERT_EQ(scene->models().back().name, "static-neo-hookean");
  const Vec3 point = test::pickable_point(*scene);
  for (std::size_t k = 0; k < scene->models().size(); ++k) {
    if (scene->models()[k].cuttable()) continue;  // static uncut (cut_test.cpp cuts it)
    SCOPED_TRACE(scene->models()[k].name);
    const bool nonlinear = scene->models()[k].nonlinear();
    const GrabRecord grab = live_grab(*scene, k, point, nonlinear ? 6 : 12);  // roifem run's Newton: a shorter grab
    ASSERT_EQ(grab.model, k);
    ASSERT_GT(grab.samples.size(), nonlinear ? 170U : 290U);  // 180 or 300 ticks
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
    EXPECT_GT(tool_moved, nonlinear ? 0.9e-3 : 1.5e-3);  // the hand went out about 1 or 2 mm
    EXPECT_GT(largest, 1e-3);                            // and felt at least a millinewton
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
  const std::vector<CompareSample> compared = compared_forces(*scene, grab, 5);
  ASSERT_EQ(compared.size() + 1, grab.samples.size());
  // The same hand replayed on the full model by roifem run.
  const auto full = replayed_force(*scene, grab, 0);
  ASSERT_EQ(full.size(), grab.samples.size());
  double largest = 0, difference = 0, roi_error = 0;
  for (std::size_t i = 0; i < compared.size(); ++i) {
    const Vec3& replayed = full[i + 1];
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

TEST(ServeCompare, TheHybridRoiIsComparedWithTheFullNeoHookeanModelAndFeelsTheLaw) {
  // The hybrid ROI live at the default budget (2 modified-Newton iterations a tick), Compare's
  // reference the whole brain neo-Hookean (converged every tick); each against roifem run's replay.
  const auto scene = test::paper_scene({"full-neo-hookean", "static-neo-hookean", "static"});
  const std::size_t hybrid = 1, linear = 2;
  ASSERT_EQ(scene->reference_of(hybrid), std::optional<std::size_t>(0));
  ASSERT_EQ(scene->reference_of(linear), std::nullopt);  // no linear full model prepared
  ASSERT_EQ(scene->reference_of(0), std::nullopt);
  const Vec3 point = test::pickable_point(*scene);
  const GrabRecord grab = live_grab(*scene, hybrid, point, 6);  // 1.2 mm out
  const std::vector<CompareSample> compared = compared_forces(*scene, grab, 20);
  ASSERT_EQ(compared.size() + 1, grab.samples.size());
  // The full neo-Hookean replay (Newton on 2,400 unknowns, 40 ms a step) over the grab's first 60 ticks.
  GrabRecord start = grab;
  start.samples.resize(std::min<std::size_t>(61, grab.samples.size()));
  const auto full = replayed_force(*scene, start, 0), converged = replayed_force(*scene, grab, hybrid),
             linear_force = replayed_force(*scene, grab, linear);
  ASSERT_EQ(full.size(), start.samples.size());
  ASSERT_EQ(converged.size(), grab.samples.size());
  double compare_gap = 0, budget_gap = 0, law = 0;
  for (std::size_t i = 1; i < full.size(); ++i) compare_gap = std::max(compare_gap, (compared[i - 1].force - full[i]).norm());
  for (std::size_t i = 1; i < grab.samples.size(); ++i) {
    budget_gap = std::max(budget_gap, (grab.samples[i].force - converged[i]).norm());
    law = std::max(law, (converged[i] - linear_force[i]).norm());
  }
  const double largest = largest_norm(converged);
  EXPECT_GT(largest, 1e-3);
  // Compare's converged reference is roifem run's full neo-Hookean model on the same hand.
  EXPECT_LT(compare_gap, 1e-9 * largest_norm(full));
  // The live budget leaves a small share of the law's correction unresolved...
  EXPECT_LT(budget_gap, 2e-2 * largest);
  // ... and the law changes the force at 1.2 mm on the paper's soft brain.
  EXPECT_GT(law, 10 * budget_gap);
  std::printf(
      "[ figures ] hybrid ROI, %zu ticks, largest force %.4g N: live budget of 2 within %.2e of the converged replay; "
      "linear static differs by %.2e; Compare (full neo-Hookean) within %.2e of its replay\n",
      grab.samples.size() - 1, largest, budget_gap / largest, law / largest, compare_gap / largest_norm(full));
}

TEST(ServeModels, TheDefaultsAndTheNamesStateEachModelsLaw) {
  std::ostringstream log;
  const auto names = [](const LiveScene& scene) {
    std::vector<std::string> out;
    for (const LiveModel& m : scene.models()) out.push_back(m.name + (m.nonlinear() ? " (nonlinear)" : ""));
    return out;
  };
  EXPECT_EQ(names(*test::paper_scene()), (std::vector<std::string>{"full", "static", "guyan", "craig-bampton-10", "static-cut",
                                                                   "static-neo-hookean (nonlinear)"}));
  const LiveScene neo(scenario::read_scenario(ROIFEM_SCENARIO_DIR "/paper-spatulas-setup1-neo-hookean.toml"), 1000, 5.0, {}, log);
  EXPECT_EQ(names(neo), (std::vector<std::string>{"full-neo-hookean (nonlinear)", "static-neo-hookean (nonlinear)", "full",
                                                  "static", "guyan", "craig-bampton-10", "static-cut"}));
  EXPECT_EQ(neo.reference_of(6), std::nullopt);  // a cut model: the full model is whole
  EXPECT_EQ(neo.reference_of(1), std::optional<std::size_t>(0));
  EXPECT_EQ(neo.reference_of(3), std::optional<std::size_t>(2));
  EXPECT_EQ(neo.scenario_of(3).material.model, fem::MaterialModel::linear);
  EXPECT_EQ(neo.scenario_of(1).material.model, fem::MaterialModel::neo_hookean);
  const auto refusal = [&](std::vector<std::string> models, integrators::HapticNewton newton = {}) {
    try {
      LiveScene scene(scenario::read_scenario(ROIFEM_SCENARIO_DIR "/paper-setup1.toml"), 1000, 5.0, models, log, newton);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(refusal({"guyan-neo-hookean"}).find("guyan-neo-hookean: a reduction by modes"), std::string::npos);
  EXPECT_NE(refusal({"guyan-neo-hookean"}).find("static-neo-hookean"), std::string::npos);
  EXPECT_NE(refusal({"neo-hookean"}).find("'neo-hookean' is neither full nor a reduction"), std::string::npos);
  for (const char* cut : {"guyan-cut", "craig-bampton-10-cut", "static-neo-hookean-cut"})
    EXPECT_NE(refusal({cut}).find(std::string(cut) + ": the page's scalpel cuts the linear full model (full-cut) or static "
                                                     "condensation (static-cut)"),
              std::string::npos)
        << cut;
  EXPECT_EQ(refusal({"full-cut", "static-cut"}), "accepted");
  EXPECT_NE(refusal({"static-neo-hookean"}, {.iterations = 0, .tolerance = 0}).find("0 Newton iterations"), std::string::npos);
}

TEST(ServeModels, TheHapticRateAndBudgetComeFromTheCommandLineElseTheScenarioElseTheDefaults) {
  scenario::Scenario sc = scenario::read_scenario(ROIFEM_SCENARIO_DIR "/paper-setup1.toml");
  EXPECT_EQ(haptic_settings(sc, std::nullopt, std::nullopt, 0).rate_hz, 1000);
  EXPECT_EQ(haptic_settings(sc, std::nullopt, std::nullopt, 0).newton.iterations, 2);
  sc.haptic_rate_hz = 500;
  sc.haptic_newton_iterations = 3;
  const HapticSettings from_file = haptic_settings(sc, std::nullopt, std::nullopt, 0);
  EXPECT_EQ(from_file.rate_hz, 500);
  EXPECT_EQ(from_file.newton.iterations, 3);
  const HapticSettings given = haptic_settings(sc, 2000.0, 5, 1e-9);
  EXPECT_EQ(given.rate_hz, 2000);
  EXPECT_EQ(given.newton.iterations, 5);
  EXPECT_EQ(given.newton.tolerance, 1e-9);
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
