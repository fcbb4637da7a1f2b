#pragma once
/// Nodal force vectors in the full 3N numbering (N).
#include <string>

#include "common/types.hpp"
#include "mesh/tet_mesh.hpp"

namespace roifem::fem {

/// Spreads `total_force` (N) over a named set: by triangle area (a uniform traction, consistent
/// for linear triangles) on a 2D set, by volume on a 3D set, evenly over the nodes otherwise.
Vector set_force(const mesh::TetMesh& mesh, const std::string& set_name, const Vec3& total_force);
/// Gravity on the lumped masses: rho V/4 g at each node of each tetrahedron.
Vector gravity_force(const mesh::TetMesh& mesh, double rho, const Vec3& g);

}  // namespace roifem::fem
