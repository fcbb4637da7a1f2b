// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Box meshes for verification: a structured one (each of nx*ny*nz hexahedra split into six
/// tetrahedra sharing the main diagonal, Kuhn's subdivision, conforming across cells) and an
/// unstructured one meshed by Gmsh. Both name the six faces x0, x1, y0, y1, z0, z1 (2D sets
/// of nodes) and the volume "box".
#include "mesh/tet_mesh.hpp"

namespace roifem::mesh {

/// Box [0,lx] x [0,ly] x [0,lz] (metres).
TetMesh structured_box_mesh(int nx, int ny, int nz, double lx, double ly, double lz);

/// Box [0,lx] x [0,ly] x [0,lz] (metres) meshed by Gmsh with element size h (metres).
TetMesh unstructured_box_mesh(double lx, double ly, double lz, double h);

}  // namespace roifem::mesh
