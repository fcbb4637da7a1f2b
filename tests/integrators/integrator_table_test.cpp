// SPDX-License-Identifier: GPL-3.0-or-later
// The one table of integrators: every row makes the integrator it names, the traits the factory
// and compare read agree with what the integrator does, the stability search reads the tableau
// (checked against RK4's known limit), and the guide (docs/integrators.md) lists every name.
#include "integrators/integrator_table.hpp"

#include <gtest/gtest.h>

#include <algorithm>

#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include "common/errors.hpp"
#include "integrators/factory.hpp"
#include "integrators/stability.hpp"

namespace roifem::integrators {
namespace {

TEST(IntegratorTable, EveryRowMakesTheIntegratorItNamesAndNamesAreUnique) {
  std::set<std::string> seen;
  for (const auto& info : integrator_table()) {
    EXPECT_TRUE(seen.insert(info.name).second) << info.name;
    EXPECT_GT(info.order, 0) << info.name;
    EXPECT_TRUE(info.fixed_step || info.adaptive) << info.name;
    ASSERT_NE(info.make, nullptr) << info.name;
    const StepControl control = info.fixed_step ? StepControl{.dt = 0.01} : StepControl{.dt = 0.01, .adaptive = true};
    EXPECT_EQ(make_integrator(info.name, control)->name(), info.name);
    if (info.tableau) {
      EXPECT_TRUE(info.is_explicit) << info.name << ": a tableau for the explicit stability search";
    }
  }
}

TEST(IntegratorTable, AnAdaptiveRequestToAFixedOnlyMethodIsRefusedAndAnUnknownNameListsTheValidOnes) {
  for (const auto& info : integrator_table()) {
    if (info.adaptive) continue;
    EXPECT_THROW(make_integrator(info.name, StepControl{.dt = 0.01, .adaptive = true}), InputError) << info.name;
  }
  try {
    make_integrator("rk45", 0.01);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("valid: " + integrator_name_list()), std::string::npos) << e.what();
  }
}

TEST(IntegratorTable, StabilitySearchReadsTheTableauAndMeetsRk4sImaginaryAxisLimit) {
  // Undamped: the eigenvalues +-i w lie on the imaginary axis, where classical RK4 is stable up
  // to h w = 2 sqrt(2); Heun-Euler's R(z) = 1 + z + z^2/2 exceeds 1 all along it (no stable step).
  const double w = 40.0;
  const Vector frequencies = Vector::Constant(1, w);
  // GSL's rk4 takes two classical steps of h/2 per step of h (its step doubling): 4 sqrt(2).
  EXPECT_NEAR(predicted_stability_limit(integrator_info("gsl-rk4"), frequencies, 0.0) * w, 4.0 * std::sqrt(2.0), 1e-9);
  // (the search allows |R| up to 1 + 1e-12, which h w = (8e-12)^(1/4) = 1.7e-3 meets)
  EXPECT_LT(predicted_stability_limit(integrator_info("arkode-erk2"), frequencies, 0.0) * w, 2e-3);
  EXPECT_TRUE(std::isinf(predicted_stability_limit(integrator_info("arkode-esdirk4"), frequencies, 0.0)));
}

TEST(IntegratorTable, TheGuideListsEveryIntegrator) {
  std::ifstream file(std::string(ROIFEM_SOURCE_DIR) + "/docs/integrators.md");
  ASSERT_TRUE(file) << "docs/integrators.md";
  std::stringstream text;
  text << file.rdbuf();
  const std::string readme = text.str();
  for (const auto& info : integrator_table()) {
    std::string base = info.name;
    for (const char* suffix : {"-mass-schur", "-schur", "-mass"})
      if (base.size() > std::string(suffix).size() && base.ends_with(suffix)) {
        EXPECT_NE(readme.find(std::string("`...") + (std::string(suffix) == "-mass-schur" ? "-schur" : suffix) + "`"),
                  std::string::npos)
            << info.name;
        base.resize(base.size() - std::string(suffix).size());
        break;
      }
    EXPECT_NE(readme.find("`" + base + "`"), std::string::npos) << "docs/integrators.md does not list " << info.name;
  }
}

// scenarios/README.md lists every base name too, on a line that says how it steps as the table does.
TEST(IntegratorTable, TheScenarioGuideListsEveryIntegratorWithItsStepping) {
  std::ifstream file(std::string(ROIFEM_SCENARIO_DIR) + "/README.md");
  ASSERT_TRUE(file) << "scenarios/README.md";
  std::vector<std::string> lines;
  for (std::string line; std::getline(file, line);) lines.push_back(line);
  for (const auto& info : integrator_table()) {
    std::string base = info.name;
    for (const char* suffix : {"-mass-schur", "-schur", "-mass"})
      if (base.ends_with(suffix) && base != "trapezoid") {
        base.resize(base.size() - std::string(suffix).size());
        break;
      }
    const auto line = std::find_if(lines.begin(), lines.end(),
                                   [&](const std::string& l) { return l.find("`" + base + "`") != std::string::npos; });
    ASSERT_NE(line, lines.end()) << "scenarios/README.md does not list " << info.name;
    const std::string steps = line->substr(line->rfind('|', line->size() - 2));
    EXPECT_EQ(steps.find("fixed") != std::string::npos, info.fixed_step) << *line;
    EXPECT_EQ(steps.find("adaptive") != std::string::npos, info.adaptive) << *line;
  }
}

}  // namespace
}  // namespace roifem::integrators
