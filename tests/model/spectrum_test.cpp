// SPDX-License-Identifier: GPL-3.0-or-later
#include "model/spectrum.hpp"

#include <gtest/gtest.h>

#include "common/errors.hpp"
#include "mesh/box_mesh.hpp"
#include "model/fem_model.hpp"
#include "model/modal_reference.hpp"
#include "scenario/scenario.hpp"
#include "simulation/scenario_model.hpp"

namespace roifem::model {
namespace {

double dense_highest(const SecondOrderSystem& sys) {
  const State rest = model::State::at_rest(sys.size());
  return ModalReference(sys, rest).frequencies().maxCoeff();
}

TEST(Spectrum, LanczosEqualsTheDenseEigensolverOnABox) {
  const auto mesh = mesh::structured_box_mesh(4, 2, 2, 0.04, 0.02, 0.02);
  const auto m = build_fem_model(mesh, fem::Material::from_young_poisson(3000, 0.45, 1000, 0.8), {"x0"}, {});
  const double lanczos = highest_frequency(m.system), dense = dense_highest(m.system);
  std::printf("box, %lld dofs: w_max Lanczos %.10g, dense %.10g rad/s\n", static_cast<long long>(m.system.size()), lanczos,
              dense);
  EXPECT_NEAR(lanczos / dense, 1.0, 1e-9);
}

TEST(Spectrum, LanczosEqualsTheDenseEigensolverOnTheCondensedPaperModel) {
  const auto model =
      simulation::build_scenario_model(scenario::read_scenario(std::string(ROIFEM_SCENARIO_DIR) + "/paper-setup1.toml"));
  const double lanczos = highest_frequency(model->system()), dense = dense_highest(model->system());
  std::printf("setup 1: w_max Lanczos %.10g, dense %.10g rad/s\n", lanczos, dense);
  EXPECT_NEAR(lanczos / dense, 1.0, 1e-9);
}

TEST(Spectrum, FullMassMatrixTakesTheGeneralizedForm) {
  // The box with a consistent-like M: the lumped M plus a symmetric coupling of neighbouring dofs.
  const auto mesh = mesh::structured_box_mesh(4, 2, 2, 0.04, 0.02, 0.02);
  auto m = build_fem_model(mesh, fem::Material::from_young_poisson(3000, 0.45, 1000, 0.8), {"x0"}, {});
  const Index n = m.system.size();
  DenseMatrix M(m.system.M);
  for (Index i = 0; i + 1 < n; ++i) M(i, i + 1) = M(i + 1, i) = 0.2 * std::min(M(i, i), M(i + 1, i + 1));
  m.system.M = M.sparseView();
  m.system.C = 0.8 * m.system.M;
  const double lanczos = highest_frequency(m.system), dense = dense_highest(m.system);
  std::printf("box with a full M: w_max Lanczos %.10g, dense %.10g rad/s\n", lanczos, dense);
  EXPECT_NEAR(lanczos / dense, 1.0, 1e-9);
}

}  // namespace
}  // namespace roifem::model
