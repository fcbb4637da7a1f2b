// SPDX-License-Identifier: GPL-3.0-or-later
// Cuts in split mode, run by a scenario, against what does not depend on the split's machinery:
// the model assembled (and condensed) from scratch on the split mesh, the energy balance (a split
// takes no energy), the mass (it removes none), and known answers: a piece split off at rest falls
// freely; a cantilever split at its root leaves the tool holding its tip with no force.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <regex>
#include <set>

#include "common/errors.hpp"
#include "integrators/haptic_trapezoid.hpp"
#include "mesh/box_mesh.hpp"
#include "mesh/msh_writer.hpp"
#include "simulation/cut_test_support.hpp"
#include "test_support.hpp"

namespace roifem::simulation {
namespace {

using cut_test::kMaterial;
using cut_test::scenario_on;

/// The exactness tests' bar (cut_test::bar_scenario) opened by its two blades in split mode, the far
/// one at x = 22.5 mm.
std::string split_bar(const std::string& roi) { return cut_test::bar_scenario(roi, "split", 22.5); }

/// The mesh as the splits left it (the copies among its nodes), the copies no split has used in a
/// set "unused" (none, once the blades are through).
mesh::TetMesh split_mesh(const mesh::TetMesh& mesh) {
  mesh::TetMesh out = mesh;
  std::vector<bool> used(static_cast<std::size_t>(mesh.num_nodes()), false);
  for (const auto& t : mesh.tets)
    for (const int n : t) used[static_cast<std::size_t>(n)] = true;
  mesh::NamedSet& unused = out.sets["unused"];
  unused.dim = 0;
  for (int n = 0; n < mesh.num_nodes(); ++n)
    if (!used[static_cast<std::size_t>(n)]) unused.nodes.push_back(n);
  return out;
}

class SplitAgainstRebuild : public ::testing::TestWithParam<cut_test::ModelCase> {};

TEST_P(SplitAgainstRebuild, EqualsTheModelAssembledAndCondensedFromTheSplitMesh) {
  test::TempDir dir;
  const mesh::TetMesh bar = mesh::structured_box_mesh(6, 2, 2, 0.03, 0.01, 0.01);
  mesh::write_msh(bar, dir / "bar.msh", mm);
  const scenario::Scenario sc = scenario_on(dir / "bar.msh", split_bar(GetParam().roi));
  ScenarioStepper stepper(sc);
  const ScenarioModel& cut = stepper.model();
  const Index copies = cut.split_plan->num_copies();
  ASSERT_GT(copies, 6);
  // The copies' unknowns (held before their split, with a stand-in mass).
  std::vector<Index> copy_dofs;
  const auto in_system = cut_test::unknowns(cut.full, cut.condensation.get());
  for (std::size_t i = 0; i < in_system.size(); ++i)
    if (in_system[i].first >= cut.split_plan->num_nodes) copy_dofs.push_back(static_cast<Index>(i));
  ASSERT_EQ(static_cast<Index>(copy_dofs.size()), 3 * copies);
  const auto mass_of = [&](const model::SecondOrderSystem& s, const std::vector<Index>& held) {
    double m = s.M.diagonal().sum();
    for (const Index d : held) m -= s.M.coeff(d, d);
    return m / 3;
  };
  const double mass_before = mass_of(cut.system(), copy_dofs);
  std::vector<int> split_nodes;
  std::size_t events = 0;
  double taken = 0;
  stepper.on_cut([&](const CutEvent& e, const model::State&) {
    events += e.splits.empty() ? 0 : 1;
    taken += std::abs(e.energy_removed());
    for (const auto& [node, copy] : e.splits) split_nodes.push_back(node);
    EXPECT_TRUE(e.elements.empty());
  });
  for (int k = 0; k < 20; ++k) stepper.step();
  ASSERT_GE(events, 3u);
  EXPECT_EQ(stepper.cuts().faces_separated(), cut.split_plan->faces.size());

  // The model from scratch on the split mesh: the copies no split used fixed, the ROI without them.
  const mesh::TetMesh rebuilt_mesh = split_mesh(cut.mesh);
  const std::vector<int>& unused = rebuilt_mesh.sets.at("unused").nodes;
  EXPECT_EQ(static_cast<Index>(unused.size()), 0);  // every copy reserved is used by the run's end
  model::FemModel rebuilt = model::build_fem_model(rebuilt_mesh, fem::MaterialMap(sc.material), {"x0"}, sc.loads);
  std::unique_ptr<condensation::ReducedModel> reduced;
  std::vector<int> roi_nodes;
  for (const int n : cut.roi_nodes)
    if (!std::binary_search(unused.begin(), unused.end(), n)) roi_nodes.push_back(n);
  if (cut.condensation)
    reduced = std::make_unique<condensation::ReducedModel>(
        rebuilt.system, roi::partition_dofs(rebuilt.system.K, *rebuilt.dofs, roi_nodes), *rebuilt.dofs, sc.reduction);
  const model::SecondOrderSystem& expected = reduced ? reduced->system() : rebuilt.system;
  const model::SecondOrderSystem& system = cut.system();
  const cut_test::Rebuilt compare(expected, cut_test::unknowns(rebuilt, reduced.get()), system,
                                  cut_test::unknowns(cut.full, cut.condensation.get()));
  ASSERT_EQ(system.size(), expected.size());
  const cut_test::Rebuilt::Gaps gaps = compare.operator_gaps();
  EXPECT_LT(gaps.K, 1e-12) << "K x";
  EXPECT_LT(gaps.M, 1e-14) << "M x";
  EXPECT_LT(gaps.f, 1e-13) << "f";
  // Mass: none removed (the uncut model's, the copies' stand-ins aside, to round-off).
  if (!cut.condensation || sc.reduction.is_static_condensation()) {
    EXPECT_NEAR(mass_of(system, {}), mass_before, 1e-13 * mass_before);
    EXPECT_NEAR(mass_of(system, {}), mass_of(expected, {}), 1e-13 * mass_before);
  }
  const double gap = compare.trajectory_gap(stepper, sc.dt, 20);
  EXPECT_LT(gap, 1e-10);
  // Each split taken by the factor's correction or, once that would cost more than the factor's
  // solve (integrators::Refactor), by a new factor: on this small bar, some of each.
  EXPECT_GE(stepper.stats().system_changes, 1);
  EXPECT_EQ(stepper.stats().system_changes + stepper.stats().lin_setups - 1, static_cast<long>(events));
  // The energy: a split takes none, so E + D = W + E_0 across it.
  const model::EnergyLedger& ledger = *stepper.energy();
  EXPECT_LT(taken, 1e-13 * std::abs(ledger.external_work()));
  EXPECT_LT(std::abs(ledger.balance_residual()), 5e-12 * std::abs(ledger.external_work()));
  std::cout << GetParam().name << ": " << split_nodes.size() << " nodes split (" << copies << " copies) in " << events
            << " events over " << cut.split_plan->faces.size() << " faces; against the rebuilt model: K x " << gaps.K << ", M x "
            << gaps.M << ", f " << gaps.f << ", u after 20 more steps " << gap << " (relative); energy taken " << taken
            << " J, |E + D - W - E_0| / W = " << std::abs(ledger.balance_residual()) / std::abs(ledger.external_work()) << "\n";
}

INSTANTIATE_TEST_SUITE_P(Models, SplitAgainstRebuild, ::testing::ValuesIn(cut_test::model_cases(13.0)),
                         [](const auto& param_info) { return param_info.param.name; });

using cut_test::g;
using cut_test::kGravity;

/// The unknowns of the nodes that the tetrahedra with centroids below z (m) hold now, per component,
/// with their masses.
struct Piece {
  std::vector<Index> dofs[3];
  std::vector<double> mass;
  double center(const Vector& u, int c) const {
    double m = 0, mu = 0;
    for (std::size_t i = 0; i < mass.size(); ++i) m += mass[i], mu += mass[i] * u[dofs[c][i]];
    return mu / m;
  }
};

Piece piece_below(const ScenarioModel& m, double z) {
  std::set<int> nodes;
  for (const auto& t : m.mesh.tets) {
    double zc = 0;
    for (const int n : t) zc += m.mesh.node(n).z() / 4;
    if (zc < z - 1e-12) nodes.insert(t.begin(), t.end());
  }
  Piece piece;
  for (const int n : nodes) {
    for (int c = 0; c < 3; ++c) piece.dofs[c].push_back(m.full.dofs->free_dof(n, c));
    piece.mass.push_back(m.system().M.coeff(piece.dofs[2].back(), piece.dofs[2].back()));
  }
  return piece;
}

TEST(SplitKnownAnswer, APieceSplitOffAtRestFallsAsGTSquaredOverTwo) {
  test::TempDir dir;
  mesh::write_msh(mesh::structured_box_mesh(2, 2, 8, 0.01, 0.01, 0.04), dir / "bar.msh", mm);
  ScenarioStepper stepper(scenario_on(dir / "bar.msh", cut_test::hanging_bar("trapezoid", 0.001, 20, 0.0, kGravity, "split")));
  std::vector<std::string> warnings;
  std::size_t splits = 0;
  stepper.on_cut([&](const CutEvent& e, const model::State& at) {
    warnings.insert(warnings.end(), e.warnings.begin(), e.warnings.end());
    splits += e.splits.size();
    EXPECT_EQ(at.t, 0.0);
  });
  stepper.step_to(0.02);
  // Each node that tetrahedra of both sides hold splits once (the blade's plane runs through the
  // centroids of a third of the layer's tetrahedra: those count as above, the side its normal gives).
  const mesh::TetMesh bar = mesh::structured_box_mesh(2, 2, 8, 0.01, 0.01, 0.04);
  std::vector<int> sides(static_cast<std::size_t>(bar.num_nodes()), 0);
  for (const auto& t : bar.tets) {
    double zc = 0;
    for (const int n : t) zc += bar.node(n).z() / 4;
    for (const int n : t) sides[static_cast<std::size_t>(n)] |= zc < 0.0175 - 1e-12 ? 1 : 2;
  }
  EXPECT_EQ(splits, static_cast<std::size_t>(std::count(sides.begin(), sides.end(), 3)));
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_TRUE(std::regex_search(warnings[0], std::regex("set loose a piece of [0-9]+ nodes .* held by no support")))
      << warnings[0];
  // The piece below the blade, undeformed, in free fall (the rule integrates a constant acceleration exactly).
  const Piece piece = piece_below(stepper.model(), 0.0175);
  ASSERT_GT(piece.mass.size(), 27u);
  const double t = stepper.state().t, fall = -0.5 * g * t * t;
  for (int c = 0; c < 3; ++c)
    for (const Index d : piece.dofs[c]) EXPECT_NEAR(stepper.state().u[d], c == 2 ? fall : 0.0, 1e-13 * std::abs(fall)) << d;
  EXPECT_LT(std::abs(stepper.energy()->balance_residual()), 1e-12 * stepper.energy()->external_work());
}

class SplitRestart : public ::testing::TestWithParam<const char*> {};

TEST_P(SplitRestart, APieceSplitOffMidSwingFallsWithItsCentreOfMassOnAParabola) {
  // As in remove mode (cut_scenario_test.cpp): the bar swings under gravity, undamped, for 10 ms,
  // then the blade splits it through; the lower piece's centre of mass then follows the parabola.
  test::TempDir dir;
  mesh::write_msh(mesh::structured_box_mesh(2, 2, 8, 0.01, 0.01, 0.04), dir / "bar.msh", mm);
  ScenarioStepper stepper(
      scenario_on(dir / "bar.msh", cut_test::hanging_bar(GetParam(), 0.0002, 100, 0.0101, kGravity, "split")));
  Piece piece;
  double t_cut = -1, z_cut = 0, v_cut = 0;
  stepper.on_cut([&](const CutEvent& e, const model::State& at) {
    if (e.splits.empty()) return;
    piece = piece_below(stepper.model(), 0.0175);  // its nodes and masses after the split
    t_cut = at.t;
    z_cut = piece.center(at.u, 2);
    v_cut = piece.center(at.v, 2);
  });
  while (stepper.state().t < 0.0199) stepper.step();
  ASSERT_NEAR(t_cut, 0.0100, 1e-12);
  EXPECT_GT(std::abs(v_cut), 1e-4);  // it was swinging
  const double dt = stepper.state().t - t_cut;
  const double expected = z_cut + v_cut * dt - 0.5 * g * dt * dt;
  EXPECT_NEAR(piece.center(stepper.state().u, 2), expected, 1e-12 * std::abs(expected));
  EXPECT_NEAR(piece.center(stepper.state().v, 2), v_cut - g * dt, 1e-11 * g * dt);
}

INSTANTIATE_TEST_SUITE_P(Methods, SplitRestart, ::testing::Values("trapezoid", "arkode-erk4", "gsl-rk4"),
                         [](const auto& param_info) { return std::regex_replace(param_info.param, std::regex("-"), "_"); });

/// The cantilever: the bar held at x = 0, its tip (x = 30 mm) pulled down 1 mm by a tool and held
/// there; at 0.1 s a blade in split mode goes through the whole section 7.5 mm from the root.
std::string split_cantilever(const std::string& gravity) {
  return R"(
[material]
young_Pa = 3000.0
poisson = 0.45
rho_kg_m3 = 1000.0
alpha_per_s = 60.0
)" + gravity +
         R"(
[boundary]
fixed = ["x0"]
[[tool]]
name = "tip"
set = "x1"
displacement_mm = [0.0, 0.0, -1.0]
ramp_s = 0.05
[[cut]]
name = "root"
mode = "split"
edge_from_mm = [7.5, -1.0, 11.0]
edge_to_mm = [7.5, 11.0, 11.0]
move_mm = [0.0, 0.0, -12.0]
start_s = 0.1
duration_s = 0.000001
[time]
integrator = "trapezoid"
dt_s = 0.0005
steps = 2000
)";
}

