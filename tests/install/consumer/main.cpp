// SPDX-License-Identifier: GPL-3.0-or-later
// Statically solves a bar in tension through the installed roifem libraries; prints the error
// against F L / (E A) and exits non-zero if it is not at round-off level.
#include <cmath>
#include <cstdio>

#include "fem/assembly.hpp"
#include "fem/loads.hpp"
#include "fem/static_solve.hpp"
#include "integrators/trapezoid.hpp"
#include "mesh/box_mesh.hpp"

int main() {
  using namespace roifem;
  const auto mesh = mesh::structured_box_mesh(10, 2, 2, 0.1, 0.01, 0.01);
  fem::Constraints constraints(mesh.num_nodes());
  for (int n : mesh.set("x0").nodes) constraints.prescribe(n, 0);
  for (int n : mesh.set("y0").nodes) constraints.prescribe(n, 1);
  for (int n : mesh.set("z0").nodes) constraints.prescribe(n, 2);
  const fem::DofMap dofs(constraints);
  const auto material = fem::Material::from_young_poisson(1e4, 0.3, 1000, 0);
  const fem::StiffnessAssembler assembler(mesh, dofs);
  const Vector u = dofs.expand(
      fem::solve_static(assembler.stiffness(material), dofs.restrict_to_free(fem::set_force(mesh, "x1", Vec3(1, 0, 0))), dofs));
  const double expected = 1.0 * 0.1 / (1e4 * 1e-4);
  const double error = std::abs(u.maxCoeff() - expected) / expected;
  std::printf("installed roifem: bar elongation %.6e m, relative error %.2e\n", u.maxCoeff(), error);
  integrators::Trapezoid trapezoid(0.01);  // roifem::integrators links too
  return error < 1e-10 ? 0 : 1;
}
