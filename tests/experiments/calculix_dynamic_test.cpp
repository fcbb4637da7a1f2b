// SPDX-License-Identifier: GPL-3.0-or-later
// The damped neo-Hookean cantilever (tests/integrators/neo_hookean_cantilever.hpp: 6 cm, E = 3 kPa,
// bent by 30 mN ramped over 0.25 s to a tip drop of about a third of its length, C = alpha M)
// by roifem's trapezoidal rule with Newton against CalculiX's own nonlinear dynamics (*DYNAMIC,
// DIRECT, ALPHA = 0, NLGEOM, *DAMPING ALPHA): an independent element, law, Newton and Newmark.
// With roifem's lumped mass given to CalculiX as point masses the two solve the same ODE, and
// agree to the 7 digits ccx prints; with CalculiX's own consistent mass they differ by the mass
// discretization.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "experiments/calculix_dynamic.hpp"
#include "fem/loads.hpp"
#include "integrators/neo_hookean_cantilever.hpp"
#include "integrators/trapezoid.hpp"
#include "test_support.hpp"

namespace roifem::experiments {
namespace {

using integrators::testing::NeoHookeanCantilever;

double largest_nodal_norm(const Vector& u) {
  double m = 0;
  for (Index n = 0; n < u.size() / 3; ++n) m = std::max(m, u.segment<3>(3 * n).norm());
  return m;
}

struct Difference {
  double relative = 0;  ///< max over the steps of max_i |u_i - u_ccx,i|, over max over the steps of max_i |u_ccx,i|
  double peak_mm = 0;   ///< that max |u_ccx|
};

Difference difference(const std::vector<Vector>& ours, const std::vector<Vector>& ccx) {
  double worst = 0, peak = 0;
  for (std::size_t k = 0; k < ours.size(); ++k) {
    worst = std::max(worst, largest_nodal_norm(ours[k] - ccx[k]));
    peak = std::max(peak, largest_nodal_norm(ccx[k]));
  }
  return {worst / peak, peak / mm};
}

TEST(NeoHookeanDynamicsAgainstCalculix, TheDampedCantileverByTheTrapezoidalRuleIsCalculixsNewmark) {
  if (!calculix_available()) GTEST_SKIP() << "CalculiX (ccx) is not installed: scripts/setup.sh installs calculix-ccx";
  constexpr double alpha = 2, force = integrators::testing::bending_force, ramp = 0.25, dt = 0.01;
  constexpr long steps = 80;  // 0.8 s: the ramp and more than one period of the first mode (0.65 s)
  const NeoHookeanCantilever beam(alpha, force, ramp);
  const fem::DofMap& dofs = *beam.model.dofs;

  integrators::Trapezoid trapezoid(dt);
  model::State state = model::State::at_rest(beam.sys().size());
  trapezoid.reset(beam.sys(), state);
  std::vector<Vector> ours;
  for (long k = 1; k <= steps; ++k) {
    trapezoid.advance_to(static_cast<double>(k) * dt, state);
    ours.push_back(dofs.expand(state.u));
  }

  fem::Material material = fem::Material::from_young_poisson(3000, 0.45, 1000, alpha);
  material.model = fem::MaterialModel::neo_hookean;
  CalculixDynamicProblem problem{.model = {.mesh = &beam.mesh,
                                           .material = material,
                                           .fixed_nodes = beam.mesh.set("x0").nodes,
                                           .forces = fem::set_force(beam.mesh, "x1", Vec3(0, 0, -force)),
                                           .newton_tolerance = 1e-10},
                                 .ramp_s = ramp,
                                 .dt = dt,
                                 .steps = steps};
  problem.lumped_mass = Vector::Zero(beam.mesh.num_nodes());
  for (Index i = 0; i < dofs.num_free(); i += 3) problem.lumped_mass[dofs.full_dof(i) / 3] = beam.sys().M.coeff(i, i);
  const test::TempDir scratch;  // each run its own CalculiX files
  const auto dir = scratch.path();
  const Difference lumped = difference(ours, solve_dynamics_with_calculix(problem, dir / "lumped"));
  problem.mass = CalculixMass::consistent;
  const Difference consistent = difference(ours, solve_dynamics_with_calculix(problem, dir / "consistent"));
  std::printf(
      "cantilever, %ld steps of %g s: peak |u| %.3f mm; roifem (lumped mass) against CalculiX: with the same lumped mass "
      "%.2e, with CalculiX's consistent mass %.2e; %ld Newton iterations\n",
      steps, dt, lumped.peak_mm, lumped.relative, consistent.relative, trapezoid.stats().nonlinear_iterations);
  EXPECT_GT(lumped.peak_mm, 15) << "a large deformation: a quarter of the length";
  EXPECT_LT(lumped.relative, 1e-5);
  EXPECT_GT(consistent.relative, 100 * lumped.relative) << "the comparison sees the mass matrix";
}

}  // namespace
}  // namespace roifem::experiments
