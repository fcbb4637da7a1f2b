// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Writes a TetMesh as Gmsh MSH 4.1 (ASCII), its named sets as physical groups, so that
/// read_mesh() gives the same nodes, tetrahedra and sets back. Each tetrahedron (and each
/// triangle of a 2D set) lies in one discrete entity: the elements that belong to the same
/// named sets share one, and a set is the physical group of the entities that carry it.
#include <filesystem>

#include "mesh/tet_mesh.hpp"

namespace roifem::mesh {

/// Coordinates are divided by length_unit (mm: the file in millimetres). Atomic: the file
/// appears complete or not at all.
void write_msh(const TetMesh& mesh, const std::filesystem::path& output, double length_unit);

}  // namespace roifem::mesh
