// SPDX-License-Identifier: GPL-3.0-or-later
// `roifem energy` on the undamped neo-Hookean paper brain: the energy-momentum method's ledger
// balances to rounding, the trapezoidal rule's and BDF2's do not; the
// files hold what the summary says; misuse is refused by name.
#include "experiments/energy_study.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "common/errors.hpp"
#include "test_support.hpp"

namespace roifem::experiments {
namespace {

scenario::Scenario undamped_brain() {
  return scenario::read_scenario(std::string(ROIFEM_SCENARIO_DIR) + "/paper-full-neo-hookean-undamped.toml");
}

const EnergyRow& row_named(const EnergyStudy& study, const std::string& name) {
  for (const auto& row : study.rows)
    if (row.integrator == name) return row;
  throw std::runtime_error("no row " + name);
}

TEST(EnergyStudy, EnergyMomentumKeepsTheBalanceWhereTheTrapezoidalRuleDoesNot) {
  test::TempDir dir;
  EnergyStudyOptions o;
  o.out = dir.path();
  o.integrators = {"trapezoid", "energy-momentum", "ida-bdf2"};
  o.t_end = 0.6;  // the ramp and 0.1 s of free swing
  o.rtol = 1e-5;
  o.plots = false;
  std::ostringstream log;
  const EnergyStudy study = run_energy_study(undamped_brain(), o, log);
  std::printf("%s", log.str().c_str());
  ASSERT_EQ(study.rows.size(), 3u);
  const EnergyRow& em = row_named(study, "energy-momentum");
  const EnergyRow& trapezoid = row_named(study, "trapezoid");
  const EnergyRow& bdf = row_named(study, "ida-bdf2");
  for (const EnergyRow* r : {&em, &trapezoid, &bdf}) {
    EXPECT_EQ(r->status, "ok") << r->integrator;
    EXPECT_EQ(r->outputs, 60) << r->integrator;
    EXPECT_GT(r->work_scale_J, 1e-5) << r->integrator;  // the loads' work, ~3.6e-5 J
  }
  EXPECT_LT(em.max_error, 1e-12);
  EXPECT_LT(em.drift_after_ramps, 1e-12);
  EXPECT_GT(trapezoid.drift_after_ramps, 0);  // the loads are constant from 0.5 s: the column is there
  EXPECT_GT(trapezoid.max_error, 1e3 * em.max_error);
  // BDF2 on its own steps, the ledger on the output grid: its figure holds the grid's quadrature of
  // the work during the ramp too, and is far above rounding either way.
  EXPECT_GT(bdf.max_error, 1e3 * em.max_error);
  EXPECT_EQ(study.samples.size(), 180u);

  // The files: one summary row per method, one line per output.
  std::ifstream summary(dir.path() / "energy_summary.csv"), samples(dir.path() / "energy.csv");
  std::string line;
  int summary_lines = 0, sample_lines = 0;
  while (std::getline(summary, line)) summary_lines += line.starts_with("#") ? 0 : 1;
  while (std::getline(samples, line)) sample_lines += line.starts_with("#") ? 0 : 1;
  EXPECT_EQ(summary_lines, 1 + 3);
  EXPECT_EQ(sample_lines, 1 + 180);
}

TEST(EnergyStudy, RefusesWhatItCannotRunByName) {
  test::TempDir dir;
  EnergyStudyOptions o;
  o.out = dir.path() / "out";
  o.plots = false;
  std::ostringstream log;
  const auto refusal = [&](std::vector<std::string> names, double rtol) {
    o.integrators = std::move(names);
    o.rtol = rtol;
    try {
      run_energy_study(undamped_brain(), o, log);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(refusal({"arkode-sdirk2-schur"}, 1e-6).find("arkode-sdirk2-schur does not take a nonlinear model"),
            std::string::npos);
  EXPECT_NE(refusal({"ida-index3"}, 1e-6).find("holds the tools as constraints"), std::string::npos);
  EXPECT_NE(refusal({"energy-momentun"}, 1e-6).find("energy-momentum"), std::string::npos) << "did you mean";
  EXPECT_NE(refusal({"trapezoid"}, 0.0).find("--rtol"), std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(o.out)) << "a refused study leaves no directory";
}

}  // namespace
}  // namespace roifem::experiments
