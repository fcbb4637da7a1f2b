// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// A 3D image on a regular grid, as read from a NIfTI file or derived from one (a mask, a blurred
/// mask, a resampled grid).
///   values:  nx * ny * nz, x fastest (index i + nx (j + ny k)), as NIfTI stores them
///   index_to_mm: the 4 x 4 affine from voxel indices (i, j, k, 1) to world millimetres (the
///   sform, else the qform, else the voxel sizes alone); for the Colin27 template, MNI space
#include <array>
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/LU>

namespace roifem::anatomy {

struct ImageVolume {
  std::array<int, 3> dims{0, 0, 0};
  std::vector<float> values;
  Eigen::Matrix4d index_to_mm = Eigen::Matrix4d::Identity();
  std::string source = "<memory>";  ///< the file it came from, for messages

  std::size_t size() const { return values.size(); }
  std::size_t index(int i, int j, int k) const {
    return static_cast<std::size_t>(i) +
           static_cast<std::size_t>(dims[0]) * (static_cast<std::size_t>(j) + static_cast<std::size_t>(dims[1]) * k);
  }
  float at(int i, int j, int k) const { return values[index(i, j, k)]; }
  bool inside(int i, int j, int k) const { return i >= 0 && j >= 0 && k >= 0 && i < dims[0] && j < dims[1] && k < dims[2]; }
  /// Edge lengths of a voxel (mm): the norms of the affine's columns.
  Eigen::Vector3d spacing_mm() const { return index_to_mm.topLeftCorner<3, 3>().colwise().norm(); }
  double voxel_volume_mm3() const { return std::abs(index_to_mm.topLeftCorner<3, 3>().determinant()); }
  Eigen::Vector3d to_mm(const Eigen::Vector3d& ijk) const {
    return index_to_mm.topLeftCorner<3, 3>() * ijk + index_to_mm.topRightCorner<3, 1>();
  }
  Eigen::Vector3d to_index(const Eigen::Vector3d& mm) const {
    return index_to_mm.topLeftCorner<3, 3>().inverse() * (mm - index_to_mm.topRightCorner<3, 1>());
  }
  /// The value at the voxel nearest to a point in millimetres, or `outside` beyond the grid.
  float nearest(const Eigen::Vector3d& mm, float outside = 0) const;
};

/// Reads a 3D NIfTI-1 or NIfTI-2 image (.nii or .nii.gz) with libnifti, as float (scl_slope and
/// scl_inter applied). Throws InputError naming the file for a missing, unreadable or truncated
/// file, an image that is not 3D (a 2D slice, a time series), or a singular voxel-to-mm affine.
ImageVolume read_nifti(const std::filesystem::path& file);

}  // namespace roifem::anatomy
