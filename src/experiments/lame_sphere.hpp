// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Verification against Lame's solution: a thick-walled sphere (radii a < b) under internal
/// pressure p, linear elastic (E, nu). Radial displacement
///   u_r(r) = p a^3 / (E (b^3 - a^3)) [ (1 - 2 nu) r + (1 + nu) b^3 / (2 r^2) ].
/// As nu nears 1/2 the volume hardly changes, which linear tetrahedra cannot represent on a
/// coarse mesh: they lock, the computed displacement far too small. The case exposes it: the
/// error at nu = 0.49, 0.499, 0.4999 against nu = 0.3 on the same meshes, with observed orders.
/// Solved on one octant (mesh/sphere_shell_mesh.hpp) with symmetry (each plane's normal
/// component held) and p on the inner face, consistently lumped (p A / 3 per node of each facet).
#include <filesystem>
#include <optional>
#include <vector>

#include "common/types.hpp"
#include "mesh/tet_mesh.hpp"

namespace roifem::experiments {

struct LameSphere {
  double inner_radius = 0.01, outer_radius = 0.02;  ///< m
  double pressure = 1e3;                            ///< Pa
  double young = 3000, poisson = 0.3;               ///< Pa, -
  /// The exact displacement at x (m).
  Vec3 displacement(const Vec3& x) const;
};

struct LameError {
  Index nodes = 0, tets = 0;
  double l2 = 0;          ///< sqrt(sum |u_h - u|^2 / sum |u|^2) over the nodes
  double inner_mean = 0;  ///< (mean u_r on the inner face - exact u_r(a)) / u_r(a)
};

/// Solves the octant `mesh` (sets shell, inner, x0, y0, z0) and measures the error at its
/// vertices: with linear tetrahedra, with nodal-pressure ones (fem/nodal_pressure.hpp) of
/// stabilization s when `nodal_pressure` is set, or with the 10-node tetrahedron on a quadratic
/// mesh (mesh/quadratic_mesh.hpp). Throws InputError for a mesh without those sets.
LameError solve_lame_sphere(const mesh::TetMesh& mesh, const LameSphere& sphere,
                            std::optional<double> nodal_pressure = std::nullopt);
/// The computed displacement of that problem (3N, every node).
Vector solve_lame_field(const mesh::TetMesh& mesh, const LameSphere& sphere, std::optional<double> nodal_pressure = std::nullopt);
/// The same problem solved by CalculiX with quadratic tetrahedra on this linear mesh (C3D10 on
/// mesh::with_midside_nodes) in `work_dir`; the error measured at the vertices, as for the others.
/// Throws SolverError without ccx.
LameError solve_lame_sphere_c3d10(const mesh::TetMesh& mesh, const LameSphere& sphere, const std::filesystem::path& work_dir);

}  // namespace roifem::experiments
