// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// A brain mask from an image, cleaned for meshing, and the grey image the mesher reads:
///   threshold -> largest 6-connected piece (drops loose specks) -> interior holes filled
///   (ventricles, enclosed CSF) -> cut flat at the bottom (the brainstem cut) -> carved
///   (a surgical opening) -> averaged to the working resolution -> Gaussian blur.
/// The mesher meshes the blurred mask's 0.5 level set: smooth, without the voxel staircase, and
/// without the runaway refinement of meshing a binary label image with the manifold option.
/// Masks hold 0 or 1 in ImageVolume::values; every function keeps the voxel-to-mm affine right.
#include <cstddef>

#include "anatomy/image_volume.hpp"

namespace roifem::anatomy {

struct MaskCleanup {
  ImageVolume mask;
  std::size_t voxels = 0;          ///< in the cleaned mask
  std::size_t dropped_pieces = 0;  ///< connected pieces dropped beside the largest
  std::size_t dropped_voxels = 0;  ///< their voxels
  std::size_t filled_voxels = 0;   ///< interior holes filled
};

/// Voxels with a value above `threshold`, the largest 6-connected piece, its holes filled.
/// Throws InputError naming the image when no voxel is above the threshold (an empty mask).
MaskCleanup clean_mask(const ImageVolume& image, float threshold);

/// Clears the mask's voxels whose centres lie less than `height_mm` above its lowest voxel
/// (world z); returns the height of the cut plane (mm). The cut leaves a flat face where the
/// brain is held.
double cut_bottom(ImageVolume& mask, double height_mm);

/// Clears the voxels whose centres lie inside the axis-aligned box [lo, hi] (world mm).
/// Returns how many were cleared.
std::size_t carve_box(ImageVolume& mask, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi);

/// Averages blocks of factor^3 voxels (a coarser grid for a coarse mesh); the affine follows.
ImageVolume block_average(const ImageVolume& image, int factor);

/// Adds `voxels` of zeros on every side, so that the mask's level set closes inside the grid.
ImageVolume pad(const ImageVolume& image, int voxels);

/// Gaussian blur (separable, truncated at 3 sigma) with standard deviation sigma_mm along each axis.
void gaussian_blur(ImageVolume& image, double sigma_mm);

/// Sum of the values times the voxel volume (mm^3): a mask's volume, which blurring and block
/// averaging preserve.
double integral_mm3(const ImageVolume& image);

}  // namespace roifem::anatomy
