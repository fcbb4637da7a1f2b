// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// A simplified brain for surgery simulation, meshed with Gmsh's OpenCASCADE kernel:
/// an ellipsoid (semi-axes 70 x 85 x 50 mm: 14 x 17 x 10 cm) with a narrow surgical opening, a
/// slit along y cut into the top, its walls the planes x = -w/2 and x = +w/2.
/// Named sets (Gmsh physical groups):
///   brain          3D  the whole volume
///   base           3D  the lowest 15% of the height (skull base and brain stem): held fixed
///   opening_left   2D  the wall x = -w/2 of the slit (a spatula pulls it towards -x)
///   opening_right  2D  the wall x = +w/2 of the slit (pulled towards +x)
///   opening_floor  2D  the bottom of the slit
/// Without the opening (BrainShape::opening false) the ellipsoid is whole and has no opening_* sets:
/// a blade cuts the incision instead (docs/cutting.md), and the slit's box marks where.
#include <filesystem>
#include <functional>

#include "mesh/tet_mesh.hpp"

namespace roifem::mesh {

struct BrainShape {  // millimetres
  double semi_axis_x = 70, semi_axis_y = 85, semi_axis_z = 50;
  double slit_width = 4, slit_length = 30, slit_depth = 20;
  bool opening = true;  ///< false: no slit is carved; the refinement then fills the slit's box
  double base_fraction = 0.15;
  /// Element size at the slit's faces relative to the rest (1: uniform; 0.25: four times smaller),
  /// growing back to the full size over slit_grading_mm: the slit's walls and corners carry the
  /// loads and a stress singularity, which a uniform mesh resolves only at very small sizes.
  /// Without the opening the size is smaller in the box the slit would take (where a blade cuts),
  /// growing back to the full size over slit_grading_mm outside it.
  double slit_refinement = 1.0;
  double slit_grading_mm = 30;
};

/// Element sizes that vary over the body (mesh/adapted_size_field.hpp), relative to the size the
/// node-count search sets: the mesher is asked for h * at(x) at x (m), within [smallest, largest].
struct RelativeSizes {
  std::function<double(const Vec3&)> at;
  double smallest = 1, largest = 1;
};

struct BrainMesh {
  TetMesh mesh;
  double element_size_mm = 0;  ///< the Gmsh size that gave the node count
  int attempts = 0;            ///< meshings needed to land within the tolerance
};

/// Meshes the brain with `target_nodes` nodes within +-tolerance (relative), adjusting the element
/// size by a secant on log(nodes) against log(size). Writes the mesh (MSH 4.1, millimetres) to
/// `output` when it is not empty, atomically. With `sizes`, the size varies as they say (the
/// shape's slit refinement must then be 1). Throws InputError for an impossible request.
BrainMesh generate_brain_mesh(Index target_nodes, const std::filesystem::path& output = {}, const BrainShape& shape = {},
                              double tolerance = 0.03, const RelativeSizes& sizes = {});

}  // namespace roifem::mesh
