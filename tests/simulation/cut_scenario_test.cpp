// SPDX-License-Identifier: GPL-3.0-or-later
// Cuts in remove mode, run by a scenario, against what does not depend on the cut's machinery:
// the model assembled (and condensed) from scratch on the cut mesh, the energy balance, the
// mass, and two known answers (a piece cut loose falls freely; a tool holding a piece cut off
// from its support ends up holding nothing).
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <random>
#include <regex>

#include "common/errors.hpp"
#include "condensation/reduced_model.hpp"
#include "integrators/trapezoid.hpp"
#include "mesh/box_mesh.hpp"
#include "mesh/msh_writer.hpp"
#include "model/fem_model.hpp"
#include "model/reaction_forces.hpp"
#include "roi/node_dofs.hpp"
#include "simulation/cut_test_support.hpp"
#include "simulation/scenario_stepper.hpp"
#include "test_support.hpp"

namespace roifem::simulation {
namespace {

using cut_test::kMaterial;
using cut_test::scenario_on;

/// The mesh without the removed tetrahedra, its nodes as they were, the nodes left with no
/// tetrahedron in a set "orphans" (to be fixed), and its volume set renumbered.
mesh::TetMesh cut_mesh(const mesh::TetMesh& mesh, const std::vector<bool>& still_there) {
  mesh::TetMesh out = mesh;
  out.tets.clear();
  std::vector<bool> used(static_cast<std::size_t>(mesh.num_nodes()), false);
  for (std::size_t e = 0; e < mesh.tets.size(); ++e)
    if (still_there[e]) {
      out.tets.push_back(mesh.tets[e]);
      for (const int n : mesh.tets[e]) used[static_cast<std::size_t>(n)] = true;
    }
  for (auto& [name, set] : out.sets)
    if (set.dim == 3) {
      set.tets.resize(out.tets.size());
      for (std::size_t e = 0; e < out.tets.size(); ++e) set.tets[e] = static_cast<int>(e);
    }
  mesh::NamedSet& orphans = out.sets["orphans"];
  orphans.dim = 0;
  for (int n = 0; n < mesh.num_nodes(); ++n)
    if (!used[static_cast<std::size_t>(n)]) orphans.nodes.push_back(n);
  return out;
}

using cut_test::bar_scenario;

class CutAgainstRebuild : public ::testing::TestWithParam<cut_test::ModelCase> {};

TEST_P(CutAgainstRebuild, EqualsTheModelAssembledAndCondensedFromTheCutMesh) {
  test::TempDir dir;
  const mesh::TetMesh bar = mesh::structured_box_mesh(6, 2, 2, 0.03, 0.01, 0.01);
  mesh::write_msh(bar, dir / "bar.msh", mm);
  const scenario::Scenario sc = scenario_on(dir / "bar.msh", bar_scenario(GetParam().roi));
  ScenarioStepper stepper(sc);
  const double mass_before = stepper.model().system().M.diagonal().sum() / 3;
  double removed_mass = 0;
  std::vector<CutEvent> events;
  stepper.on_cut([&](const CutEvent& e, const model::State&) {
    events.push_back(e);
    removed_mass += e.mass_removed;
  });
  for (int k = 0; k < 20; ++k) stepper.step();
  // The middle's top layer and the part of its bottom layer above 3 mm, the end's top layer.
  const std::size_t removed = stepper.cuts().schedule().size();
  ASSERT_GT(removed, 12u + 12u);
  ASSERT_LT(removed, 12u + 12u + 12u);
  ASSERT_GE(events.size(), 3u);
  std::vector<int> orphans;
  for (const auto& e : events) orphans.insert(orphans.end(), e.orphan_nodes.begin(), e.orphan_nodes.end());
  ASSERT_EQ(orphans.size(), 3u);  // the far end's top edge

  // The model from scratch on the cut mesh: the orphans fixed, the same ROI nodes less them.
  const ScenarioModel& cut = stepper.model();
  const mesh::TetMesh rebuilt_mesh = cut_mesh(bar, stepper.cuts().still_there());
  model::FemModel rebuilt = model::build_fem_model(rebuilt_mesh, fem::MaterialMap(sc.material), {"x0", "orphans"}, sc.loads);
  std::unique_ptr<condensation::ReducedModel> reduced;
  std::vector<int> roi_nodes;
  for (const int n : cut.roi_nodes)
    if (std::find(orphans.begin(), orphans.end(), n) == orphans.end()) roi_nodes.push_back(n);
  if (cut.condensation)
    reduced = std::make_unique<condensation::ReducedModel>(
        rebuilt.system, roi::partition_dofs(rebuilt.system.K, *rebuilt.dofs, roi_nodes), *rebuilt.dofs, sc.reduction);
  const model::SecondOrderSystem& expected = reduced ? reduced->system() : rebuilt.system;

  const model::SecondOrderSystem& system = cut.system();
  const cut_test::Rebuilt compare(expected, cut_test::unknowns(rebuilt, reduced.get()), system,
                                  cut_test::unknowns(cut.full, cut.condensation.get()));
  const Index n = expected.size();
  ASSERT_EQ(system.size(), n + 9);  // the orphans' dofs stay, held
  const cut_test::Rebuilt::Gaps gaps = compare.operator_gaps();
  EXPECT_LT(gaps.K, 1e-12) << "K x";
  EXPECT_LT(gaps.M, 1e-14) << "M x";
  EXPECT_LT(gaps.f, 1e-13) << "f";
  // The held dofs: no stiffness, no load, at rest (to the round-off of the corrected solve).
  Vector e_held = Vector::Zero(system.size()), K_e(system.size());
  for (const auto& e : events)
    for (const Index d : e.change.held) {
      e_held.setZero();
      e_held[d] = 1;
      system.apply_stiffness(e_held, K_e);
      EXPECT_EQ(K_e.lpNorm<Eigen::Infinity>(), 0.0) << "held dof " << d;
      EXPECT_EQ(system.load.at(0.2)[d], 0.0);
      EXPECT_LT(std::abs(stepper.state().v[d]), 1e-10 * stepper.state().v.lpNorm<Eigen::Infinity>());
    }
  // Mass: the uncut mass less the removed tetrahedra's, to the round-off of the sums (the held dofs' stand-ins aside).
  if (!cut.condensation || sc.reduction.is_static_condensation()) {
    double held_mass = 0;
    for (const auto& e : events)
      for (const Index d : e.change.held) held_mass += system.M.coeff(d, d) / 3;
    EXPECT_NEAR(system.M.diagonal().sum() / 3 - held_mass, mass_before - removed_mass, 1e-14 * mass_before);
    EXPECT_NEAR(removed_mass, static_cast<double>(removed) * 1000 * (0.005 * 0.005 * 0.005 / 6), 1e-18);
  }

  // The trajectory from here on: the cut model's trapezoid (its factor corrected, not rebuilt)
  // against a fresh one on the rebuilt model, from the same state.
  const double gap = compare.trajectory_gap(stepper, sc.dt, 20);
  EXPECT_LT(gap, 1e-10);
  std::cout << GetParam().name << ": " << removed << " tetrahedra removed in " << events.size()
            << " events; against the rebuilt model: K x " << gaps.K << ", M x " << gaps.M << ", f " << gaps.f
            << ", u after 20 more steps " << gap << " (relative)";
  // Each cut taken by the factor's correction, or, once that would cost a solve more than the factor
  // does (integrators::Refactor), by a new factor: on this small bar, some of each.
  EXPECT_GE(stepper.stats().system_changes, 1);
  EXPECT_EQ(stepper.stats().system_changes + stepper.stats().lin_setups - 1, static_cast<long>(events.size()));
  // The energy: E + D + E_cut = W + E_0, to round-off.
  const model::EnergyLedger& ledger = *stepper.energy();
  EXPECT_GT(ledger.cut(), 0);
  EXPECT_LT(std::abs(ledger.balance_residual()), 5e-12 * std::abs(ledger.external_work()));
  std::cout << "; E_cut " << ledger.cut()
            << " J, |E + D + E_cut - W - E_0| / W = " << std::abs(ledger.balance_residual()) / std::abs(ledger.external_work())
            << "\n";
}

INSTANTIATE_TEST_SUITE_P(Models, CutAgainstRebuild, ::testing::ValuesIn(cut_test::model_cases(11.0)),
                         [](const auto& param_info) { return param_info.param.name; });

using cut_test::hanging_bar;

using cut_test::g;
using cut_test::kGravity;

/// The lower piece's unknowns (z components of the nodes below the cut) and their masses.
struct LowerPiece {
  std::vector<Index> z;
  std::vector<double> mass;
  double center(const Vector& u) const {
    double m = 0, mz = 0;
    for (std::size_t i = 0; i < z.size(); ++i) m += mass[i], mz += mass[i] * u[z[i]];
    return mz / m;
  }
};

LowerPiece lower_piece(const ScenarioStepper& stepper) {
  LowerPiece piece;
  const ScenarioModel& m = stepper.model();
  for (int n = 0; n < m.mesh.num_nodes(); ++n)
    if (m.mesh.node(n).z() < 0.0151) {
      const int d = m.full.dofs->free_dof(n, 2);
      piece.z.push_back(d);
      piece.mass.push_back(m.system().M.coeff(d, d));
    }
  return piece;
}

TEST(CutKnownAnswer, APieceCutLooseAtRestFallsAsGTSquaredOverTwo) {
  test::TempDir dir;
  mesh::write_msh(mesh::structured_box_mesh(2, 2, 8, 0.01, 0.01, 0.04), dir / "bar.msh", mm);
  const scenario::Scenario sc = scenario_on(dir / "bar.msh", hanging_bar("trapezoid", 0.001, 20, 0.0, kGravity));
  ScenarioStepper stepper(sc);
  std::vector<std::string> warnings;
  stepper.on_cut([&](const CutEvent& e, const model::State& at) {
    warnings = e.warnings;
    EXPECT_EQ(at.t, 0.0);
    EXPECT_EQ(e.elements.size(), 2u * 2u * 6u);
  });
  stepper.step_to(0.02);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_TRUE(std::regex_search(warnings[0], std::regex("set loose a piece of 36 nodes \\(0, 1, 2, .*\\) held by no support")))
      << warnings[0];
  // Every node below the cut, undeformed, in free fall: the rule integrates a constant acceleration exactly.
  const ScenarioModel& m = stepper.model();
  const double t = stepper.state().t, fall = -0.5 * g * t * t;
  for (int n = 0; n < m.mesh.num_nodes(); ++n) {
    if (m.mesh.node(n).z() > 0.0151) continue;
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(stepper.state().u[m.full.dofs->free_dof(n, c)], c == 2 ? fall : 0.0, 1e-13 * std::abs(fall)) << "node " << n;
    }
  }
  EXPECT_LT(std::abs(stepper.energy()->balance_residual()), 1e-12 * stepper.energy()->external_work());
}

class CutRestart : public ::testing::TestWithParam<const char*> {};

TEST_P(CutRestart, APieceCutLooseMidSwingFallsWithItsCentreOfMassOnAParabola) {
  // The bar hangs and swings under gravity (no damping) for 10 ms; then the cut frees its lower
  // part, whose centre of mass from then on moves as x_c + v_c (t - t_c) - g (t - t_c)^2 / 2
  // whatever the part does inside: the trapezoidal rule takes the cut by a correction of its
  // factor, the others restart, and each keeps that exactly (a linear invariant, a quadratic path).
  test::TempDir dir;
  mesh::write_msh(mesh::structured_box_mesh(2, 2, 8, 0.01, 0.01, 0.04), dir / "bar.msh", mm);
  const scenario::Scenario sc = scenario_on(dir / "bar.msh", hanging_bar(GetParam(), 0.0002, 100, 0.0101, kGravity));
  ScenarioStepper stepper(sc);
  LowerPiece piece;
  double t_cut = -1, z_cut = 0, v_cut = 0;
  stepper.on_cut([&](const CutEvent&, const model::State& at) {
    piece = lower_piece(stepper);  // the masses after the cut
    t_cut = at.t;
    z_cut = piece.center(at.u);
    v_cut = piece.center(at.v);
  });
  while (stepper.state().t < 0.0199) stepper.step();
  ASSERT_NEAR(t_cut, 0.0100, 1e-12);  // the start of the step that reaches the layer
  EXPECT_GT(std::abs(v_cut), 1e-4);   // it was swinging
  const double dt = stepper.state().t - t_cut;
  const double expected = z_cut + v_cut * dt - 0.5 * g * dt * dt;
  EXPECT_NEAR(piece.center(stepper.state().u), expected, 1e-12 * std::abs(expected));
  EXPECT_NEAR(piece.center(stepper.state().v), v_cut - g * dt, 1e-11 * g * dt);
  EXPECT_EQ(stepper.stats().steps, 100);  // the counters of a restarted method go on
}

INSTANTIATE_TEST_SUITE_P(Methods, CutRestart, ::testing::Values("trapezoid", "arkode-erk4", "gsl-rk4"),
                         [](const auto& param_info) { return std::regex_replace(param_info.param, std::regex("-"), "_"); });

TEST(CutKnownAnswer, AToolHoldingAPieceCutOffFromItsSupportEndsUpHoldingNothing) {
  // The tool pulls the bar's lower end down 1 mm and holds it; cut through above it, the piece it
  // holds has no load and no other support, so at rest the tool's force is zero (damped: alpha = 60/s).
  test::TempDir dir;
  mesh::write_msh(mesh::structured_box_mesh(2, 2, 8, 0.01, 0.01, 0.04), dir / "bar.msh", mm);
  const scenario::Scenario sc = scenario_on(
      dir / "bar.msh",
      hanging_bar("trapezoid", 0.0005, 2000, 0.1,
                  "60.0\n[[tool]]\nname = \"grip\"\nset = \"z0\"\ndisplacement_mm = [0.0, 0.0, -1.0]\nramp_s = 0.05\n"));
  ScenarioStepper stepper(sc);
  Vector held;
  stepper.on_cut([&](const CutEvent&, const model::State& at) { held = stepper.model().tools.forces(at.u, at.t); });
  stepper.step_to(1.0);
  ASSERT_EQ(held.size(), 3);
  EXPECT_GT(std::abs(held.z()), 1e-4);  // N: it was stretching the bar
  EXPECT_LT(stepper.tool_forces().norm(), 1e-8 * held.norm());
  EXPECT_LT(std::abs(stepper.energy()->balance_residual()), 1e-12 * std::abs(stepper.energy()->tool_work()));
}

TEST(CutKnownAnswer, TheSupportsCarryTheWeightLeftAfterACutAtTheRoot) {
  // The bar held at x = 0 under gravity and a 0.5 mN pull, its root's top layer cut away (the
  // tetrahedra at the fixed nodes): at rest the supports carry the weight of what is left and the
  // pull, sum R = g sum m_i + F over the free nodes' lumped masses rho V / 4 of the tetrahedra left
  // (a fixed node's own weight goes straight into its support). Stiffened, E = 300 kPa, so that
  // alpha = 200/s settles it within 0.5 s, in steps short enough (0.1 ms) that the modes the cut
  // sets ringing are damped too; at every 250th step the reactions also equal those of K assembled
  // from scratch on the cut mesh.
  test::TempDir dir;
  const mesh::TetMesh bar = mesh::structured_box_mesh(6, 2, 2, 0.03, 0.01, 0.01);
  mesh::write_msh(bar, dir / "bar.msh", mm);
  const scenario::Scenario sc = scenario_on(dir / "bar.msh", std::string(R"(
[material]
young_Pa = 300000.0
poisson = 0.45
rho_kg_m3 = 1000.0
alpha_per_s = 200.0
)") + cut_test::kBarHeldAndLoaded + R"(
[[cut]]
edge_from_mm = [2.5, -1.0, 11.0]
edge_to_mm = [2.5, 11.0, 11.0]
move_mm = [0.0, 0.0, -5.0]
start_s = 0.01
duration_s = 0.01
[time]
integrator = "trapezoid"
dt_s = 0.0001
steps = 5000
)");
  ScenarioStepper stepper(sc);
  double gap = 0;
  for (int k = 1; k <= 5000; ++k) {
    stepper.step();
    if (k % 250 != 0 || stepper.state().t < 0.021) continue;
    const mesh::TetMesh rebuilt_mesh = cut_mesh(bar, stepper.cuts().still_there());
    const model::FemModel rebuilt =
        model::build_fem_model(rebuilt_mesh, fem::MaterialMap(sc.material), {"x0", "orphans"}, sc.loads);
    const model::ReactionForces expected(rebuilt);
    const Vector u = stepper.displacement(), r = expected.nodal(u), r_cut = stepper.reaction_forces();
    const std::vector<int>& nodes = stepper.reactions().nodes();
    for (std::size_t i = 0; i < expected.nodes().size(); ++i) {
      const auto at = std::find(nodes.begin(), nodes.end(), expected.nodes()[i]);
      if (at == nodes.end()) continue;  // an orphan: fixed in the rebuilt model only
      const Index j = at - nodes.begin();
      for (int c = 0; c < 3; ++c)
        gap = std::max(gap, std::abs(r_cut[3 * j + c] - r[3 * static_cast<Index>(i) + c]) / r.lpNorm<Eigen::Infinity>());
    }
  }
  const std::size_t removed = stepper.cuts().schedule().size();
  ASSERT_GT(removed, 0u);
  EXPECT_LT(gap, 1e-12);
  double free_mass = 0;  // from the mesh: the tetrahedra left, each a quarter of rho V at its free corners
  const std::vector<int>& held = bar.sets.at("x0").nodes;
  for (std::size_t e = 0; e < bar.tets.size(); ++e)
    if (stepper.cuts().still_there()[e])
      for (const int n : bar.tets[e])
        if (std::find(held.begin(), held.end(), n) == held.end())
          free_mass += 1000 * std::abs(mesh::signed_volume(bar, static_cast<Index>(e))) / 4;
  const double expected_z = free_mass * cut_test::g + 0.0005;
  const Vec3 total = stepper.reactions().total(stepper.displacement());
  EXPECT_NEAR(total.z(), expected_z, 1e-9 * expected_z);
  EXPECT_LT(std::abs(total.x()) + std::abs(total.y()), 1e-9 * total.z());
  std::cout << removed << " tetrahedra removed at the root; the supports carry " << total.z()
            << " N against g sum m + F = " << expected_z << " N (" << std::abs(total.z() / expected_z - 1)
            << " relative); reactions against the rebuilt K: " << gap << " (relative)\n";
}

TEST(CutKnownAnswer, TheCondensedRoiFollowsTheFullModelThroughTheSameCut) {
  // The paper's comparison with a cut inside the ROI: the bar's condensed model (static
  // condensation) against the full dynamic model, both cut by the same blades. The reduction
  // error (the static part's missing inertia) before and after the cut, beside what the cut
  // itself changes (the uncut full model against the cut one): the condensed model must follow
  // the cut, not the uncut bar.
  test::TempDir dir;
  cut_test::write_bar(dir);
  const std::string roi = "[roi]\nkind = \"ball\"\ncenter_mm = [22.5, 5.0, 5.0]\nradius_mm = 11.0\n";
  std::string uncut = bar_scenario("");
  uncut.erase(uncut.find("[[cut]]"), uncut.find("[time]") - uncut.find("[[cut]]"));
  ScenarioStepper condensed(scenario_on(dir / "bar.msh", bar_scenario(roi))),
      full(scenario_on(dir / "bar.msh", bar_scenario(""))), full_uncut(scenario_on(dir / "bar.msh", uncut));
  const roi::NodeDofs in_condensed = condensed.model().node_positions();
  const roi::NodeDofs in_full = roi::node_dofs_in_full(condensed.model().roi_nodes, *full.model().full.dofs);
  double first_cut = -1;
  condensed.on_cut([&](const CutEvent& e, const model::State&) {
    if (first_cut < 0) first_cut = e.time;
  });
  double before = 0, after = 0, cut_effect = 0, peak = 0;
  for (int k = 0; k < 40; ++k) {
    condensed.step();
    full.step();
    full_uncut.step();
    for (std::size_t i = 0; i < in_full.size(); ++i)
      for (std::size_t c = 0; c < 3; ++c) {
        const Index a = in_condensed[i][c], b = in_full[i][c];
        if (a < 0) continue;
        const double u = full.state().u[b], gap = std::abs(condensed.state().u[a] - u);
        peak = std::max(peak, std::abs(u));
        (first_cut < 0 ? before : after) = std::max(first_cut < 0 ? before : after, gap);
        if (first_cut >= 0) cut_effect = std::max(cut_effect, std::abs(full_uncut.state().u[b] - u));
      }
  }
  ASSERT_GT(first_cut, 0.0);
  std::cout << "condensed against full, the same cut: reduction error " << before / peak << " of the peak before the cut, "
            << after / peak << " after; the cut itself changes the ROI's motion by " << cut_effect / peak << '\n';
  EXPECT_LT(after, 0.2 * cut_effect);
  EXPECT_GT(before, 0.0);
}

/// The refusal `pattern` for the bar scenario with `old_text` replaced by `new_text`.
void expect_refused(const std::string& roi, const std::string& old_text, const std::string& new_text,
                    const std::string& pattern) {
  cut_test::expect_refused(bar_scenario(roi), old_text, new_text, pattern);
}

TEST(CutRefusal, NamesTheTetrahedronTheTimeAndTheNodeOfAStaticPartOrATool) {
  expect_refused("[roi]\nkind = \"ball\"\ncenter_mm = [27.5, 5.0, 5.0]\nradius_mm = 8.0\n", "", "",
                 "cut.toml:[0-9]+: cut 'middle' \\(cut.toml:[0-9]+\\) reaches tetrahedron [0-9]+ at t = 0.0[2-7][0-9]* s, which "
                 "touches node [0-9]+ of the static part");
  expect_refused("", "[[cut]]\nname = \"middle\"",
                 "[[tool]]\nset = \"x1\"\ndisplacement_mm = [0.0, 0.0, 1.0]\n[[cut]]\nname = \"middle\"",
                 "cut 'end' .* reaches tetrahedron [0-9]+ at t = .* s, which holds node [0-9]+ of tool 'tool1'");
}

TEST(CutRefusal, RefusesWhatItIsNotBuiltFor) {
  const std::string roi = "[roi]\nkind = \"ball\"\ncenter_mm = [22.5, 5.0, 5.0]\nradius_mm = 11.0\n";
  expect_refused(roi + "reduction = \"craig-bampton\"\nmodes = 2\n", "", "", "keeps modes of the uncut mesh's static part");
  expect_refused(roi, "integrator = \"trapezoid\"", "integrator = \"ida-roi-dae\"",
                 "integrator 'ida-roi-dae' integrates a DAE form");
  expect_refused("", "alpha_per_s = 2.0", "alpha_per_s = 2.0\nmodel = \"neo-hookean\"", "built for the linear material");
  // Two blades through both layers of cells, along the whole bar: nothing would be left.
  expect_refused(
      "", "[time]",
      "[[cut]]\nedge_from_mm = [-1.0, -1.0, 2.5]\nedge_to_mm = [-1.0, 11.0, 2.5]\nmove_mm = [32.0, 0.0, 0.0]\n"
      "duration_s = 0.1\n[[cut]]\nedge_from_mm = [-1.0, -1.0, 7.5]\nedge_to_mm = [-1.0, 11.0, 7.5]\nmove_mm = [32.0, 0.0, 0.0]\n"
      "duration_s = 0.1\n[time]",
      "the cuts would remove the last 144 tetrahedra of the mesh");
}

}  // namespace
}  // namespace roifem::simulation
