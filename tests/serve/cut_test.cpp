// SPDX-License-Identifier: GPL-3.0-or-later
// The page's scalpel on a cut model: strokes taken by the live loop (between grabs, and during one
// by the haptic loop's correction), replayed by `roifem run` as [[cut]] tables; the refusals; the
// surface the display draws after a cut.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <map>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "h5_read.hpp"
#include "serve/hand_recording.hpp"
#include "serve/physics_loop.hpp"
#include "serve/scalpel.hpp"
#include "serve_test_support.hpp"
#include "simulation/scenario_run.hpp"
#include "test_support.hpp"

namespace roifem::serve {
namespace {

using namespace std::chrono_literals;

/// The loop's snapshot once it has ticked (or idled) `n` turns more.
PhysicsSnapshot wait_turns(PhysicsLoop& loop, long n) {
  PhysicsSnapshot s;
  for (int turn = 0; turn < n; ++turn) {
    bool fresh = false;
    for (int wait = 0; !fresh && wait < 60000; ++wait) {
      loop.request_snapshot();
      std::this_thread::sleep_for(1ms);
      fresh = loop.take_snapshot(s);
    }
    if (!fresh) throw std::runtime_error("the physics loop did not turn for a minute");
  }
  return s;
}

struct CutGrab {
  GrabRecord grab;
  std::vector<LiveCut> cuts;
  std::vector<std::string> notices;
};

/// On model k: `before` cut between grabs, then a grab at `point_mm` (12 targets 20 ticks apart),
/// `during` cut after its sixth target, a release and the ease back.
CutGrab cut_grab(LiveScene& scene, std::size_t k, const Vec3& point_mm, const HandMessage& before, const HandMessage& during) {
  PhysicsLoop loop(scene, {.hand_speed_mm_s = 40, .reach_mm = 20});
  loop.start();
  std::uint32_t sequence = 0;
  loop.post({.kind = HandKind::model, .sequence = ++sequence, .point_mm = Vec3::Zero(), .model = static_cast<std::uint32_t>(k)});
  loop.post(before);
  wait_turns(loop, 3);
  loop.post({.kind = HandKind::pick, .sequence = ++sequence, .point_mm = point_mm, .model = 0});
  for (int step = 1; step <= 12; ++step) {
    loop.post({.kind = HandKind::target,
               .sequence = ++sequence,
               .point_mm = point_mm + Vec3(0.1 * step, -0.15 * step, 0.05 * step * (step % 3)),
               .model = 0});
    if (step == 6) loop.post(during);
    wait_turns(loop, 20);
  }
  loop.post({.kind = HandKind::release, .sequence = ++sequence, .point_mm = Vec3::Zero(), .model = 0});
  wait_turns(loop, 60);
  loop.stop();
  CutGrab out;
  std::vector<HandSample> samples;
  loop.drain_samples(samples);
  for (const HandSample& s : samples) {
    if (s.grab != out.grab.grab)
      out.grab = {
          .grab = s.grab, .model = s.model, .center_mm = s.center_mm, .grip_nodes = s.grip_nodes, .samples = {}, .cuts = {}};
    out.grab.samples.push_back(s);
  }
  out.cuts = loop.take_cuts();
  out.notices = loop.take_notices();
  return out;
}

/// `roifem run`'s replay of the grab with `cuts`: its force per tick (N).
std::vector<Vec3> replayed(const LiveScene& scene, GrabRecord grab, const std::vector<LiveCut>& cuts) {
  grab.cuts = cuts;
  return test::replayed_force(scene, grab);
}

std::string joined(const std::vector<std::string>& lines) {
  std::string all;
  for (const auto& l : lines) all += l + "\n";
  return all;
}

TEST(ServeCut, StrokesBetweenGrabsAndDuringOneAreReplayedByRoifemRunWithTheLiveForce) {
  const auto scene = test::paper_scene({"static", "static-cut"});
  ASSERT_TRUE(scene->models()[1].cuttable());
  ASSERT_FALSE(scene->models()[0].cuttable());
  const Vec3 point = test::pickable_point(*scene);
  const HandMessage before = test::stroke_beside(*scene, 1, point, 6.0);
  // The second stroke: the first one's, 2 mm deeper and moved on, so that it removes more.
  const HandMessage during =
      test::stroke(*scene, before.point_mm - Vec3(0, 0, 2), before.edge_to_mm - Vec3(0, 0, 2), before.move_mm * 1.5);
  const CutGrab live = cut_grab(*scene, 1, point, before, during);
  ASSERT_EQ(live.cuts.size(), 2U) << joined(live.notices);
  EXPECT_FALSE(live.cuts[0].during);
  EXPECT_TRUE(live.cuts[1].during);
  EXPECT_EQ(live.cuts[1].grab, live.grab.grab);
  EXPECT_GT(live.cuts[1].t, 0.1);
  EXPECT_FALSE(live.cuts[1].elements.empty()) << "the second stroke removed nothing more";
  // No tetrahedron twice; each one the server found its stroke crossing.
  for (const Index e : live.cuts[1].elements) {
    EXPECT_FALSE(std::binary_search(live.cuts[0].elements.begin(), live.cuts[0].elements.end(), e));
    EXPECT_TRUE(std::binary_search(during.crossed.begin(), during.crossed.end(), e));
  }
  ASSERT_GT(live.grab.samples.size(), 290U);

  const std::vector<Vec3> with_cuts = replayed(*scene, live.grab, live.cuts);
  const std::vector<Vec3> first_only = replayed(*scene, live.grab, {live.cuts[0]});
  const std::vector<Vec3> uncut = replayed(*scene, live.grab, {});
  ASSERT_EQ(with_cuts.size(), live.grab.samples.size());
  double largest = 0, difference = 0, second_cut = 0, any_cut = 0;
  for (std::size_t i = 1; i < live.grab.samples.size(); ++i) {
    const Vec3& f = live.grab.samples[i].force;
    largest = std::max(largest, f.norm());
    difference = std::max(difference, (with_cuts[i] - f).norm());
    second_cut = std::max(second_cut, (first_only[i] - f).norm());
    any_cut = std::max(any_cut, (uncut[i] - f).norm());
    // Before the second cut the first alone replays it.
    if (live.grab.samples[i].t <= live.cuts[1].t + 1e-12) {
      EXPECT_LT((first_only[i] - f).norm(), 1e-9 * largest + 1e-15);
    }
  }
  EXPECT_GT(largest, 1e-3);
  EXPECT_LT(difference, 1e-9 * largest) << "largest force " << largest << " N";
  // Each cut is felt: the replay without it is a different force, by far more than round-off.
  EXPECT_GT(second_cut, 1e-6 * largest);
  EXPECT_GT(any_cut, 1e-4 * largest);
  std::printf(
      "[ figures ] scalpel: %zu then %zu tetrahedra removed (between grabs, at t = %.3f s of the grab); largest force "
      "%.4g N, replayed within %.2e; the force without the second cut differs by %.2e, without either by %.2e\n",
      live.cuts[0].elements.size(), live.cuts[1].elements.size(), live.cuts[1].t, largest, difference / largest,
      second_cut / largest, any_cut / largest);

  // What the loop said of each cut (its time between two ticks), for docs/simulator.md.
  for (const std::string& n : live.notices)
    if (n.starts_with("cut: ")) std::printf("[ figures ] %s\n", n.c_str());
}

// A cut during a grab left the haptic loop's factor corrected, and every later pick on the cut
// model was refused ("attach it before the model is cut") until Whole again: the next pick after
// such a grab takes the cut model with a fresh factor.
TEST(ServeCut, APickAfterAGrabThatWasCutTakesTheCutModelWithAFreshFactor) {
  const auto scene = test::paper_scene({"static-cut"});
  const Vec3 point = test::pickable_point(*scene);
  const HandMessage before = test::stroke_beside(*scene, 0, point, 6.0);
  const HandMessage during =
      test::stroke(*scene, before.point_mm - Vec3(0, 0, 2), before.edge_to_mm - Vec3(0, 0, 2), before.move_mm * 1.5);
  const CutGrab live = cut_grab(*scene, 0, point, before, during);
  ASSERT_EQ(live.cuts.size(), 2U) << joined(live.notices);
  ASSERT_TRUE(live.cuts[1].during);
  PhysicsLoop loop(*scene, {.hand_speed_mm_s = 40, .reach_mm = 20});
  loop.start();
  loop.post({.kind = HandKind::pick, .sequence = 1, .point_mm = point, .model = 0});
  loop.post({.kind = HandKind::target, .sequence = 2, .point_mm = point + Vec3(0.5, 0, 0), .model = 0});
  const PhysicsSnapshot s = wait_turns(loop, 30);
  loop.stop();
  const std::string said = joined(loop.take_notices());
  EXPECT_EQ(said.find("refused pick"), std::string::npos) << said;
  EXPECT_NE(said.find("its factor made afresh after the cuts"), std::string::npos) << said;
  EXPECT_GT(s.t, 0.0) << "the second grab ticks";
}

TEST(ServeCut, RefusesAModelNotCutTheStaticPartTheHandsNodesAndAPickOnTheCut) {
  const auto scene = test::paper_scene({"static", "static-cut"});
  const Vec3 point = test::pickable_point(*scene);
  const HandMessage beside = test::stroke_beside(*scene, 1, point, 6.0);
  PhysicsLoop loop(*scene, {.hand_speed_mm_s = 40, .reach_mm = 20});
  loop.start();
  const auto said = [&] {
    wait_turns(loop, 3);
    return joined(loop.take_notices());
  };
  loop.post({.kind = HandKind::model, .sequence = 1, .point_mm = Vec3::Zero(), .model = 0});
  loop.post(beside);
  EXPECT_NE(said().find("refused cut: the static model is not cut by the scalpel"), std::string::npos);

  loop.post({.kind = HandKind::model, .sequence = 2, .point_mm = Vec3::Zero(), .model = 1});
  // Through the whole brain, top to bottom: it reaches the static part.
  const Eigen::AlignedBox3d& box = scene->box();
  const Vec3 top(point.x(), point.y(), box.max().z() / mm + 5), bottom(point.x(), point.y(), box.min().z() / mm - 5);
  loop.post(test::stroke(*scene, top, bottom, Vec3(0, 40, 0)));
  const std::string static_part = said();
  EXPECT_NE(static_part.find("refused cut: it reaches tetrahedron"), std::string::npos) << static_part;
  EXPECT_NE(static_part.find("of the static part"), std::string::npos) << static_part;
  // A stroke through the hand's footprint, while it holds.
  loop.post({.kind = HandKind::pick, .sequence = 3, .point_mm = point, .model = 0});
  wait_turns(loop, 5);
  loop.post(test::stroke(*scene, point + Vec3(-2, -2, 3), point + Vec3(-2, -2, -4), Vec3(4, 4, 0)));
  const std::string hand = said();
  EXPECT_NE(hand.find("of the hand"), std::string::npos) << hand;
  // A stroke that meets nothing, and one beside the hand: taken during the grab.
  loop.post(test::stroke(*scene, box.max() / mm + Vec3(10, 10, 10), box.max() / mm + Vec3(10, 10, 20), Vec3(5, 0, 0)));
  EXPECT_NE(said().find("crosses no tetrahedron"), std::string::npos);
  loop.post(beside);
  EXPECT_NE(said().find("removed from the static-cut model at t = "), std::string::npos);
  // Then a pick whose footprint holds a node of a removed tetrahedron.
  loop.post({.kind = HandKind::release, .sequence = 4, .point_mm = Vec3::Zero(), .model = 0});
  const mesh::TetMesh& mesh = scene->mesh();
  const std::vector<LiveCut> cuts = loop.take_cuts();
  ASSERT_EQ(cuts.size(), 1U);
  const int on_cut = mesh.tets[static_cast<std::size_t>(cuts[0].elements.front())][0];
  loop.post({.kind = HandKind::pick, .sequence = 5, .point_mm = mesh.node(on_cut) / mm, .model = 0});
  const std::string pick = said();
  EXPECT_TRUE(pick.find("lies on a cut") != std::string::npos || pick.find("refused pick") != std::string::npos) << pick;
  loop.stop();
}

TEST(ServeCut, MadeWholeAgainTheCutModelFeelsAsTheModelNeverCut) {
  const auto scene = test::paper_scene({"static", "static-cut"});
  const Vec3 point = test::pickable_point(*scene);
  const HandMessage beside = test::stroke_beside(*scene, 1, point, 6.0);
  // A cut, then whole again, then a grab: the live force is roifem run's replay with no cut
  // (cuts_of_grab leaves the cut out), and not its replay with the cut.
  PhysicsLoop loop(*scene, {.hand_speed_mm_s = 40, .reach_mm = 20});
  loop.start();
  loop.post({.kind = HandKind::model, .sequence = 1, .point_mm = Vec3::Zero(), .model = 1});
  loop.post(beside);
  loop.post({.kind = HandKind::whole, .sequence = 2, .point_mm = Vec3::Zero(), .model = 0});
  wait_turns(loop, 4);
  loop.post({.kind = HandKind::pick, .sequence = 3, .point_mm = point, .model = 0});
  for (int step = 1; step <= 6; ++step) {
    loop.post({.kind = HandKind::target,
               .sequence = 3U + static_cast<std::uint32_t>(step),
               .point_mm = point + Vec3(0.2 * step, -0.1 * step, 0),
               .model = 0});
    wait_turns(loop, 20);
  }
  loop.stop();
  const std::string said = joined(loop.take_notices());
  EXPECT_NE(said.find("whole again: the static-cut model built afresh"), std::string::npos) << said;
  const std::vector<LiveCut> record = loop.take_cuts();
  ASSERT_EQ(record.size(), 2U);
  EXPECT_TRUE(record[1].whole);
  ASSERT_TRUE(record[1].fresh);
  std::vector<HandSample> samples;
  loop.drain_samples(samples);
  GrabRecord grab{.grab = samples.back().grab,
                  .model = 1,
                  .center_mm = point,
                  .grip_nodes = samples.back().grip_nodes,
                  .samples = {},
                  .cuts = {}};
  for (const HandSample& s : samples)
    if (s.grab == grab.grab) grab.samples.push_back(s);
  ASSERT_GT(grab.samples.size(), 100U);
  EXPECT_TRUE(cuts_of_grab(record, grab).empty());
  const std::vector<Vec3> whole = replayed(*scene, grab, cuts_of_grab(record, grab));
  const std::vector<Vec3> cut = replayed(*scene, grab, {record[0]});
  double largest = 0, difference = 0, with_cut = 0;
  for (std::size_t i = 1; i < grab.samples.size(); ++i) {
    largest = std::max(largest, grab.samples[i].force.norm());
    difference = std::max(difference, (whole[i] - grab.samples[i].force).norm());
    with_cut = std::max(with_cut, (cut[i] - grab.samples[i].force).norm());
  }
  EXPECT_GT(largest, 1e-4);
  EXPECT_LT(difference, 1e-9 * largest);
  EXPECT_GT(with_cut, 1e-4 * largest);  // the cut, had it stayed, is felt
  // The display draws it whole again.
  scene->cut_surface(1, record[0].elements);
  EXPECT_NE(&scene->surface(1), &scene->surface(0));
  scene->show_whole(1, record[1].fresh);
  EXPECT_EQ(&scene->surface(1), &scene->surface(0));
}

TEST(ServeCut, AReplayTakesTheCutsBeforeItsGrabSinceTheModelWasLastWholeAndThoseDuringIt) {
  GrabRecord grab{.grab = 4, .model = 1, .center_mm = Vec3::Zero(), .grip_nodes = 1, .samples = {}, .cuts = {}};
  HandSample last;
  last.t = 0.5;
  grab.samples = {HandSample{}, last};
  const auto cut = [](std::size_t model, std::uint32_t g, bool during, double t, Index tag) {
    LiveCut c;
    c.model = model;
    c.grab = g;
    c.during = during;
    c.t = t;
    c.elements = {tag};
    return c;
  };
  LiveCut whole;
  whole.model = 1;
  whole.whole = true;
  whole.grab = 2;
  const std::vector<LiveCut> record{
      cut(1, 1, true, 0.2, 10), cut(1, 2, false, 0, 11),  whole,
      cut(1, 2, false, 0, 12),  cut(0, 3, false, 0, 13),                             // another model's
      cut(1, 3, true, 0.1, 14), cut(1, 4, true, 0.3, 15), cut(1, 4, true, 0.5, 16),  // at the grab's last tick: not replayed
      cut(1, 4, false, 0, 17),  cut(1, 5, false, 0, 18)};
  std::vector<Index> taken;
  for (const LiveCut& c : cuts_of_grab(record, grab)) taken.push_back(c.elements.front());
  EXPECT_EQ(taken, (std::vector<Index>{12, 14, 15}));
}

/// The faces of `tets` that no other of them shares, each as its sorted nodes.
std::map<std::array<int, 3>, int> faces_once(const std::vector<mesh::Tet>& tets) {
  std::map<std::array<int, 3>, int> count;
  for (const auto& t : tets)
    for (int skip = 0; skip < 4; ++skip) {
      std::array<int, 3> f{};
      for (int c = 0, j = 0; c < 4; ++c)
        if (c != skip) f[static_cast<std::size_t>(j++)] = t[static_cast<std::size_t>(c)];
      std::sort(f.begin(), f.end());
      ++count[f];
    }
  std::erase_if(count, [](const auto& kv) { return kv.second != 1; });
  return count;
}

TEST(ServeCut, TheDisplayDrawsTheSurfaceTheCutLeaves) {
  const auto scene = test::paper_scene({"static", "static-cut"});
  const Vec3 point = test::pickable_point(*scene);
  const HandMessage beside = test::stroke_beside(*scene, 1, point, 6.0);
  const SurfaceView& whole = scene->surface(1);
  EXPECT_EQ(&whole, &scene->surface(0));  // one surface while uncut
  scene->cut_surface(1, beside.crossed);
  const SurfaceView& cut = scene->surface(1);
  EXPECT_EQ(scene->surface(0).triangles.size(), whole.triangles.size());
  std::vector<mesh::Tet> left;
  for (std::size_t e = 0; e < scene->mesh().tets.size(); ++e)
    if (!std::binary_search(beside.crossed.begin(), beside.crossed.end(), static_cast<Index>(e)))
      left.push_back(scene->mesh().tets[e]);
  const auto expected = faces_once(left);
  ASSERT_EQ(cut.triangles.size(), expected.size());
  EXPECT_GT(cut.triangles.size(), whole.triangles.size());  // the cut's walls
  for (const auto& t : cut.triangles) {
    std::array<int, 3> f{cut.nodes[static_cast<std::size_t>(t[0])], cut.nodes[static_cast<std::size_t>(t[1])],
                         cut.nodes[static_cast<std::size_t>(t[2])]};
    std::sort(f.begin(), f.end());
    EXPECT_EQ(expected.count(f), 1U);
  }
  // The frame follows the new surface: a vertex per node, its unknowns the model's.
  const Vector u = Vector::LinSpaced(scene->models()[1].physics.model->system().size(), 0.0, 1e-3);
  std::vector<float> shown;
  scene->surface_displacement(1, u, 0.0, true, shown);
  EXPECT_EQ(shown.size(), 3 * cut.nodes.size());
}

}  // namespace
}  // namespace roifem::serve
