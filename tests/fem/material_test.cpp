// SPDX-License-Identifier: GPL-3.0-or-later
#include "fem/material.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "common/errors.hpp"

namespace roifem::fem {
namespace {

void expect_input_error(auto&& f, const std::string& fragment) {
  try {
    f();
    FAIL() << "expected InputError mentioning '" << fragment << "'";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(Material, YoungPoissonRoundTrip) {
  const Material m = Material::from_young_poisson(3000, 0.45, 1040, 5);
  EXPECT_NEAR(m.young(), 3000, 1e-9);
  EXPECT_NEAR(m.poisson(), 0.45, 1e-14);
  EXPECT_NEAR(m.mu, 3000 / 2.9, 1e-9);
}

TEST(Material, PaperPresetIsTable1InCgsUnits) {
  const Material m = material_preset("paper");
  EXPECT_DOUBLE_EQ(m.lambda, 4000.0);  // 0.4e5 dyn/cm^2
  EXPECT_DOUBLE_EQ(m.mu, 12.0);        // 0.0012e5 dyn/cm^2
  EXPECT_DOUBLE_EQ(m.rho, 1000.0);     // 1 g/cm^3
  EXPECT_DOUBLE_EQ(m.alpha, 0.8);
}

TEST(Material, RejectsNonPhysicalParametersByName) {
  expect_input_error([] { Material::from_young_poisson(1e3, 0.5, 1000, 0); }, "Poisson");
  expect_input_error([] { Material::from_young_poisson(1e3, 0.7, 1000, 0); }, "Poisson");
  expect_input_error([] { Material::from_young_poisson(1e3, -1.0, 1000, 0); }, "Poisson");
  expect_input_error([] { Material::from_young_poisson(0, 0.3, 1000, 0); }, "Young");
  expect_input_error([] { Material::from_young_poisson(-5, 0.3, 1000, 0); }, "Young");
  expect_input_error([] { Material::from_young_poisson(1e3, 0.3, 0, 0); }, "density");
  expect_input_error([] { Material::from_young_poisson(1e3, 0.3, -1, 0); }, "density");
  expect_input_error([] { Material::from_young_poisson(1e3, 0.3, 1000, -0.1); }, "alpha");
  expect_input_error([] { Material{.lambda = 1, .mu = 0, .rho = 1, .alpha = 0}.validate(); }, "mu");
  expect_input_error([] { Material{.lambda = -10, .mu = 1, .rho = 1, .alpha = 0}.validate(); }, "Poisson");
  expect_input_error([] { Material{.lambda = std::nan(""), .mu = 1, .rho = 1, .alpha = 0}.validate(); }, "lambda");
  expect_input_error([] { Material::from_young_poisson(std::numeric_limits<double>::infinity(), 0.3, 1, 0); }, "Young");
  expect_input_error([] { material_preset("jelly"); }, "valid: paper, brain");
}

}  // namespace
}  // namespace roifem::fem
