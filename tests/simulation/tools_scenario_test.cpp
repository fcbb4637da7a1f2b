// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <sstream>

#include "common/errors.hpp"
#include "h5_read.hpp"
#include "integrators/factory.hpp"
#include "integrators/trapezoid.hpp"
#include "model/energy.hpp"
#include "model/modal_reference.hpp"
#include "scenario/scenario.hpp"
#include "simulation/scenario_model.hpp"
#include "simulation/scenario_run.hpp"
#include "test_support.hpp"

namespace roifem::simulation {
namespace {

/// The paper's brain with two spatulas on the opening's walls, each moved `mm` outwards over 0.5 s,
/// the material's law `law`, and `roi` (TOML, may be empty).
scenario::Scenario spatulas(const std::string& roi, long steps = 40, const std::string& mm = "1.0",
                            const std::string& law = "linear") {
  const std::string text =
      "mesh = \"" + std::string(ROIFEM_MESH_DIR) + "/brain-800.msh\"\n" + "[material]\npreset = \"paper\"\nmodel = \"" + law +
      "\"\n" + "[[tool]]\nname = \"left\"\nset = \"opening_left\"\ndisplacement_mm = [-" + mm + ", 0, 0]\nramp_s = 0.5\n" +
      "[[tool]]\nname = \"right\"\nset = \"opening_right\"\ndisplacement_mm = [" + mm + ", 0, 0]\nramp_s = 0.5\n" + roi +
      "[time]\ndt_s = 0.05\nsteps = " + std::to_string(steps) + "\n[output]\nfield_every = 0\n";
  return scenario::parse_scenario(text, "spatulas.toml", ROIFEM_MESH_DIR);
}

const std::string setup1 = "[roi]\nkind = \"nearest\"\ntarget_mm = [0, 0, 40]\nnodes = 306\n";

/// The static tool forces of a model (K u = f at t after the ramp).
Vector static_forces(const ScenarioModel& m, double t) {
  const Vector u = DenseMatrix(m.system().K).llt().solve(m.system().load.at(t));
  return m.tools.forces(u, t);
}

TEST(ToolsScenario, TheCondensedModelFeelsTheFullModelsStaticToolForces) {
  // Static condensation is exact at rest: the ROI model's tools feel what the full model's do.
  const auto full = build_scenario_model(spatulas(""));
  const auto condensed = build_scenario_model(spatulas(setup1));
  ASSERT_EQ(condensed->tools.count(), 2);
  const Vector F_full = static_forces(*full, 1.0), F_roi = static_forces(*condensed, 1.0);
  std::printf("static spatula forces (mN): full (%.4f, %.4f, %.4f | %.4f, %.4f, %.4f), condensed differs by %.1e relative\n",
              F_full[0] * 1e3, F_full[1] * 1e3, F_full[2] * 1e3, F_full[3] * 1e3, F_full[4] * 1e3, F_full[5] * 1e3,
              (F_roi - F_full).norm() / F_full.norm());
  EXPECT_LT((F_roi - F_full).norm(), 1e-9 * F_full.norm());
  EXPECT_LT(F_full[0], 0);  // the left spatula pulls left, the right one right
  EXPECT_GT(F_full[3], 0);
}

TEST(ToolsScenario, AToolBesideTheStaticPartIsRefusedNamingBoth) {
  try {
    build_scenario_model(spatulas("[roi]\nkind = \"nearest\"\ntarget_mm = [0, 0, 40]\nnodes = 5\n"));
    FAIL() << "expected a ModelError";
  } catch (const ModelError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("tool '"), std::string::npos) << what;
    EXPECT_NE(what.find("shares an element with node"), std::string::npos) << what;
    EXPECT_NE(what.find("which is in the static part"), std::string::npos) << what;
  }
}

TEST(ToolsScenario, ARunWritesEachToolsForceAndKeepsTheBalance) {
  const auto sc = spatulas(setup1, 30);
  const test::TempDir dir;
  std::ostringstream log;
  run_scenario(sc, dir.path(), log);
  const auto force = test::read_h5(dir.path() / "results.h5", "tools/right/force_N");
  const auto position = test::read_h5(dir.path() / "results.h5", "tools/right/displacement_mm");
  ASSERT_EQ(force.size(), 31u * 3);
  EXPECT_DOUBLE_EQ(position[3 * 30], 1.0);  // at the end of the ramp (t = 1.5 s)
  EXPECT_DOUBLE_EQ(position[3 * 5], 0.5);   // half way
  EXPECT_EQ(force[0], 0.0);                 // at rest
  // The force written at the last step is the model's for the last state: recompute it.
  const auto built = build_scenario_model(sc);
  model::State s = model::State::at_rest(built->system().size());
  integrators::Trapezoid trapezoid(sc.dt);
  trapezoid.reset(built->system(), s);
  model::EnergyLedger ledger(built->system(), s, &built->tools);
  for (int n = 1; n <= 30; ++n) {
    trapezoid.advance_to(n * sc.dt, s);
    ledger.record(s);
  }
  const Vector F = built->tools.forces(s.u, s.t);
  for (int c = 0; c < 3; ++c) EXPECT_DOUBLE_EQ(force[3 * 30 + c], F[3 + c]);
  EXPECT_LT(std::abs(ledger.balance_residual()), 1e-10 * ledger.tool_work());
  const auto work = test::read_h5(dir.path() / "results.h5", "energy/tool_work_J");
  EXPECT_DOUBLE_EQ(work.back(), ledger.tool_work());
  EXPECT_NE(log.str().find("tool 'right': force on the tissue"), std::string::npos) << log.str();
}

TEST(ToolsScenario, TheDaeFormsOfTheCondensedModelMeetItsExactSolution) {
  // Static condensation keeps the tools' dofs in its DAE form (the full model condensed onto the
  // ROI and the tools' nodes): by name, each form meets the eliminated condensed model's exact
  // (modal) solution and its exact tool forces.
  const auto built = build_scenario_model(spatulas(setup1));
  const model::SecondOrderSystem& system = built->system();
  ASSERT_TRUE(system.constrained);
  const model::ModalReference exact(system, model::State::at_rest(system.size()));
  const double t = 0.05;
  const Vector u = exact.displacement(t), F = built->tools.forces(u, t);
  for (const char* name : {"ida-ggl"}) {  // (index 1 and 3: on the beam and the box, cheaper)
    auto dae = integrators::make_integrator(name, {.dt = t, .adaptive = true, .rtol = 1e-8, .atol = 1e-14});
    model::State s = model::State::at_rest(system.size());
    dae->reset(system, s);
    dae->advance_to(t, s);
    const auto held = dae->constraints();
    ASSERT_TRUE(held.has_value());
    std::printf("%s on setup 1 with spatulas: displacement error %.1e, tool force error %.1e (relative), drift %.1e mm\n", name,
                (s.u - u).norm() / u.norm(), (held->forces - F).norm() / F.norm(), held->position_drift / mm);
    EXPECT_LT((s.u - u).norm(), 1e-6 * u.norm()) << name;
    EXPECT_LT((held->forces - F).norm(), 1e-6 * F.norm()) << name;
    EXPECT_LT(held->position_drift, 1e-8 * mm) << name;
  }
}

TEST(ToolsScenario, TheDaeFormsTakeANeoHookeanModelByNewtonAndMeetATightRunOfTheEliminatedCondensedOne) {
  // The spatulas 3 mm out on the neo-Hookean brain, full and as the hybrid ROI (setup 1): each
  // tools' DAE form, and on the hybrid the ROI uncondensed (ida-roi-dae), the law's tangent their
  // Jacobian, against a tight ida-bdf5 run of the tools eliminated and the ROI condensed (a second
  // method on the same equations): displacements and the spatulas' forces.
  auto neo_hookean = [](const std::string& roi, const std::string& law = "neo-hookean") { return spatulas(roi, 2, "3.0", law); };
  const double t = 0.02;
  for (const std::string& roi : {setup1, std::string()}) {
    const auto built = build_scenario_model(neo_hookean(roi));
    const model::SecondOrderSystem& system = built->system();
    ASSERT_TRUE(system.is_nonlinear());
    ASSERT_TRUE(system.constrained);
    auto reference = integrators::make_integrator("ida-bdf5", {.dt = t, .adaptive = true, .rtol = 1e-9, .atol = 1e-13});
    model::State r = model::State::at_rest(system.size());
    reference->reset(system, r);
    reference->advance_to(t, r);
    const Vector F = built->tools.forces(r.u, t);
    // The law matters here: the linear model's forces at the same displacement differ.
    const auto linear = build_scenario_model(neo_hookean(roi, "linear"));
    ASSERT_FALSE(linear->system().is_nonlinear());
    const double law_share = (linear->tools.forces(r.u, t) - F).norm() / F.norm();
    const std::vector<std::string> forms = roi.empty()
                                               ? std::vector<std::string>{"ida-ggl"}
                                               : std::vector<std::string>{"ida-index3", "ida-ggl", "ida-index1", "ida-roi-dae"};
    for (const std::string& name : forms) {
      auto dae = integrators::make_integrator(name, {.dt = t, .adaptive = true, .rtol = 1e-7, .atol = 1e-11});
      ASSERT_TRUE(dae->takes_nonlinear()) << name;
      model::State s = model::State::at_rest(system.size());
      dae->reset(system, s);
      dae->advance_to(t, s);
      const auto held = dae->constraints();  // ida-roi-dae: the tools eliminated, their forces from the state
      const Vector F_dae = held ? held->forces : built->tools.forces(s.u, t);
      const double drift = held ? held->position_drift : 0.0;
      const integrators::Stats st = dae->stats();
      std::printf(
          "%s on the neo-Hookean brain (%s), spatulas 3 mm: displacement %.1e, tool force %.1e from a tight ida-bdf5 run "
          "(relative; the law changes the force by %.1e), drift %.1e mm; %ld steps, %ld Newton, %ld Jacobians\n",
          name.c_str(), roi.empty() ? "full" : "hybrid ROI, setup 1", (s.u - r.u).norm() / r.u.norm(),
          (F_dae - F).norm() / F.norm(), law_share, drift / mm, st.steps, st.nonlinear_iterations, st.jac_evals);
      EXPECT_LT((s.u - r.u).norm(), 1e-5 * r.u.norm()) << name;
      EXPECT_LT((F_dae - F).norm(), 1e-5 * F.norm()) << name;
      EXPECT_GT(law_share, 1e3 * (F_dae - F).norm() / F.norm()) << name;
      EXPECT_GT(st.jac_evals, 1) << name << ": the Jacobian moves with the state";
    }
  }
}

TEST(ToolsScenario, TheDaeFormsUnderCraigBamptonMeetItsExactSolution) {
  // A reduction that carries the static part's mass (a dense interface block in M, modal
  // coordinates; Guyan is the same without modes): the tool-kept model reduced alike (same static
  // part, same modes) holds the tools by multipliers, and meets the eliminated reduced model's
  // exact (modal) solution and tool forces (Guyan, by hand: 1.6e-8 and 7.9e-10). POD learns its
  // basis from the eliminated model's loads, so the tool-kept model has none to share: refused.
  for (const std::string reduction : {"reduction = \"craig-bampton\"\nmodes = 10\n"}) {
    const auto built = build_scenario_model(spatulas(setup1 + reduction));
    const model::SecondOrderSystem& system = built->system();
    ASSERT_TRUE(system.constrained) << reduction;
    const model::ModalReference exact(system, model::State::at_rest(system.size()));
    const double t = 0.05;
    const Vector u = exact.displacement(t), F = built->tools.forces(u, t);
    auto dae = integrators::make_integrator("ida-ggl", {.dt = t, .adaptive = true, .rtol = 1e-8, .atol = 1e-14});
    model::State s = model::State::at_rest(system.size());
    dae->reset(system, s);
    dae->advance_to(t, s);
    const auto held = dae->constraints();
    ASSERT_TRUE(held.has_value());
    std::printf(
        "ida-ggl on setup 1 (%s) with spatulas: displacement error %.1e, tool force error %.1e (relative), drift %.1e mm\n",
        reduction.substr(13, reduction.find('"', 13) - 13).c_str(), (s.u - u).norm() / u.norm(),
        (held->forces - F).norm() / F.norm(), held->position_drift / mm);
    EXPECT_LT((s.u - u).norm(), 1e-6 * u.norm()) << reduction;
    EXPECT_LT((held->forces - F).norm(), 1e-6 * F.norm()) << reduction;
    EXPECT_LT(held->position_drift, 1e-8 * mm) << reduction;
  }
  const auto pod = build_scenario_model(spatulas(setup1 + "reduction = \"pod\"\nmodes = 10\n"));
  EXPECT_FALSE(pod->system().constrained);
  auto dae = integrators::make_integrator("ida-ggl", {.dt = 0.05, .adaptive = true, .rtol = 1e-8, .atol = 1e-14});
  model::State s = model::State::at_rest(pod->system().size());
  try {
    dae->reset(pod->system(), s);
    ADD_FAILURE() << "ida-ggl ran on a POD reduction";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("POD"), std::string::npos) << e.what();
  }
}

