// SPDX-License-Identifier: GPL-3.0-or-later
#include "experiments/lame_sphere.hpp"

#include <cmath>
#include <sstream>

#include "experiments/calculix_static.hpp"
#include "fem/assembly.hpp"
#include "fem/dof_map.hpp"
#include "fem/loads.hpp"
#include "fem/material.hpp"
#include "fem/nodal_pressure.hpp"
#include "fem/static_solve.hpp"
#include "mesh/quadratic_mesh.hpp"
#include "solvers/cholesky.hpp"

namespace roifem::experiments {

Vec3 LameSphere::displacement(const Vec3& x) const {
  const double a = inner_radius, b = outer_radius, r = x.norm();
  const double u_r = pressure * a * a * a / (young * (b * b * b - a * a * a)) *
                     ((1 - 2 * poisson) * r + (1 + poisson) * b * b * b / (2 * r * r));
  return u_r / r * x;
}

namespace {

/// p A / 3 on each node that carries a facet of the inner face (fem::facet_load_nodes), along the
/// facet's normal away from the cavity (into the material).
Vector inner_pressure(const mesh::TetMesh& mesh, double pressure) {
  Vector f = Vector::Zero(3 * mesh.num_nodes());
  for (const auto& facet : mesh.set("inner").triangles) {
    const Vec3 p0 = mesh.node(facet[0]), p1 = mesh.node(facet[1]), p2 = mesh.node(facet[2]);
    Vec3 area_normal = 0.5 * (p1 - p0).cross(p2 - p0);  // |.| = A
    if (area_normal.dot(p0 + p1 + p2) < 0) area_normal = -area_normal;
    for (const int n : fem::facet_load_nodes(mesh, facet)) f.segment<3>(3 * n) += pressure / 3 * area_normal;
  }
  return f;
}

}  // namespace

Vector solve_lame_field(const mesh::TetMesh& mesh, const LameSphere& s, std::optional<double> nodal_pressure) {
  fem::Constraints constraints(mesh.num_nodes());
  const char* planes[] = {"x0", "y0", "z0"};
  for (int c = 0; c < 3; ++c)
    for (const int n : mesh.set(planes[c]).nodes) constraints.prescribe(n, c);
  const fem::DofMap dofs(constraints);
  const fem::Material material = fem::Material::from_young_poisson(s.young, s.poisson, 1000, 0);
  const SparseMatrix K = nodal_pressure ? fem::nodal_pressure_stiffness(mesh, dofs, material, *nodal_pressure)
                                        : fem::StiffnessAssembler(mesh, dofs).stiffness(material);
  solvers::Cholesky factor;
  fem::factorize_stiffness(factor, K, dofs);
  return dofs.expand(factor.solve(dofs.restrict_to_free(inner_pressure(mesh, s.pressure))));
}

namespace {

/// The error of u (3 per node) against Lame's solution, at the vertices (a quadratic mesh's too:
/// the same points for every element).
LameError lame_error(const mesh::TetMesh& mesh, const LameSphere& s, const Vector& u) {
  LameError e{.nodes = mesh.num_nodes(), .tets = mesh.num_tets(), .l2 = 0, .inner_mean = 0};
  double error2 = 0, exact2 = 0;
  for (Index n = 0; n < mesh.num_vertices(); ++n) {
    const Vec3 exact = s.displacement(mesh.node(static_cast<int>(n)));
    error2 += (u.segment<3>(3 * n) - exact).squaredNorm();
    exact2 += exact.squaredNorm();
  }
  e.l2 = std::sqrt(error2 / exact2);
  double radial = 0;
  int count = 0;
  for (const int n : mesh.set("inner").nodes)
    if (n < mesh.num_vertices()) {
      radial += u.segment<3>(3 * n).dot(mesh.node(n).normalized());
      ++count;
    }
  const double exact_inner = s.displacement(Vec3(s.inner_radius, 0, 0)).x();
  e.inner_mean = (radial / count - exact_inner) / exact_inner;
  return e;
}

}  // namespace

LameError solve_lame_sphere(const mesh::TetMesh& mesh, const LameSphere& s, std::optional<double> nodal_pressure) {
  return lame_error(mesh, s, solve_lame_field(mesh, s, nodal_pressure));
}

LameError solve_lame_sphere_c3d10(const mesh::TetMesh& mesh, const LameSphere& s, const std::filesystem::path& work_dir) {
  const mesh::TetMesh quadratic = mesh::with_midside_nodes(mesh);
  CalculixProblem problem{.mesh = &quadratic,
                          .material = fem::Material::from_young_poisson(s.young, s.poisson, 1000, 0),
                          .fixed_nodes = {},
                          .held_components = {},
                          .forces = inner_pressure(quadratic, s.pressure)};
  const char* planes[] = {"x0", "y0", "z0"};
  for (int c = 0; c < 3; ++c)
    for (const int n : quadratic.set(planes[c]).nodes) problem.held_components.emplace_back(n, c);
  std::ostringstream log;
  const auto solutions = solve_with_calculix(problem, {1.0}, false, work_dir, log);
  return lame_error(quadratic, s, solutions.front().u);
}

}  // namespace roifem::experiments
