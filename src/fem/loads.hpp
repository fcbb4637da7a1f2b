// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Nodal force vectors in the full 3N numbering (N).
#include <string>

#include "common/types.hpp"
#include "fem/material_map.hpp"
#include "mesh/tet_mesh.hpp"

namespace roifem::fem {

/// The nodes that carry a flat triangle's uniform traction, a third of its force each: its
/// corners, or on a quadratic mesh its edges' midpoints (the 6-node triangle's consistent shares:
/// nothing at the corners, a third at each midpoint).
mesh::Triangle facet_load_nodes(const mesh::TetMesh& mesh, const mesh::Triangle& t);
/// Spreads `total_force` (N) over a named set: by triangle area (a uniform traction, consistent
/// for linear triangles) on a 2D set, by volume on a 3D set, evenly over the nodes otherwise.
/// On a quadratic mesh a triangle's share goes to its edges' midpoints (consistent for 6-node
/// triangles) and a tetrahedron's by the HRZ mass fractions.
Vector set_force(const mesh::TetMesh& mesh, const std::string& set_name, const Vec3& total_force);
/// The area-weighted mean displacement of a 2D set (m): the displacement a uniform traction on the
/// set does work on. `u` over all nodes (3N). InputError for a set without boundary triangles.
/// On a quadratic mesh it is the exact mean of the quadratic field: a third of each triangle's
/// midpoints.
Vec3 set_mean_displacement(const mesh::TetMesh& mesh, const std::string& set_name, const Vector& u);
/// Gravity on the lumped masses: rho V/4 g at each node of each tetrahedron.
Vector gravity_force(const mesh::TetMesh& mesh, double rho, const Vec3& g);
/// The same with each tetrahedron's own density.
Vector gravity_force(const mesh::TetMesh& mesh, const MaterialMap& materials, const Vec3& g);

}  // namespace roifem::fem
