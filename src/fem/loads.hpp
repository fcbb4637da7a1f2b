#pragma once
/// Nodal force vectors in the full 3N numbering (N).
#include <string>

#include "common/types.hpp"
#include "fem/material_map.hpp"
#include "mesh/tet_mesh.hpp"

namespace roifem::fem {

/// Spreads `total_force` (N) over a named set: by triangle area (a uniform traction, consistent
/// for linear triangles) on a 2D set, by volume on a 3D set, evenly over the nodes otherwise.
Vector set_force(const mesh::TetMesh& mesh, const std::string& set_name, const Vec3& total_force);
/// The area-weighted mean displacement of a 2D set (m): the displacement a uniform traction on the
/// set does work on. `u` over all nodes (3N). InputError for a set without boundary triangles.
Vec3 set_mean_displacement(const mesh::TetMesh& mesh, const std::string& set_name, const Vector& u);
/// Gravity on the lumped masses: rho V/4 g at each node of each tetrahedron.
Vector gravity_force(const mesh::TetMesh& mesh, double rho, const Vec3& g);
/// The same with each tetrahedron's own density.
Vector gravity_force(const mesh::TetMesh& mesh, const MaterialMap& materials, const Vec3& g);

}  // namespace roifem::fem
