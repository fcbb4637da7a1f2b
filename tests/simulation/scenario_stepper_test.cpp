// SPDX-License-Identifier: GPL-3.0-or-later
// The stepper that programs drive (the Python module) against `roifem run` itself: the same
// states bit for bit, the same energies, the same grid.
#include "simulation/scenario_stepper.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "common/errors.hpp"
#include "h5_read.hpp"
#include "simulation/scenario_run.hpp"
#include "test_support.hpp"

namespace roifem::simulation {
namespace {

scenario::Scenario shipped(const std::string& name) {
  return scenario::read_scenario(std::filesystem::path(ROIFEM_SOURCE_DIR) / "scenarios" / name);
}

TEST(ScenarioStepper, StepsToTheSameStatesAndEnergiesAsTheRunBitForBit) {
  scenario::Scenario sc = shipped("paper-setup1.toml");
  sc.steps = 60;
  test::TempDir dir;
  std::ostringstream log;
  run_scenario(sc, dir.path(), log);
  const std::vector<double> recorded = test::read_h5(dir / "results.h5", "/roi/displacement_mm");
  const std::vector<double> strain = test::read_h5(dir / "results.h5", "/energy/strain_J");
  const std::vector<double> work = test::read_h5(dir / "results.h5", "/energy/external_work_J");

  ScenarioStepper stepper(sc);
  const std::size_t per_step = stepper.roi_displacement_mm().size();
  ASSERT_EQ(per_step, 3 * 306u);
  ASSERT_EQ(recorded.size(), per_step * 61);
  double peak = 0;
  for (long k = 1; k <= sc.steps; ++k) {
    stepper.step();
    const std::vector<double> u = stepper.roi_displacement_mm();
    for (std::size_t i = 0; i < per_step; ++i) {
      ASSERT_EQ(u[i], recorded[static_cast<std::size_t>(k) * per_step + i]) << "step " << k << ", entry " << i;
      peak = std::max(peak, std::abs(u[i]));
    }
    ASSERT_EQ(stepper.energy()->strain(), strain[static_cast<std::size_t>(k)]) << "step " << k;
    ASSERT_EQ(stepper.energy()->external_work(), work[static_cast<std::size_t>(k)]) << "step " << k;
  }
  EXPECT_GT(peak, 1.0);  // mm: the walls did move
  EXPECT_EQ(stepper.state().t, 60 * 0.05);
}

TEST(ScenarioStepper, StepsToATimeAlongTheGridAndReportsTheField) {
  scenario::Scenario sc = shipped("paper-setup2.toml");
  ScenarioStepper stepper(sc, /*energy=*/false);
  EXPECT_EQ(stepper.energy(), nullptr);
  EXPECT_EQ(stepper.step_to(0.5), 10);  // 0.5 / 0.05, despite 10 * 0.05 rounding
  EXPECT_EQ(stepper.step_to(0.52), 0);
  EXPECT_EQ(stepper.step_to(0.55), 1);
  EXPECT_EQ(stepper.steps_taken(), 11);
  // A time that is not finite or not ahead is refused; it used to return 0 (nan) or loop for ever (inf).
  for (const double t : {std::nan(""), HUGE_VAL, 0.55, 0.3}) EXPECT_THROW(stepper.step_to(t), InputError) << t;
  EXPECT_EQ(stepper.steps_taken(), 11);
  const Vector field = stepper.displacement();
  EXPECT_EQ(field.size(), 3 * stepper.model().mesh.num_nodes());
  // Within the ROI the field is the state itself (the ROI components come first).
  const std::vector<double> roi = stepper.roi_displacement_mm();
  const int first = stepper.model().roi_nodes.front();
  for (int c = 0; c < 3; ++c) EXPECT_EQ(field[3 * first + c] / mm, roi[static_cast<std::size_t>(c)]);
}

TEST(ScenarioStepper, NamesAnUnknownIntegratorBeforeBuildingTheModel) {
  scenario::Scenario sc = shipped("paper-setup1.toml");
  sc.integrator = "trapezium";
  sc.mesh = "does-not-exist.msh";  // never read: the name fails first
  EXPECT_THROW(
      {
        try {
          ScenarioStepper stepper(sc);
        } catch (const InputError& e) {
          EXPECT_NE(std::string(e.what()).find("trapezium"), std::string::npos) << e.what();
          throw;
        }
      },
      InputError);
}

}  // namespace
}  // namespace roifem::simulation
