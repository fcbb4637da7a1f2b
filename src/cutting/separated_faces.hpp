// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Where a blade in split mode opens the mesh: the interior faces it separates. A cut that removes
/// no material has to run along faces of the mesh; the face shared by tetrahedra a and b is
/// separated when the segment joining their centroids crosses the swept surface (the blade's
/// strips, cutting/blade.hpp), at the time the blade reaches that crossing. For a blade through the
/// whole body this separates exactly the tetrahedra whose centroids lie on one side from those on
/// the other; the opened surface is made of faces, within an element of the blade's (a staircase:
/// the face-snapping of node-splitting cutters, as against the virtual node algorithm's embedding).
#include <array>
#include <vector>

#include "common/types.hpp"
#include "cutting/blade.hpp"
#include "mesh/tet_mesh.hpp"

namespace roifem::cutting {

/// An interior face the blade separates: the two tetrahedra sharing it (a < b), and when.
struct SeparatedFace {
  Index a = 0, b = 0;
  double time = 0;  ///< s
};

/// Per tetrahedron, the tetrahedron across its face opposite corner k (k = 0..3), or -1 on the
/// boundary. Throws ModelError naming the face when three or more tetrahedra share one.
std::vector<std::array<Index, 4>> face_neighbours(const mesh::TetMesh& mesh);

/// The faces the blade separates, each with the earliest time it reaches the crossing of their
/// centroids' segment, ascending by time (then by a, b). `neighbours`: face_neighbours(mesh).
/// Throws InputError for a quadratic mesh.
std::vector<SeparatedFace> separated_faces(const Blade& blade, const mesh::TetMesh& mesh,
                                           const std::vector<std::array<Index, 4>>& neighbours);

}  // namespace roifem::cutting