TEST(SplitKnownAnswer, ACantileverSplitAtItsRootLeavesTheToolAtItsTipHoldingNothing) {
  test::TempDir dir;
  cut_test::write_bar(dir);
  ScenarioStepper stepper(scenario_on(dir / "bar.msh", split_cantilever("")));
  Vector held;
  stepper.on_cut([&](const CutEvent& e, const model::State& at) {
    if (!e.splits.empty()) held = stepper.model().tools.forces(at.u, at.t);
  });
  stepper.step_to(1.0);
  ASSERT_EQ(held.size(), 3);
  EXPECT_GT(std::abs(held.z()), 1e-5);  // N: it was bending the cantilever
  std::cout << "tool force at the split " << held.transpose() << " N, at 1 s " << stepper.tool_forces().transpose() << " N\n";
  EXPECT_LT(stepper.tool_forces().norm(), 1e-8 * held.norm());
  EXPECT_LT(std::abs(stepper.energy()->balance_residual()), 1e-12 * std::abs(stepper.energy()->tool_work()));
}

TEST(SplitKnownAnswer, UnderGravityTheToolEndsUpCarryingExactlyTheWeightOfWhatWasSplitOff) {
  // The same under gravity: once split, the tool alone holds the piece beyond the blade, whose mass
  // is that of the tetrahedra with centroids beyond x = 7.5 mm (the separated faces' two sides).
  test::TempDir dir;
  const mesh::TetMesh bar = mesh::structured_box_mesh(6, 2, 2, 0.03, 0.01, 0.01);
  mesh::write_msh(bar, dir / "bar.msh", mm);
  ScenarioStepper stepper(scenario_on(dir / "bar.msh", split_cantilever("[[load]]\ngravity_m_s2 = [0.0, 0.0, -9.81]\n")));
  stepper.step_to(1.0);
  double beyond = 0;
  for (Index e = 0; e < bar.num_tets(); ++e) {
    double x = 0;
    for (const int n : bar.tets[static_cast<std::size_t>(e)]) x += bar.node(n).x() / 4;
    if (x > 0.0075) beyond += 1000 * mesh::signed_volume(bar, e);
  }
  const Vector force = stepper.tool_forces();
  std::cout << "tool force at 1 s " << force.transpose() << " N against the piece's weight " << beyond * g << " N\n";
  EXPECT_NEAR(std::abs(force.z()), beyond * g, 1e-8 * beyond * g);
  EXPECT_LT(std::abs(force.x()) + std::abs(force.y()), 1e-8 * beyond * g);
}

