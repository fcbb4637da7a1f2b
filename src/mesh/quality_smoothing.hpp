// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Optimization-based smoothing (after Freitag & Ollivier-Gooch): each interior node of a poor
/// tetrahedron moves to where the worst tetrahedron around it is best, among its neighbours'
/// centroid and pattern-search steps; a move is kept only if it raises that minimum and inverts
/// nothing. Boundary nodes stay, unless a projection onto the boundary's surface is given: then
/// they move too, each candidate projected back onto the surface, and a move that turns any of
/// the node's boundary triangles by more than `max_turn_deg` is refused (sharp edges stay sharp).
#include <functional>

#include "mesh/tet_mesh.hpp"

namespace roifem::mesh {

struct SmoothingReport {
  double quality_min_before = 0, quality_min_after = 0;
  Index moves = 0;  ///< node moves kept, over all sweeps
};

/// Smooths the interior nodes of tetrahedra with quality (tet_quality) below `below`, for up to
/// `sweeps` sweeps or until a sweep moves nothing.
/// `project_to_boundary` (metres to metres), when given, lets boundary nodes slide on the surface.
SmoothingReport smooth_poor_tetrahedra(TetMesh& mesh, double below = 0.3, int sweeps = 8,
                                       const std::function<Vec3(const Vec3&)>& project_to_boundary = {},
                                       double max_turn_deg = 10);

/// Removes the poor "caps" on the boundary: tetrahedra below `below` with two boundary faces
/// (flat wedges lying on the surface), when the edge their two inner faces share is not on the
/// boundary already and every node keeps a tetrahedron, so that the boundary stays a closed
/// manifold. Returns how many were removed. Named sets are not updated: call before naming them.
Index remove_boundary_caps(TetMesh& mesh, double below);

}  // namespace roifem::mesh