TEST(ToolsScenario, TheUncondensedRoiDaeWithToolsMeetsTheCondensedModelsExactSolution) {
  // ida-roi-dae integrates setup 1 uncondensed (the static part algebraic, the spatulas
  // eliminated): its ROI state is the condensed model's, so it meets that model's exact (modal)
  // solution and exact tool forces (over the first step: the linear ramp's jump in velocity at
  // t = 0 excites the stiffest modes, which IDA's BDF resolves with steps of 5e-5 s).
  const auto built = build_scenario_model(spatulas(setup1));
  const model::SecondOrderSystem& system = built->system();
  ASSERT_TRUE(system.uncondensed);
  const model::ModalReference exact(system, model::State::at_rest(system.size()));
  auto dae = integrators::make_integrator("ida-roi-dae", {.dt = 0.05, .adaptive = true, .rtol = 1e-8, .atol = 1e-14});
  model::State s = model::State::at_rest(system.size());
  dae->reset(system, s);
  for (const double t : {0.025, 0.05}) {
    dae->advance_to(t, s);
    const Vector u = exact.displacement(t), F = built->tools.forces(u, t), F_dae = built->tools.forces(s.u, t);
    std::printf("ida-roi-dae on setup 1 with spatulas, t = %g s: displacement error %.1e, tool force error %.1e (relative)\n", t,
                (s.u - u).norm() / u.norm(), (F_dae - F).norm() / F.norm());
    EXPECT_LT((s.u - u).norm(), 1e-6 * u.norm()) << t;
    EXPECT_LT((F_dae - F).norm(), 1e-6 * F.norm()) << t;
    EXPECT_LT((s.v - exact.velocity(t)).norm(), 1e-5 * exact.velocity(t).norm()) << t;
  }
  std::printf("  %ld steps, %ld residuals, %ld Jacobians\n", dae->stats().steps, dae->stats().rhs_evals, dae->stats().jac_evals);
  // Not a static condensation: refused by name.
  const auto full = build_scenario_model(spatulas(""));
  auto refused = integrators::make_integrator("ida-roi-dae", {.dt = 0.05, .adaptive = true, .rtol = 1e-8, .atol = 1e-14});
  model::State f = model::State::at_rest(full->system().size());
  try {
    refused->reset(full->system(), f);
    ADD_FAILURE() << "ida-roi-dae ran without an [roi]";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("reduction = \"static\""), std::string::npos) << e.what();
  }
}