TEST(SplitHaptic, TheLoopTakesASplitAsTheModelRebuiltFromTheSplitMesh) {
  // The bar's far end held by the hand; the middle blade of the exactness test split through at
  // once, mid-run. The loop takes the split between two ticks (HapticTrapezoid::take_change, the
  // copies started at their nodes by the split): against the model assembled from the split mesh
  // with the tool attached afresh there, the compliance W to round-off, and the force after.
  test::TempDir dir;
  cut_test::write_bar(dir);
  std::string text = split_bar("");
  text.erase(text.find("[[cut]]\nname = \"end\""), text.find("[time]") - text.find("[[cut]]\nname = \"end\""));
  text.erase(text.find("[[load]]"), text.find("[[cut]]") - text.find("[[load]]"));  // the hand alone
  const scenario::Scenario sc = scenario_on(dir / "bar.msh", text);
  const std::unique_ptr<ScenarioModel> m = build_scenario_model(sc);
  ScenarioCuts cuts(sc, *m);
  std::vector<std::array<Index, 3>> held;
  for (const int n : m->mesh.set("x1").nodes)
    held.push_back({m->full.dofs->free_dof(n, 0), m->full.dofs->free_dof(n, 1), m->full.dofs->free_dof(n, 2)});
  const double dt = 1e-3;
  const auto hand = [](double t) { return Vec3(0, 0.0005 * std::sin(20 * t), 0.001 * std::min(t / 0.02, 1.0)); };
  model::SecondOrderSystem system = m->system();
  integrators::HapticTrapezoid haptic(system, dt);
  haptic.attach(held);
  model::State s = model::State::at_rest(system.size());
  haptic.reset(s);
  for (long n = 1; n <= 15; ++n) haptic.tick(hand(static_cast<double>(n) * dt), s);
  CutEvent event = cuts.cut_due(1.0, *m, s);  // every face at once
  ASSERT_GT(event.splits.size(), 5u);
  event.change.apply(system);
  haptic.take_change(event.change, s);

  const model::FemModel rebuilt = model::build_fem_model(m->mesh, fem::MaterialMap(sc.material), {"x0"}, {});
  ASSERT_EQ(rebuilt.system.size(), system.size());  // every copy in use: the same free numbering
  integrators::HapticTrapezoid fresh(rebuilt.system, dt);
  fresh.attach(held);
  const double W_gap =
      (haptic.compliance() - fresh.compliance()).cwiseAbs().maxCoeff() / fresh.compliance().cwiseAbs().maxCoeff();
  EXPECT_LT(W_gap, 1e-13);
  // The force from here on against the rebuilt loop from the same state (its acceleration consistent).
  model::State r = s;
  fresh.reset(r);
  double worst = 0, largest = 0;
  for (long n = 16; n <= 60; ++n) {
    const Vec3 F = haptic.tick(hand(static_cast<double>(n) * dt), s),
               F_rebuilt = fresh.tick(hand(static_cast<double>(n) * dt), r);
    worst = std::max(worst, (F - F_rebuilt).norm());
    largest = std::max(largest, F_rebuilt.norm());
  }
  EXPECT_LT(worst, 1e-10 * largest);
  std::cout << "haptic split: " << event.splits.size() << " nodes split; W against the rebuilt model's " << W_gap
            << ", force over 45 ticks " << worst / largest << '\n';
}

