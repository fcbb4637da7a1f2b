// `roifem compare` on the paper's setup 2, a few integrators, a short window.
#include "experiments/compare_experiment.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "test_support.hpp"

namespace roifem::experiments {
namespace {

TEST(Compare, MeasuresOrdersStabilityLimitsAndKeepsDivergedRunsFreeOfNumbers) {
  test::TempDir dir;
  scenario::Scenario sc = scenario::read_scenario(std::string(ROIFEM_SCENARIO_DIR) + "/paper-setup2.toml");
  CompareOptions o;
  o.out = dir.path();
  o.integrators = {"trapezoid", "arkode-erk4", "arkode-esdirk4-schur", "ida-bdf5"};
  o.t_end = 0.5;
  o.fixed_levels = 4;
  o.tolerances = {1e-4, 1e-6};
  o.plots = false;
  std::ostringstream log;
  const CompareResults r = run_compare(sc, o, log);

  // Trapezoid: second order against the exact solution over the last halvings.
  std::vector<double> errors;
  for (const auto& row : r.rows)
    if (row.integrator == "trapezoid") errors.push_back(row.err_max_mm);
  ASSERT_EQ(errors.size(), 4u);
  const double order = std::log2(errors[2] / errors[3]);
  EXPECT_NEAR(order, 2.0, 0.3) << log.str();

  // ERK4: the predicted limit holds in practice (bisection within a few percent), and the run just
  // above it is reported unstable.
  ASSERT_EQ(r.stability.size(), 1u);
  EXPECT_NEAR(r.stability[0].measured_dt / r.stability[0].predicted_dt, 1.0, 0.05) << log.str();
  bool saw_unstable = false;
  for (const auto& row : r.rows)
    if (row.integrator == "arkode-erk4" && row.mode == "fixed" && !row.stable) saw_unstable = true;
  EXPECT_TRUE(saw_unstable);

  // Tighter tolerance, smaller error, for the adaptive methods.
  for (const char* name : {"arkode-esdirk4-schur", "ida-bdf5"}) {
    std::vector<double> e;
    for (const auto& row : r.rows)
      if (row.integrator == name && row.mode == "adaptive") e.push_back(row.err_max_mm);
    ASSERT_EQ(e.size(), 2u);
    EXPECT_LT(e[1], e[0]) << name;
  }

  // The CSV: header, one row per run, no NaN or inf anywhere, empty error fields where diverged.
  std::ifstream csv(dir / "compare.csv");
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line,
            "integrator,mode,dt_or_tol,steps,rhs_evals,jac_evals,lin_setups,lin_solves,wall_s,err_max_mm,"
            "err_rms_mm,stable,energy_drift");
  std::size_t rows = 0;
  while (std::getline(csv, line)) {
    ++rows;
    EXPECT_EQ(line.find("nan"), std::string::npos) << line;
    EXPECT_EQ(line.find("inf"), std::string::npos) << line;
    std::vector<std::string> fields;
    std::stringstream in(line);
    for (std::string field; std::getline(in, field, ',');) fields.push_back(field);
    if (line.back() == ',') fields.emplace_back();
    ASSERT_EQ(fields.size(), 13u) << line;
    if (fields[11] == "0") {  // diverged: no error figures at all
      EXPECT_TRUE(fields[9].empty() && fields[10].empty() && fields[12].empty()) << line;
    }
  }
  EXPECT_EQ(rows, r.rows.size());
}

}  // namespace
}  // namespace roifem::experiments
