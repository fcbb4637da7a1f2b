// SPDX-License-Identifier: GPL-3.0-or-later
// The error budget (experiments/error_budget.hpp) on a small brain: the space error against the
// same mesh regenerated vanishes, and the time error is the trapezoidal rule's own, as a run at dt / 32
// measures it.
#include "experiments/error_budget.hpp"

#include <gtest/gtest.h>

#include <sstream>

#include "common/errors.hpp"
#include "integrators/trapezoid.hpp"
#include "mesh/brain_mesh.hpp"
#include "roi/roi.hpp"
#include "test_support.hpp"

namespace roifem::experiments {
namespace {

struct Brain {
  // A small brain (about 300 nodes): the dense modal solution stays cheap, under ASan too.
  mesh::TetMesh mesh = mesh::generate_brain_mesh(300).mesh;
  model::FemModel full = model::build_fem_model(mesh, fem::material_preset("paper"), {"base"},
                                                {{"opening_left", Vec3(-0.016, 0, 0), model::Ramp{0}, std::nullopt},
                                                 {"opening_right", Vec3(0.016, 0, 0), model::Ramp{0}, std::nullopt}});
  BudgetInput input(double dt, long steps) const {
    const roi::RoiSpec spec{.kind = roi::RoiSpec::Kind::nearest, .center = Vec3(0, 0, 0.04), .radius = 0, .count = 60, .set = {}};
    BudgetInput in{.full = &full,
                   .fixed_sets = {"base"},
                   .force_N = 0.016,
                   .dt = dt,
                   .steps = steps,
                   .ramps_s = {0.5},
                   .setups = {{"near", roi::select_roi_nodes(mesh, *full.dofs, spec)}},
                   .reduction = {}};
    const std::vector<double> zero(static_cast<std::size_t>(steps), 0.0);
    in.reduction = {{ErrorCurve{zero, zero}}};
    return in;
  }
};

/// The full model's ROI displacements per step under the paper's 0.5 s ramp, by the trapezoidal
/// rule at dt / refine, read at the steps of dt.
std::vector<Vector> trapezoid_run(const model::FemModel& full, double dt, long steps, int refine) {
  model::SecondOrderSystem system = full.system;
  system.load = full.system.load.with_ramp(model::Ramp{0.5});
  integrators::Trapezoid trapezoid(dt / refine);
  model::State state = model::State::at_rest(system.size());
  trapezoid.reset(system, state);
  std::vector<Vector> u;
  for (long k = 0; k < steps * refine; ++k) {
    trapezoid.step(state);
    if ((k + 1) % refine == 0) u.push_back(full.dofs->expand(state.u));
  }
  return u;
}

TEST(ErrorBudget, SpaceErrorVanishesAgainstTheSameMeshAndTimeErrorIsTheTrapezoidalRulesOwn) {
  const Brain brain;
  std::ostringstream log;
  const test::TempDir scratch;  // each run its own
  const auto dir = scratch / "budget";
  const double dt = 0.05;
  const long steps = 20;
  const BudgetInput input = brain.input(dt, steps);
  // The reference: the same recipe (the mesher gives the same file for the same request), the same element.
  const ErrorBudget budget = measure_error_budget(
      input, {.reference_nodes = 300, .reference_element = fem::Element::tet4, .model_error = false}, dir, log);
  ASSERT_EQ(budget.entries.size(), 1u);
  const BudgetEntry& e = budget.entries.front();
  EXPECT_LT(e.space.peak(), 1e-9);
  EXPECT_NEAR(budget.reference_opening_error_pct, 0, 1e-9);
  EXPECT_EQ(e.dominant, "time");
  // A second method for the time error: the distance to the same rule at dt / 32 (whose own error
  // is a few percent of it), per step, at the worst ROI node.
  const auto coarse = trapezoid_run(brain.full, dt, steps, 1), fine = trapezoid_run(brain.full, dt, steps, 32);
  for (long k : {9L, 14L, 19L}) {
    double worst = 0;
    for (int n : input.setups.front().second)
      worst = std::max(
          worst,
          (coarse[static_cast<std::size_t>(k)].segment<3>(3 * n) - fine[static_cast<std::size_t>(k)].segment<3>(3 * n)).norm() /
              mm);
    EXPECT_GT(worst, 1e-3);  // mm: the rule's error at dt = 0.05 s is real
    EXPECT_NEAR(e.time.max[static_cast<std::size_t>(k)] / worst, 1.0, 0.1) << "step " << k + 1;
  }
}

TEST(ErrorBudget, OneUnitSlopeRunGivesEveryRampsTrapezoidalRunBySuperposition) {
  const Brain brain;
  const auto slope = unit_slope_run(brain.full, 0.05, 30, [](const Vector& u) { return u; });
  for (const double ramp : {0.05, 0.5, 1.0}) {
    model::SecondOrderSystem system = brain.full.system;
    system.load = brain.full.system.load.with_ramp(model::Ramp{ramp});
    integrators::Trapezoid trapezoid(0.05);
    model::State state = model::State::at_rest(system.size());
    trapezoid.reset(system, state);
    const auto superposed = ramp_response(slope, ramp, 0.05);
    ASSERT_EQ(superposed.size(), 30u);
    for (const auto& u : superposed) {
      trapezoid.step(state);
      const Vector direct = brain.full.displacement(state.u, state.t);
      EXPECT_LT((u - direct).norm(), 1e-11 * direct.norm()) << "ramp " << ramp << ", t = " << state.t;
    }
  }
  EXPECT_THROW(ramp_response(slope, 0.07, 0.05), InputError);
}

}  // namespace
}  // namespace roifem::experiments
