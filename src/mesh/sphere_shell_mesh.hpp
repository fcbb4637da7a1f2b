// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// A thick-walled spherical shell (inner radius a, outer radius b), one octant (x, y, z >= 0),
/// meshed with Gmsh's OpenCASCADE kernel at a uniform element size: the verification case of
/// Lame's solution under internal pressure (experiments/lame_sphere.hpp).
/// Named sets (Gmsh physical groups):
///   shell        3D  the volume
///   inner, outer 2D  the spherical faces r = a and r = b
///   x0, y0, z0   2D  the symmetry planes x = 0, y = 0, z = 0
#include "mesh/tet_mesh.hpp"

namespace roifem::mesh {

/// Radii and size in metres. Throws InputError unless 0 < a < b and 0 < h < b - a.
TetMesh sphere_shell_octant_mesh(double inner_radius, double outer_radius, double element_size);

}  // namespace roifem::mesh