TEST(ToolsScenario, ToolTablesAreReadStrictlyAndWrittenBack) {
  const auto sc = spatulas(setup1);
  ASSERT_EQ(sc.tools.size(), 2u);
  EXPECT_EQ(sc.tools[1].set, "opening_right");
  EXPECT_DOUBLE_EQ(sc.tools[1].path.displacement.x(), 1e-3);
  const auto again = scenario::parse_scenario(sc.resolved_toml(), "again.toml", ROIFEM_MESH_DIR);
  ASSERT_EQ(again.tools.size(), 2u);
  EXPECT_EQ(again.tools[0].name, "left");
  EXPECT_EQ(again.tools[0].path.displacement, sc.tools[0].path.displacement);
  auto refused = [](const std::string& tool, const std::string& words) {
    const std::string text = "mesh = \"m.msh\"\n[[tool]]\n" + tool;
    try {
      scenario::parse_scenario(text, "t.toml", "/data");
      ADD_FAILURE() << "accepted: " << tool;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
  };
  refused("set = \"a\"\ncenter_mm = [0, 0, 0]\nradius_mm = 2\ndisplacement_mm = [1, 0, 0]\n", "not both");
  refused("displacement_mm = [1, 0, 0]\n", "missing required key 'tool.set' (or center_mm and radius_mm)");
  refused("center_mm = [0, 0, 0]\nradius_mm = -2\ndisplacement_mm = [1, 0, 0]\n", "'tool.radius_mm' must be positive");
  refused("set = \"a\"\n", "missing required key 'tool.displacement_mm' (or trajectory)");
  refused("set = \"a\"\ntrajectory = \"p.csv\"\ndisplacement_mm = [1, 0, 0]\n",
          "a trajectory or displacement_mm over a ramp, not both");
  refused("set = \"a\"\ntrajectory = \"p.csv\"\nramp_s = 1\n", "not both");
  refused("set = \"a\"\ntrajectory = \"p.csv\"\n", "/data/p.csv: cannot open trajectory file");
  refused("set = \"a\"\ndisplacement_mm = [1, 0, 0]\nramp = 1\n", "unknown key 'tool.ramp' (did you mean 'ramp_s'?)");
  refused(
      "name = \"x\"\nset = \"a\"\ndisplacement_mm = [1, 0, 0]\n[[tool]]\nname = \"x\"\nset = \"b\"\ndisplacement_mm = [1, 0, "
      "0]\n",
      "two [[tool]] tables are named 'x'");
}

}  // namespace
}  // namespace roifem::simulation
