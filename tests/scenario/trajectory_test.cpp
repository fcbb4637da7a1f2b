// SPDX-License-Identifier: GPL-3.0-or-later
// Tool trajectories from CSV files (scenario/trajectory_reader.hpp): what is refused and where, and
// that a trajectory drives a model exactly as the same path given as a ramp does.
#include "scenario/trajectory_reader.hpp"

#include <gtest/gtest.h>

#include "common/errors.hpp"
#include "integrators/factory.hpp"
#include "integrators/trapezoid.hpp"
#include "mesh/box_mesh.hpp"
#include "model/fem_model.hpp"
#include "test_support.hpp"

namespace roifem::scenario {
namespace {

void expect_refused(const std::string& text, const std::string& words) {
  const test::TempDir dir;
  const auto file = test::write_file(dir / "path.csv", text);
  try {
    read_trajectory(file);
    ADD_FAILURE() << "accepted:\n" << text;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("path.csv"), std::string::npos) << e.what();
  }
}

TEST(Trajectory, BadFilesAreRefusedNamingTheLine) {
  expect_refused("t,x,y,z\n0,0,0,0\n1,1,0,0\n", ":1: a trajectory starts with the header 't_s,x_mm,y_mm,z_mm'");
  expect_refused("t_s,x_mm,y_mm,z_mm\n0,0,0,0\n0.5,1,zero,0\n", ":3: 'zero' is not a number");
  expect_refused("t_s,x_mm,y_mm,z_mm\n0,0,0,0\n0.5,1,0\n", ":3: expected four numbers");
  expect_refused("t_s,x_mm,y_mm,z_mm\n0,0,0,0\n0.5,1,0,0\n0.5,2,0,0\n", ":4: t = 0.5 s is not after the previous sample's 0.5 s");
  expect_refused("t_s,x_mm,y_mm,z_mm\n0,1,0,0\n0.5,1,0,0\n", ":2: the first sample must be 0, 0, 0, 0");
  expect_refused("t_s,x_mm,y_mm,z_mm\n0,0,0,0\n", "a trajectory needs two or more samples");
  expect_refused("t_s,x_mm,y_mm,z_mm\n0,0,0,0\n0.5,1,0,inf\n", ":3: 'inf' is not finite");
  try {
    read_trajectory("/nonexistent/path.csv");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/path.csv: cannot open trajectory file"), std::string::npos);
  }
}

TEST(Trajectory, ItIsPiecewiseLinearThroughItsSamplesAndHoldsTheLast) {
  const test::TempDir dir;
  const auto path = read_trajectory(test::write_file(dir / "p.csv", "t_s,x_mm,y_mm,z_mm\n0,0,0,0\n0.1,1,0,-2\n0.3,1,3,0\n"));
  EXPECT_NEAR((path.at(0.05) - Vec3(0.5, 0, -1) * mm).norm(), 0, 1e-18);
  EXPECT_NEAR((path.at(0.2) - Vec3(1, 1.5, -1) * mm).norm(), 0, 1e-18);
  EXPECT_EQ(path.at(7.0), Vec3(1, 3, 0) * mm);
  EXPECT_NEAR((path.velocity(0.2) - Vec3(0, 15, 10) * mm).norm(), 0, 1e-15);  // right-sided at the samples
  EXPECT_EQ(path.kinks_after(0.1), (std::vector<double>{0.3}));
}

TEST(Trajectory, DrivesAModelAsTheSameRampDoes) {
  // A trajectory through (0, 0) and (0.2 s, d) is the linear ramp to d over 0.2 s: the tool's force
  // under the trapezoidal rule agrees to rounding.
  const test::TempDir dir;
  const mesh::TetMesh mesh = mesh::structured_box_mesh(6, 2, 2, 0.06, 0.02, 0.02);
  const auto material = fem::Material::from_young_poisson(3000, 0.45, 1000, 0.8);
  model::SetTool ramped{.name = "tip", .set = "x1", .path = {Vec3(0.2e-3, -0.1e-3, 1e-3), model::Ramp{0.2}}};
  model::SetTool sampled = ramped;
  sampled.path = read_trajectory(test::write_file(dir / "p.csv", "t_s,x_mm,y_mm,z_mm\n0,0,0,0\n0.2,0.2,-0.1,1.0\n"));
  const auto a = model::build_fem_model(mesh, material, {"x0"}, {}, {ramped});
  const auto b = model::build_fem_model(mesh, material, {"x0"}, {}, {sampled});
  model::State sa = model::State::at_rest(a.system.size()), sb = sa;
  integrators::Trapezoid ta(0.01), tb(0.01);
  ta.reset(a.system, sa);
  tb.reset(b.system, sb);
  double worst = 0, peak = 0;
  for (int k = 1; k <= 40; ++k) {
    ta.advance_to(0.01 * k, sa);
    tb.advance_to(0.01 * k, sb);
    const Vector Fa = a.tools.forces(sa.u, sa.t), Fb = b.tools.forces(sb.u, sb.t);
    worst = std::max(worst, (Fa - Fb).lpNorm<Eigen::Infinity>());
    peak = std::max(peak, Fa.lpNorm<Eigen::Infinity>());
  }
  EXPECT_LT(worst, 1e-12 * peak);
  // The DAE forms restart at every sample of a trajectory: with three segments, ida-ggl meets the
  // eliminated model integrated tightly by ida-bdf5.
  model::SetTool zigzag = ramped;
  zigzag.path = read_trajectory(
      test::write_file(dir / "z.csv", "t_s,x_mm,y_mm,z_mm\n0,0,0,0\n0.1,0.2,0,0.5\n0.2,0.2,-0.1,1.0\n0.3,0,0,0.5\n"));
  const auto c = model::build_fem_model(mesh, material, {"x0"}, {}, {zigzag});
  auto reference = integrators::make_integrator("ida-bdf5", {.dt = 0.01, .adaptive = true, .rtol = 1e-10, .atol = 1e-16});
  auto dae = integrators::make_integrator("ida-ggl", {.dt = 0.01, .adaptive = true, .rtol = 1e-8, .atol = 1e-14});
  model::State sr = model::State::at_rest(c.system.size()), sd = sr;
  reference->reset(c.system, sr);
  dae->reset(c.system, sd);
  worst = peak = 0;
  for (int k = 1; k <= 40; ++k) {
    reference->advance_to(0.01 * k, sr);
    dae->advance_to(0.01 * k, sd);
    const Vector F = c.tools.forces(sr.u, sr.t);
    worst = std::max(worst, (dae->constraints()->forces - F).lpNorm<Eigen::Infinity>());
    peak = std::max(peak, F.lpNorm<Eigen::Infinity>());
  }
  std::printf("zigzag trajectory: ida-ggl's multiplier force within %.1e of the tightly integrated elimination's\n",
              worst / peak);
  EXPECT_LT(worst, 1e-6 * peak);
}

}  // namespace
}  // namespace roifem::scenario
