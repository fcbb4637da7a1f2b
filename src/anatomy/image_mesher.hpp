// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// CGAL Mesh_3 on a grey image: the tetrahedra of the region where the image (trilinearly
/// interpolated) exceeds an iso-value, with a manifold boundary, Delaunay refinement to the
/// given sizes, then sliver perturbation and exudation (CGAL's defaults).
/// The only translation unit that includes CGAL: its headers are heavy, and nothing else needs them.
#include <array>
#include <optional>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "anatomy/image_volume.hpp"

namespace roifem::anatomy {

struct ImageMeshSizes {
  double size_mm = 5;           ///< facet size and cell size (the circumradius bound)
  double distance_mm = 0.5;     ///< facet centres within this distance of the level set
  double facet_angle_deg = 25;  ///< minimum boundary triangle angle
  double radius_edge = 3;       ///< cell radius-edge ratio bound
  /// Optional local refinement: within this world box (mm) the facet and cell size is
  /// refine_size_mm, growing by half the distance from the box up to size_mm.
  std::optional<std::pair<Eigen::Vector3d, Eigen::Vector3d>> refine_box_mm;
  double refine_size_mm = 0;
};

struct RawTetMesh {
  Eigen::Matrix3Xd points_mm;            ///< world millimetres (the image's affine applied)
  std::vector<std::array<int, 4>> tets;  ///< positively oriented in world coordinates
};

/// Meshes {x : image(x) > iso}. `image` must be zero on its border (pad() it). The random
/// choices (initial points, perturbation) come from `seed`: the same call gives the same mesh.
RawTetMesh mesh_image_level_set(const ImageVolume& image, double iso, const ImageMeshSizes& sizes, unsigned seed);

}  // namespace roifem::anatomy
