// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// A linear mesh made quadratic for the 10-node tetrahedron (fem/tet10.hpp): one node at the
/// midpoint of every edge, so the elements are straight-sided and the body is the linear mesh's
/// own (a comparison with the linear elements is then one of elements alone, not of geometry).
/// A set gains the midpoints of the edges with both ends in it: where the linear mesh's field is
/// the set's own (fixed on a support, a tool's motion), so is the quadratic mesh's. Its triangles
/// and tetrahedra stay as they are (their corners).
#include "mesh/tet_mesh.hpp"

namespace roifem::mesh {

/// The quadratic mesh on `linear`'s tetrahedra. Error when `linear` already is quadratic.
TetMesh with_midside_nodes(const TetMesh& linear);

}  // namespace roifem::mesh
