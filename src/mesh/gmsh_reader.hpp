// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Reads any tetrahedral mesh that Gmsh reads (.msh v2/v4, ASCII or binary, and other formats
/// Gmsh knows). Physical groups become named sets. Nodes that no tetrahedron uses are dropped.
#include <filesystem>

#include "mesh/tet_mesh.hpp"

namespace roifem::mesh {

/// `length_unit`: metres per file length unit (1e-3: the file is in millimetres).
/// Throws InputError naming the file on a missing, malformed or tetrahedron-free file.
TetMesh read_mesh(const std::filesystem::path& file, double length_unit = mm);

/// Converts the model held by the current Gmsh session (needs a GmshSession).
TetMesh extract_tet_mesh(const std::string& source, double length_unit);

}  // namespace roifem::mesh
