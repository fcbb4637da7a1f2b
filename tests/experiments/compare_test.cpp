// SPDX-License-Identifier: GPL-3.0-or-later
// `roifem compare` on the paper's setup 2, a few integrators, a short window.
#include "experiments/compare_experiment.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "common/version.hpp"
#include "test_support.hpp"

namespace roifem::experiments {
namespace {

/// compare.csv's rows as fields (the header checked): 14 plain fields, then the quoted status.
std::vector<std::vector<std::string>> read_rows(const std::filesystem::path& file) {
  std::ifstream csv(file);
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line, "# roifem " + std::string(version()));
  std::getline(csv, line);
  EXPECT_EQ(line,
            "integrator,mode,dt_or_tol,theoretical_order,steps,rhs_evals,jac_evals,lin_setups,lin_solves,wall_s,err_max_mm,"
            "err_rms_mm,stable,energy_drift_rel,status");
  std::vector<std::vector<std::string>> rows;
  while (std::getline(csv, line)) {
    EXPECT_EQ(line.find("nan"), std::string::npos) << line;
    EXPECT_EQ(line.find("inf"), std::string::npos) << line;
    std::vector<std::string> fields;
    std::size_t start = 0;
    for (int k = 0; k < 14; ++k) {
      const std::size_t comma = line.find(',', start);
      fields.push_back(line.substr(start, comma - start));
      start = comma + 1;
    }
    fields.push_back(line.substr(start));
    rows.push_back(fields);
  }
  return rows;
}

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
  // The log puts the observed order beside the method's own.
  EXPECT_NE(log.str().find("trapezoid            observed order"), std::string::npos) << log.str();
  EXPECT_NE(log.str().find("(theory 2)"), std::string::npos) << log.str();

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

  // The CSV: header, one row per run, no NaN or inf anywhere, empty error fields where diverged,
  // and the reason in the last (quoted) field.
  const auto rows = read_rows(dir / "compare.csv");
  ASSERT_EQ(rows.size(), r.rows.size());
  for (const auto& fields : rows) {
    if (fields[12] == "0") {  // diverged: no error figures at all, and why
      EXPECT_TRUE(fields[10].empty() && fields[11].empty() && fields[13].empty());
      EXPECT_EQ(fields[14].rfind("\"diverged: ", 0), 0u) << fields[14];
    } else {
      EXPECT_EQ(fields[14], "\"ok\"");
    }
  }
}

TEST(Compare, ARunStoppedByTheTimeBudgetKeepsItsRowAndItsReason) {
  test::TempDir dir;
  scenario::Scenario sc = scenario::read_scenario(std::string(ROIFEM_SCENARIO_DIR) + "/paper-setup2.toml");
  CompareOptions o;
  o.out = dir.path();
  o.integrators = {"trapezoid"};
  o.t_end = 0.5;
  o.fixed_levels = 2;
  o.max_run_s = 0;  // every run is over budget before its first step (the limit is heard inside a step)
  o.plots = false;
  std::ostringstream log;
  const CompareResults r = run_compare(sc, o, log);
  ASSERT_EQ(r.rows.size(), 1u);  // the sweep stops at the first run over budget (a smaller dt runs longer)
  EXPECT_EQ(r.rows[0].status.rfind("stopped at t = 0 s after", 0), 0u) << r.rows[0].status;
  const auto rows = read_rows(dir / "compare.csv");
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_TRUE(rows[0][10].empty() && rows[0][12].empty()) << "no error figures, stability unknown";
  EXPECT_NE(rows[0][14].find("--max-run-seconds"), std::string::npos) << rows[0][14];
}

// docs/results.md lists each table's columns as the one column list has them.
TEST(CompareResults, TheResultsPageListsEveryTablesColumns) {
  std::ifstream file(std::string(ROIFEM_SOURCE_DIR) + "/docs/results.md");
  ASSERT_TRUE(file) << "docs/results.md";
  std::stringstream text;
  text << file.rdbuf();
  const std::string page = text.str();
  for (const auto& header :
       {io::csv_header(compare_columns()), io::csv_header(stability_columns()), io::csv_header(tool_columns())})
    EXPECT_NE(page.find("`" + header + "`"), std::string::npos) << "docs/results.md does not list " << header;
}

}  // namespace
}  // namespace roifem::experiments
