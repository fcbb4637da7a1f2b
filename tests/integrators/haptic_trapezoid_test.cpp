// SPDX-License-Identifier: GPL-3.0-or-later
// The haptic loop (a tool steered tick by tick through its compliance) against the analytic
// spring-mass, against elimination (a second formulation of the same discrete problem), and its
// compliance against the dense inverse of K_eff.
#include "integrators/haptic_trapezoid.hpp"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <iostream>
#include <numeric>
#include <tuple>

#include "common/errors.hpp"
#include "condensation/reduced_model.hpp"
#include "fem/element_removal.hpp"
#include "integrators/trapezoid.hpp"
#include "simulation/scenario_model.hpp"
#include "test_models.hpp"

namespace roifem::integrators {
namespace {

/// Each node's (x, y, z) dofs in a free numbering.
std::vector<std::array<Index, 3>> node_dofs(const fem::DofMap& dofs, const std::vector<int>& nodes) {
  std::vector<std::array<Index, 3>> out;
  for (int n : nodes) out.push_back({dofs.free_dof(n, 0), dofs.free_dof(n, 1), dofs.free_dof(n, 2)});
  return out;
}

/// Max |F_haptic - F_exact| over [0, 3T] at dt, the tool's node held through its compliance.
double spring_mass_force_error(const test::SpringMass& sm, double dt) {
  const model::SecondOrderSystem all = sm.all();
  HapticTrapezoid haptic(all, dt);
  haptic.attach({{3, 4, 5}});
  model::State s = model::State::at_rest(6);
  haptic.reset(s);
  double worst = 0;
  const long steps = std::lround(3 * sm.T / dt);
  for (long n = 1; n <= steps; ++n) {
    const double t = static_cast<double>(n) * dt;
    const Vec3 F = haptic.tick(Vec3(sm.g(t), 0, 0), s);
    EXPECT_NEAR(s.u[3], sm.g(t), 1e-15);  // the held node is where the hand put it
    worst = std::max(worst, std::abs(F[0] - sm.force(t)));
    EXPECT_NEAR(F[1], 0.0, 1e-15);
  }
  return worst;
}

TEST(HapticTrapezoid, ASpringMassOnAHandFeelsTheAnalyticForceAtSecondOrder) {
  const test::SpringMass sm;
  const double coarse = spring_mass_force_error(sm, 0.01), fine = spring_mass_force_error(sm, 0.005);
  EXPECT_NEAR(std::log2(coarse / fine), 2.0, 0.05);
  EXPECT_LT(fine, 1e-3 * sm.k * sm.d);
}

/// The same tool twice: eliminated from `with_tool` (its path a ramp) and held through its
/// compliance in `without` (the hand sent the path's positions tick by tick). Returns the largest
/// force difference relative to the largest force, and checks the displacements agree.
double haptic_against_elimination(const model::SecondOrderSystem& eliminated, const model::ToolSet& tools,
                                  const model::SecondOrderSystem& without, const std::vector<std::array<Index, 3>>& held,
                                  const std::function<Vector(const Vector&, double)>& eliminated_field,
                                  const std::function<Vector(const Vector&)>& haptic_field, double dt, long steps,
                                  HapticNewton newton = {}) {
  Trapezoid trapezoid(dt);
  model::State a = model::State::at_rest(eliminated.size()), b = model::State::at_rest(without.size());
  trapezoid.reset(eliminated, a);
  HapticTrapezoid haptic(without, dt, newton);
  haptic.attach(held);
  haptic.reset(b);
  double worst = 0, largest = 0, field_worst = 0, field_largest = 0;
  for (long n = 1; n <= steps; ++n) {
    trapezoid.step(a);
    const Vec3 F_haptic = haptic.tick(tools.tools()[0].path.at(a.t), b);
    const Vector F = tools.forces(a.u, a.t);
    worst = std::max(worst, (F_haptic - F.head<3>()).norm());
    largest = std::max(largest, F.head<3>().norm());
    const Vector ua = eliminated_field(a.u, a.t), ub = haptic_field(b.u);
    field_worst = std::max(field_worst, (ua - ub).cwiseAbs().maxCoeff());
    field_largest = std::max(field_largest, ua.cwiseAbs().maxCoeff());
  }
  EXPECT_LT(field_worst, 1e-10 * field_largest);
  EXPECT_GT(largest, 0.0);
  return worst / largest;
}

TEST(HapticTrapezoid, EqualsEliminationOnADampedBeamUnderGravity) {
  const test::Beam beam;
  const auto material = fem::Material::from_young_poisson(3000, 0.45, 1000, 0.8);
  const std::vector<model::SetLoad> gravity{
      {.set = "", .force = Vec3::Zero(), .ramp = model::Ramp{0.1}, .gravity = Vec3(0, 0, -9.81)}};
  const model::SetTool tool{.name = "hand",
                            .set = "x1",
                            .center = Vec3::Zero(),
                            .radius = 0,
                            .path = {.displacement = Vec3(0, 1e-3, 2e-3),
                                     .ramp = model::Ramp{.duration = 0.2, .shape = model::Ramp::Shape::smooth, .samples = {}}}};
  const model::FemModel with_tool = model::build_fem_model(beam.mesh, material, {"x0"}, gravity, {tool});
  const model::FemModel without = model::build_fem_model(beam.mesh, material, {"x0"}, gravity);
  const double relative = haptic_against_elimination(
      with_tool.system, with_tool.tools, without.system, node_dofs(*without.dofs, beam.mesh.set("x1").nodes),
      [&](const Vector& u, double t) { return with_tool.displacement(u, t); },
      [&](const Vector& u) { return Vector(without.dofs->expand(u)); }, 0.01, 60);
  EXPECT_LT(relative, 1e-10);
}

/// The beam of the tests above with a neo-Hookean material, its end held by the hand and moved
/// 15 mm down and 5 mm sideways over 0.2 s (smooth).
struct NeoHookeanHeldBeam {
  test::Beam beam;
  fem::Material material = [] {
    fem::Material m = fem::Material::from_young_poisson(3000, 0.45, 1000, 0.8);
    m.model = fem::MaterialModel::neo_hookean;
    return m;
  }();
  model::SetTool tool{.name = "hand",
                      .set = "x1",
                      .center = Vec3::Zero(),
                      .radius = 0,
                      .path = {.displacement = Vec3(0, 5e-3, -15e-3),
                               .ramp = model::Ramp{.duration = 0.2, .shape = model::Ramp::Shape::smooth, .samples = {}}}};
  model::FemModel with_tool = model::build_fem_model(beam.mesh, material, {"x0"}, {}, {tool});
  model::FemModel without = model::build_fem_model(beam.mesh, material, {"x0"}, {});
};

TEST(HapticTrapezoid, ANeoHookeanTickConvergedEqualsEliminationByNewton) {
  // Two formulations of the same nonlinear step: the tool eliminated and the step solved by Newton
  // with the tangent (Trapezoid), and the tool held through the linear compliance with the step
  // solved by modified Newton on the fixed K_eff (the haptic tick), iterated to convergence.
  const NeoHookeanHeldBeam b;
  ASSERT_TRUE(b.without.system.is_nonlinear());
  const double relative = haptic_against_elimination(
      b.with_tool.system, b.with_tool.tools, b.without.system, node_dofs(*b.without.dofs, b.beam.mesh.set("x1").nodes),
      [&](const Vector& u, double t) { return b.with_tool.displacement(u, t); },
      [&](const Vector& u) { return Vector(b.without.dofs->expand(u)); }, 0.01, 40,
      HapticNewton{.iterations = 200, .tolerance = 1e-12});
  std::printf("neo-Hookean beam, end held and moved 15.8 mm: the converged haptic tick's force against elimination: %.2e\n",
              relative);
  EXPECT_LT(relative, 1e-9);
}

TEST(HapticTrapezoid, ANeoHookeanTickWithAFixedBudgetApproachesTheConvergedForce) {
  const NeoHookeanHeldBeam b;
  const auto held = node_dofs(*b.without.dofs, b.beam.mesh.set("x1").nodes);
  const double dt = 1e-3;  // the device's 1 kHz
  auto forces = [&](HapticNewton newton, std::vector<double>* residuals) {
    HapticTrapezoid haptic(b.without.system, dt, newton);
    haptic.attach(held);
    model::State s = model::State::at_rest(b.without.system.size());
    haptic.reset(s);
    std::vector<Vec3> out;
    for (long n = 1; n <= 300; ++n) {
      out.push_back(haptic.tick(b.tool.path.at(static_cast<double>(n) * dt), s));
      if (residuals) residuals->push_back(haptic.last_residual());
    }
    return out;
  };
  const auto converged = forces({.iterations = 200, .tolerance = 1e-12}, nullptr);
  double largest = 0;
  for (const Vec3& F : converged) largest = std::max(largest, F.norm());
  std::vector<double> errors;
  for (const int budget : {1, 2, 3}) {
    std::vector<double> residuals;
    const auto F = forces({.iterations = budget, .tolerance = 0}, &residuals);
    double worst = 0;
    for (std::size_t k = 0; k < F.size(); ++k) worst = std::max(worst, (F[k] - converged[k]).norm());
    errors.push_back(worst / largest);
    std::printf("budget %d: force error %.2e of the peak %.4f N, largest residual after the budget %.2e\n", budget, errors.back(),
                largest, *std::max_element(residuals.begin(), residuals.end()));
  }
  EXPECT_LT(errors[1], errors[0]);
  EXPECT_LT(errors[2], errors[1]);
  EXPECT_LT(errors[2], 1e-3);
}

TEST(HapticTrapezoid, EqualsEliminationOnTheCondensedPaperBrain) {
  // Setup 1's ROI (306 nodes nearest the opening) condensed with and without a spatula on the
  // right wall: the haptic loop on the tool-free condensed model (dense interface block) gives
  // the eliminated model's force.
  const test::PaperBrain brain;
  const model::SetTool spatula{.name = "right",
                               .set = "opening_right",
                               .center = Vec3::Zero(),
                               .radius = 0,
                               .path = {.displacement = Vec3(2e-3, 0, 0), .ramp = model::Ramp{0.5}}};
  const model::FemModel with_tool = model::build_fem_model(brain.mesh, fem::material_preset("paper"), {"base"}, {}, {spatula});
  const roi::RoiSpec spec = test::nearest(306);
  std::vector<int> roi_nodes = roi::select_roi_nodes(brain.mesh, *with_tool.dofs_with_tools, spec);
  const roi::Partition without_partition = roi::partition_dofs(brain.model.system.K, brain.dofs(), roi_nodes);
  const condensation::ReducedModel without(brain.model.system, without_partition, brain.dofs());
  const std::vector<int>& wall = brain.mesh.set("opening_right").nodes;
  std::erase_if(roi_nodes, [&](int n) { return std::binary_search(wall.begin(), wall.end(), n); });
  const roi::Partition with_partition = roi::partition_dofs(with_tool.system.K, *with_tool.dofs, roi_nodes);
  const condensation::ReducedModel eliminated(with_tool.system, with_partition, *with_tool.dofs);
  const model::ToolSet tools = simulation::tools_in_reduced(with_tool, with_partition, eliminated.system().size());

  // Compare the walls' loads-free models over the ROI nodes both integrate (the free ones).
  const roi::NodeDofs in_eliminated = roi::node_dofs_in_reduced(roi_nodes, with_partition, *with_tool.dofs);
  const roi::NodeDofs in_without = roi::node_dofs_in_reduced(roi_nodes, without_partition, brain.dofs());
  auto gather = [](const roi::NodeDofs& nodes, const Vector& u) {
    Vector out(3 * static_cast<Index>(nodes.size()));
    for (std::size_t n = 0; n < nodes.size(); ++n)
      for (std::size_t c = 0; c < 3; ++c) out[static_cast<Index>(3 * n + c)] = nodes[n][c] >= 0 ? u[nodes[n][c]] : 0.0;
    return out;
  };
  // The tool-free model carries the paper's 1 mN forces: take them off, the eliminated one has none.
  model::SecondOrderSystem unloaded = without.system();
  unloaded.load = model::LoadHistory(unloaded.size());
  const double relative = haptic_against_elimination(
      eliminated.system(), tools, unloaded, roi::node_dofs_in_reduced(wall, without_partition, brain.dofs()),
      [&](const Vector& u, double) { return gather(in_eliminated, u); }, [&](const Vector& u) { return gather(in_without, u); },
      0.05, 40);
  EXPECT_LT(relative, 1e-9);
}

TEST(HapticTrapezoid, ItsComplianceIsTheHeldBlockOfTheInverseEffectiveStiffness) {
  const test::Beam beam;
  const double dt = 0.01;
  HapticTrapezoid haptic(beam.model.system, dt);
  const std::vector<int>& nodes = beam.mesh.set("x1").nodes;
  haptic.attach(node_dofs(*beam.model.dofs, nodes));
  const model::AverageAcceleration rule(dt);
  const DenseMatrix inverse = DenseMatrix(rule.effective_stiffness(beam.model.system)).inverse();
  std::vector<Index> held;
  for (const auto& d : node_dofs(*beam.model.dofs, nodes)) held.insert(held.end(), d.begin(), d.end());
  const DenseMatrix& W = haptic.compliance();
  ASSERT_EQ(W.rows(), static_cast<Index>(held.size()));
  double worst = 0;
  for (std::size_t i = 0; i < held.size(); ++i)
    for (std::size_t j = 0; j < held.size(); ++j)
      worst = std::max(worst, std::abs(W(static_cast<Index>(i), static_cast<Index>(j)) - inverse(held[i], held[j])));
  EXPECT_LT(worst, 1e-10 * inverse.cwiseAbs().maxCoeff());
}

TEST(HapticTrapezoid, RefusesAToolOnNoNodeOutsideTheSystemOrHeldTwice) {
  const test::Beam beam;
  HapticTrapezoid haptic(beam.model.system, 0.01);
  const Index n = beam.model.system.size();
  EXPECT_THROW(haptic.attach({}), InputError);
  EXPECT_THROW(haptic.attach({{0, 1, n}}), InputError);
  EXPECT_THROW(haptic.attach({{0, 1, 2}, {3, 4, 2}}), InputError);
  model::State s = model::State::at_rest(n);
  haptic.reset(s);
  EXPECT_THROW(haptic.tick(Vec3::Zero(), s), Error);  // nothing attached
}

/// The beam's tetrahedra in the cell x in [20, 30] mm, z above 10 mm: a cut halfway through.
std::vector<Index> beam_cut(const mesh::TetMesh& mesh) {
  std::vector<Index> out;
  for (Index e = 0; e < mesh.num_tets(); ++e) {
    Vec3 centre = Vec3::Zero();
    for (const int n : mesh.tets[static_cast<std::size_t>(e)]) centre += mesh.node(n) / 4;
    if (centre.x() > 0.020 && centre.x() < 0.030 && centre.z() > 0.010) out.push_back(e);
  }
  return out;
}

/// The change removing `removed` makes to `dofs`' system (no node left without an element).
model::SystemChange beam_change(const test::Beam& beam, const std::vector<Index>& removed) {
  fem::ElementRemover remover(beam.mesh, *beam.model.dofs, beam.model.materials);
  const fem::ElementRemoval removal = remover.remove(removed, 0.0);
  EXPECT_TRUE(removal.orphan_nodes.empty());
  std::vector<Index> same(static_cast<std::size_t>(beam.model.dofs->num_free()));
  std::iota(same.begin(), same.end(), Index{0});
  return model::SystemChange::from_removal(removal, *beam.model.dofs, same, beam.model.system.load.terms().size());
}

/// The beam's model assembled from scratch on its mesh without the tetrahedra `removed` (the same free numbering).
model::FemModel beam_rebuilt_without(const test::Beam& beam, const std::vector<Index>& removed) {
  mesh::TetMesh cut_mesh = beam.mesh;
  cut_mesh.tets.clear();
  for (Index e = 0; e < beam.mesh.num_tets(); ++e)
    if (std::find(removed.begin(), removed.end(), e) == removed.end())
      cut_mesh.tets.push_back(beam.mesh.tets[static_cast<std::size_t>(e)]);
  cut_mesh.sets.erase("box");
  return model::build_fem_model(cut_mesh, beam.model.material, {"x0"}, {});
}

/// The hand holding the beam's far end: a sideways wobble on a 1 mm pull over 20 ms.
Vec3 beam_hand(double t) { return Vec3(0, 0.0005 * std::sin(20 * t), 0.001 * std::min(t / 0.02, 1.0)); }

TEST(HapticTrapezoid, ACutTakenByTheCorrectionFeelsAsTheModelRebuiltFromTheCutMesh) {
  // The beam's far end held by the hand; a cut halfway through its middle, at rest and mid-run.
  // Against the model assembled from the cut mesh, with the tool attached afresh there and started
  // from the state at the cut: the compliance W and the next 60 ticks' force, to round-off.
  const test::Beam beam;
  const std::vector<Index> removed = beam_cut(beam.mesh);
  ASSERT_EQ(removed.size(), 12u);
  const model::FemModel rebuilt = beam_rebuilt_without(beam, removed);
  ASSERT_EQ(rebuilt.system.size(), beam.model.system.size());  // the same free numbering
  const auto held = node_dofs(*beam.model.dofs, beam.mesh.set("x1").nodes);
  const double dt = 1e-3;
  const auto hand = beam_hand;

  for (const long cut_after : {0L, 15L}) {
    model::SecondOrderSystem system = beam.model.system;
    system.load = model::LoadHistory(system.size());  // the hand alone
    HapticTrapezoid haptic(system, dt);
    haptic.attach(held);
    model::State s = model::State::at_rest(system.size());
    haptic.reset(s);
    for (long n = 0; n < cut_after; ++n) haptic.tick(hand(static_cast<double>(n + 1) * dt), s);
    model::SystemChange change = beam_change(beam, removed);
    change.loads.assign(system.load.terms().size(), Vector());
    change.apply(system);
    haptic.take_change(change, s);

    HapticTrapezoid fresh(rebuilt.system, dt);
    fresh.attach(held);
    const double W_gap =
        (haptic.compliance() - fresh.compliance()).cwiseAbs().maxCoeff() / fresh.compliance().cwiseAbs().maxCoeff();
    EXPECT_LT(W_gap, 1e-13) << "cut after " << cut_after << " ticks";
    // From the state at the cut, the rebuilt model's acceleration its own (consistent with it);
    // mid-run this checks the acceleration take_change made consistent at the cut's dofs.
    model::State r = s;
    fresh.reset(r);
    double worst = 0, largest = 0;
    for (long n = cut_after + 1; n <= cut_after + 60; ++n) {
      const Vec3 F = haptic.tick(hand(static_cast<double>(n) * dt), s),
                 F_rebuilt = fresh.tick(hand(static_cast<double>(n) * dt), r);
      worst = std::max(worst, (F - F_rebuilt).norm());
      largest = std::max(largest, F_rebuilt.norm());
    }
    EXPECT_LT(worst, 1e-10 * largest) << "cut after " << cut_after << " ticks";
    std::cout << "haptic cut after " << cut_after << " ticks: W against the rebuilt model's " << W_gap << ", force over 60 ticks "
              << worst / largest << '\n';
  }
}

TEST(HapticTrapezoid, ACutWhoseColumnsWereSolvedAheadIsTheSameCut) {
  // The columns K_eff^-1 e_d solved between earlier ticks (as a blade approaches): the same
  // compliance and forces as the cut solved when it comes, to round-off.
  const test::Beam beam;
  const auto held = node_dofs(*beam.model.dofs, beam.mesh.set("x1").nodes);
  const std::vector<Index> removed = beam_cut(beam.mesh);
  const auto hand = beam_hand;
  model::SecondOrderSystem cold_system = beam.model.system, ahead_system = beam.model.system;
  for (auto* s : {&cold_system, &ahead_system}) s->load = model::LoadHistory(s->size());
  HapticTrapezoid cold(cold_system, 1e-3), ahead(ahead_system, 1e-3);
  model::State cold_state = model::State::at_rest(cold_system.size()), ahead_state = cold_state;
  for (auto [h, s] : {std::pair{&cold, &cold_state}, std::pair{&ahead, &ahead_state}}) {
    h->attach(held);
    h->reset(*s);
    for (long n = 1; n <= 10; ++n) h->tick(hand(static_cast<double>(n) * 1e-3), *s);
  }
  model::SystemChange cold_change = beam_change(beam, removed), ahead_change = beam_change(beam, removed);
  ahead.prefetch_change(ahead_change.dofs);
  for (auto [h, s, c, sys] : {std::tuple{&cold, &cold_state, &cold_change, &cold_system},
                              std::tuple{&ahead, &ahead_state, &ahead_change, &ahead_system}}) {
    c->loads.assign(sys->load.terms().size(), Vector());
    c->apply(*sys);
    h->take_change(*c, *s);
  }
  EXPECT_LT((cold.compliance() - ahead.compliance()).cwiseAbs().maxCoeff(), 1e-14 * cold.compliance().cwiseAbs().maxCoeff());
  double worst = 0, largest = 0;
  for (long n = 11; n <= 40; ++n) {
    const Vec3 F = cold.tick(hand(static_cast<double>(n) * 1e-3), cold_state);
    worst = std::max(worst, (F - ahead.tick(hand(static_cast<double>(n) * 1e-3), ahead_state)).norm());
    largest = std::max(largest, F.norm());
  }
  EXPECT_LT(worst, 1e-12 * largest);
}

TEST(HapticTrapezoid, CutsTakenWithTheFactorMadeAfreshInTheBackgroundFeelAsTheOnlyCorrectedLoop) {
  // The beam's cut in four pieces of three tetrahedra, at ticks 5, 10, 15 and 20, the factor made
  // afresh in a second thread and swapped in whenever one is ready: the same force as the loop
  // that only corrects its first factor, to round-off, however the threads interleave; after a
  // swap at a known point (wait_for_background), the compliance is the rebuilt model's.
  const test::Beam beam;
  const auto held = node_dofs(*beam.model.dofs, beam.mesh.set("x1").nodes);
  const std::vector<Index> removed = beam_cut(beam.mesh);
  ASSERT_EQ(removed.size(), 12u);
  const auto hand = [](long n) { return beam_hand(static_cast<double>(n) * 1e-3); };
  model::SecondOrderSystem corrected_system = beam.model.system, background_system = beam.model.system;
  for (auto* s : {&corrected_system, &background_system}) s->load = model::LoadHistory(s->size());
  HapticTrapezoid corrected(corrected_system, 1e-3), background(background_system, 1e-3);
  model::State corrected_state = model::State::at_rest(corrected_system.size()), background_state = corrected_state;
  for (auto [h, s] : {std::pair{&corrected, &corrected_state}, std::pair{&background, &background_state}}) {
    h->attach(held);
    h->reset(*s);
  }
  background.refactor_in_background();
  double worst = 0, largest = 0;
  for (long n = 1; n <= 100; ++n) {
    if (n % 5 == 0 && n <= 20) {
      const auto first = static_cast<std::ptrdiff_t>(3 * (n / 5 - 1));
      const std::vector<Index> piece(removed.begin() + first, removed.begin() + first + 3);
      for (auto [h, s, sys] : {std::tuple{&corrected, &corrected_state, &corrected_system},
                               std::tuple{&background, &background_state, &background_system}}) {
        model::SystemChange change = beam_change(beam, piece);
        change.loads.assign(sys->load.terms().size(), Vector());
        change.apply(*sys);
        h->take_change(change, *s);
      }
    }
    if (n == 30) background.wait_for_background();
    const Vec3 F = corrected.tick(hand(n), corrected_state), F_background = background.tick(hand(n), background_state);
    worst = std::max(worst, (F - F_background).norm());
    largest = std::max(largest, F.norm());
  }
  EXPECT_LT(worst, 1e-10 * largest);
  EXPECT_GE(background.background_factors(), 1);

  const model::FemModel rebuilt = beam_rebuilt_without(beam, removed);
  HapticTrapezoid fresh(rebuilt.system, 1e-3);
  fresh.attach(held);
  const double W_gap =
      (background.compliance() - fresh.compliance()).cwiseAbs().maxCoeff() / fresh.compliance().cwiseAbs().maxCoeff();
  EXPECT_LT(W_gap, 1e-13);
  std::cout << "background refactorization: " << background.background_factors() << " factors swapped in; force against the "
            << "only corrected loop over 100 ticks " << worst / largest << ", W against the rebuilt model's " << W_gap << '\n';
}

TEST(HapticTrapezoid, ACutReachingTheToolIsRefused) {
  const test::Beam beam;
  model::SecondOrderSystem system = beam.model.system;
  HapticTrapezoid haptic(system, 1e-3);
  haptic.attach(node_dofs(*beam.model.dofs, beam.mesh.set("x1").nodes));
  model::State s = model::State::at_rest(system.size());
  haptic.reset(s);
  std::vector<Index> at_the_end;
  for (Index e = 0; e < beam.mesh.num_tets(); ++e)
    for (const int n : beam.mesh.tets[static_cast<std::size_t>(e)])
      if (beam.mesh.node(n).x() > 0.0599 && std::find(at_the_end.begin(), at_the_end.end(), e) == at_the_end.end())
        at_the_end.push_back(e);
  EXPECT_THROW(haptic.take_change(beam_change(beam, {at_the_end.front()}), s), InputError);
}

}  // namespace
}  // namespace roifem::integrators