/// The refusal `pattern` for the split bar with `old_text` replaced by `new_text`.
void expect_split_refused(const std::string& roi, const std::string& old_text, const std::string& new_text,
                          const std::string& pattern) {
  cut_test::expect_refused(split_bar(roi), old_text, new_text, pattern);
}

TEST(SplitRefusal, NamesTheBladeTheFacesTheTimeAndTheNode) {
  // At the support: the blade through the first cell splits nodes of x = 0, which are fixed.
  expect_split_refused("", "edge_from_mm = [17.5, -1.0, 11.0]\nedge_to_mm = [17.5, 11.0, 11.0]",
                       "edge_from_mm = [2.5, -1.0, 11.0]\nedge_to_mm = [2.5, 11.0, 11.0]",
                       "cut.toml:[0-9]+: cut 'middle' \\(cut.toml:[0-9]+\\) separates tetrahedra [0-9]+ and [0-9]+ at t = "
                       "0.0[2-7][0-9]* s, which splits node [0-9]+, a fixed node");
  // Beyond the ROI: what moves would touch the static part.
  expect_split_refused("[roi]\nkind = \"ball\"\ncenter_mm = [25.0, 5.0, 5.0]\nradius_mm = 9.0\n", "", "",
                       "cut 'middle' .* which splits node [0-9]+.* of the static part");
  // At a tool: the far end's blade reaches the tool's nodes' tetrahedra.
  expect_split_refused(
      "", "[[cut]]\nname = \"middle\"",
      "[[tool]]\nset = \"x1\"\ndisplacement_mm = [0.0, 0.0, 1.0]\n[[cut]]\nedge_from_mm = [27.5, -1.0, "
      "11.0]\nedge_to_mm = [27.5, 11.0, 11.0]\nmove_mm = [0.0, 0.0, -5.0]\nduration_s = 0.02\nmode = \"split\"\n[[cut]]\nname = "
      "\"middle\"",
      "tool 'tool1'");
}

TEST(SplitRefusal, OneModePerScenario) {
  test::TempDir dir;
  cut_test::write_bar(dir);
  std::string text = split_bar("");
  const std::string split_end = "name = \"end\"\nmode = \"split\"";
  text.replace(text.find(split_end), split_end.size(), "name = \"end\"\nmode = \"remove\"");
  EXPECT_THROW(
      {
        try {
          scenario_on(dir / "bar.msh", text);
        } catch (const InputError& e) {
          EXPECT_TRUE(std::regex_search(e.what(), std::regex("cut 'end' .* is in remove mode and cut 'middle' .* is not: a "
                                                             "scenario's cuts share one mode")))
              << e.what();
          throw;
        }
      },
      InputError);
}

}  // namespace
}  // namespace roifem::simulation
