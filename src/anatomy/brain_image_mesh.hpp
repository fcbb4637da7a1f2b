// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// A brain mesh from a 3D image (NIfTI): the Colin27 template of mricron-data, or any
/// skull-stripped brain image or mask, meshed with CGAL Mesh_3 to a wanted number of nodes.
/// Pipeline: read -> clean the mask (largest piece, holes filled) -> average to a working grid ->
/// Gaussian blur (sigma grows with the element size: a mesh of element size h cannot carry folds
/// much finer than h) -> cut flat at the bottom and carve the surgical opening (hard, after the
/// blur, so both stay sharp) -> mesh the 0.5 level set -> name the sets.
/// Named sets written:
///   brain                  3D  every tetrahedron
///   grey_matter, white_matter, csf
///                          3D  by the image's intensity at each tetrahedron's centre: inside the
///                              cleaned mask but outside the tissue (filled ventricles, enclosed
///                              CSF) is csf; tissue is split at the Otsu threshold of its
///                              intensities (T1: white matter is the brighter); only for grey images
///   surface                2D  every boundary triangle
///   brainstem_cut          2D  the flat face of the bottom cut, where the brain is held
///   opening_left/right/floor 2D  the walls and floor of the surgical opening, when one is carved
///   <region>               2D  each --region: boundary triangles by atlas label or point and radius
/// Coordinates are the image's millimetres (MNI for Colin27).
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "anatomy/surface_regions.hpp"
#include "mesh/tet_mesh.hpp"

namespace roifem::anatomy {

/// A slit like the ellipsoid brain's, carved into the top of the brain: along y (anterior-
/// posterior), its walls the planes x = centre_x -+ width/2, `depth` below the highest point of
/// the brain over its footprint.
struct SurgicalOpening {
  double centre_x_mm = 0, centre_y_mm = 0;
  double width_mm = 4, length_mm = 30, depth_mm = 20;
  /// false: nothing is carved and no opening_* set is named; the mesh is only finer in the box
  /// (an incision that a scenario's [[cut]] makes, roifem mesh --incision)
  bool carved = true;
};

struct BrainImageOptions {
  std::filesystem::path image;
  Index target_nodes = 20000;
  double tolerance = 0.05;   ///< relative
  float threshold = 0;       ///< the mask: voxels above it
  double cut_height_mm = 5;  ///< the brainstem cut: this much of the brain's bottom removed
  std::optional<SurgicalOpening> opening;
  std::filesystem::path atlas;  ///< label image for label regions; its table is <atlas>.txt beside it
  std::vector<RegionSpec> regions;
  bool tissues = true;  ///< grey_matter / white_matter / csf sets
  unsigned seed = 1;    ///< CGAL's random choices: the same options give the same file
};

struct BrainImageMesh {
  mesh::TetMesh mesh;
  double size_mm = 0;  ///< the CGAL cell and facet size that gave the node count
  double working_voxel_mm = 0, blur_sigma_mm = 0;
  int attempts = 0;
  double quality_min_meshed = 0;  ///< before smoothing the poor tetrahedra's nodes
  Index caps_removed = 0;         ///< flat tetrahedra on the surface removed
  double mask_volume_mm3 = 0;     ///< the cleaned, cut (and carved) mask at the image's resolution
  double cut_plane_z_mm = 0;
  /// The carved opening's centre (mm): over its footprint's centre, half its depth below the
  /// brain's highest point there; the paper's ROIs gather around it (roifem paper --target-mm).
  std::optional<Eigen::Vector3d> opening_centre_mm;
  double tissue_threshold = 0;  ///< Otsu threshold between grey and white (0: no tissue sets)
  std::size_t dropped_pieces = 0, dropped_voxels = 0, filled_voxels = 0;
};

/// The Colin27 brain of Debian's mricron-data (ch2better.nii.gz, 0.5 mm, with cerebellum and
/// brainstem), its AAL atlas beside it; empty paths when the package is not installed.
std::filesystem::path colin27_image();
std::filesystem::path colin27_atlas();

/// Meshes the image to options.target_nodes within the tolerance (a secant on log(nodes) against
/// log(size)) and writes MSH 4.1 (mm) to `output` when not empty, atomically. `progress`, when
/// given, hears one line per meshing. Throws InputError for bad input: a missing or unreadable
/// image, an empty mask, a region with no boundary triangle, an opening outside the brain.
BrainImageMesh mesh_brain_image(const BrainImageOptions& options, const std::filesystem::path& output = {},
                                const std::function<void(const std::string&)>& progress = {});

}  // namespace roifem::anatomy
