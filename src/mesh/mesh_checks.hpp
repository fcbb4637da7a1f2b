// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Checks a mesh before any FEM work: every tetrahedron must be positively oriented and of
/// non-negligible volume. Errors name the tetrahedron (0-based index and its nodes).
#include "mesh/tet_mesh.hpp"

namespace roifem::mesh {

struct MeshStatistics {
  Index nodes = 0, tets = 0;
  double volume = 0;  ///< m^3
  double quality_min = 0, quality_median = 0;
  Vec3 box_min = Vec3::Zero(), box_max = Vec3::Zero();  ///< m
};

/// Throws InputError for no tetrahedra, a non-finite coordinate, a tetrahedron naming a node that
/// does not exist, an inverted or degenerate (quality < 1e-6) tetrahedron, or two nodes at the same
/// point (within 1e-10 of the bounding box's diagonal). mesh_statistics()
/// expects a mesh that passed.
void check_mesh(const TetMesh& mesh);
MeshStatistics mesh_statistics(const TetMesh& mesh);

}  // namespace roifem::mesh
