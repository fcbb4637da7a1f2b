// SPDX-License-Identifier: GPL-3.0-or-later
#include "anatomy/voxel_mask.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "common/errors.hpp"

namespace roifem::anatomy {

namespace {

/// Labels the 6-connected pieces of the voxels where `member` is true; returns per voxel a piece
/// number (0: not a member) and the sizes of the pieces (index = piece number - 1).
template <class Member>
std::vector<std::size_t> label_pieces(const ImageVolume& grid, Member member, std::vector<std::uint32_t>& label) {
  const auto [nx, ny, nz] = grid.dims;
  label.assign(grid.size(), 0);
  std::vector<std::size_t> sizes, stack;
  for (std::size_t seed = 0; seed < grid.size(); ++seed) {
    if (label[seed] != 0 || !member(seed)) continue;
    const auto piece = static_cast<std::uint32_t>(sizes.size() + 1);
    std::size_t count = 0;
    label[seed] = piece;
    stack.push_back(seed);
    while (!stack.empty()) {
      const std::size_t n = stack.back();
      stack.pop_back();
      ++count;
      const int i = static_cast<int>(n % static_cast<std::size_t>(nx));
      const int j = static_cast<int>((n / static_cast<std::size_t>(nx)) % static_cast<std::size_t>(ny));
      const int k = static_cast<int>(n / (static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny)));
      const int neighbours[6][3] = {{i - 1, j, k}, {i + 1, j, k}, {i, j - 1, k}, {i, j + 1, k}, {i, j, k - 1}, {i, j, k + 1}};
      for (const auto& q : neighbours) {
        if (!grid.inside(q[0], q[1], q[2])) continue;
        const std::size_t m = grid.index(q[0], q[1], q[2]);
        if (label[m] == 0 && member(m)) {
          label[m] = piece;
          stack.push_back(m);
        }
      }
    }
    sizes.push_back(count);
  }
  return sizes;
}

bool on_border(const ImageVolume& grid, std::size_t n) {
  const auto [nx, ny, nz] = grid.dims;
  const auto i = static_cast<int>(n % static_cast<std::size_t>(nx));
  const auto j = static_cast<int>((n / static_cast<std::size_t>(nx)) % static_cast<std::size_t>(ny));
  const auto k = static_cast<int>(n / (static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny)));
  return i == 0 || j == 0 || k == 0 || i == nx - 1 || j == ny - 1 || k == nz - 1;
}

/// The world z of every voxel centre is affine in (i, j, k): z = a i + b j + c k + d.
template <class F>
void for_each_voxel_centre(const ImageVolume& grid, F f) {
  const auto [nx, ny, nz] = grid.dims;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) f(grid.index(i, j, k), grid.to_mm(Eigen::Vector3d(i, j, k)));
}

}  // namespace

MaskCleanup clean_mask(const ImageVolume& image, float threshold) {
  MaskCleanup result;
  result.mask = image;
  ImageVolume& mask = result.mask;
  std::vector<std::uint32_t> label;
  const auto sizes = label_pieces(
      image, [&](std::size_t n) { return image.values[n] > threshold; }, label);
  if (sizes.empty())
    throw InputError(image.source + ": no voxel is above the mask threshold " + std::to_string(threshold) +
                     " (an empty mask; is it the right image, or is --threshold too high?)");
  const auto largest = static_cast<std::uint32_t>(std::max_element(sizes.begin(), sizes.end()) - sizes.begin() + 1);
  result.dropped_pieces = sizes.size() - 1;
  for (std::size_t n = 0; n < mask.size(); ++n) {
    mask.values[n] = label[n] == largest ? 1.0f : 0.0f;
    if (label[n] != 0 && label[n] != largest) ++result.dropped_voxels;
  }
  // Holes: the pieces of the background that do not reach the grid's border.
  std::vector<std::uint32_t> background;
  const auto holes = label_pieces(
      mask, [&](std::size_t n) { return mask.values[n] == 0.0f; }, background);
  std::vector<bool> outside(holes.size() + 1, false);
  for (std::size_t n = 0; n < mask.size(); ++n)
    if (background[n] != 0 && on_border(mask, n)) outside[background[n]] = true;
  for (std::size_t n = 0; n < mask.size(); ++n)
    if (background[n] != 0 && !outside[background[n]]) {
      mask.values[n] = 1.0f;
      ++result.filled_voxels;
    }
  result.voxels = static_cast<std::size_t>(std::count(mask.values.begin(), mask.values.end(), 1.0f));
  return result;
}

double cut_bottom(ImageVolume& mask, double height_mm) {
  double lowest = std::numeric_limits<double>::infinity();
  for_each_voxel_centre(mask, [&](std::size_t n, const Eigen::Vector3d& x) {
    if (mask.values[n] > 0) lowest = std::min(lowest, x.z());
  });
  const double plane = lowest + height_mm;
  for_each_voxel_centre(mask, [&](std::size_t n, const Eigen::Vector3d& x) {
    if (x.z() < plane) mask.values[n] = 0;
  });
  return plane;
}

std::size_t carve_box(ImageVolume& mask, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  std::size_t cleared = 0;
  for_each_voxel_centre(mask, [&](std::size_t n, const Eigen::Vector3d& x) {
    if (mask.values[n] > 0 && (x.array() >= lo.array()).all() && (x.array() <= hi.array()).all()) {
      mask.values[n] = 0;
      ++cleared;
    }
  });
  return cleared;
}

ImageVolume block_average(const ImageVolume& image, int factor) {
  if (factor <= 1) return image;
  ImageVolume coarse;
  coarse.source = image.source;
  for (int a = 0; a < 3; ++a)
    coarse.dims[static_cast<std::size_t>(a)] = (image.dims[static_cast<std::size_t>(a)] + factor - 1) / factor;
  coarse.values.assign(static_cast<std::size_t>(coarse.dims[0]) * static_cast<std::size_t>(coarse.dims[1]) *
                           static_cast<std::size_t>(coarse.dims[2]),
                       0.0f);
  const auto [nx, ny, nz] = image.dims;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) coarse.values[coarse.index(i / factor, j / factor, k / factor)] += image.at(i, j, k);
  const float scale = 1.0f / static_cast<float>(factor * factor * factor);
  for (float& v : coarse.values) v *= scale;  // a partial block at the border counts its missing voxels as 0
  // Coarse voxel (I, J, K) covers fine voxels f I .. f I + f - 1: its centre is fine index f I + (f - 1) / 2.
  Eigen::Matrix4d coarse_to_fine = Eigen::Matrix4d::Identity();
  coarse_to_fine.diagonal().head<3>().setConstant(factor);
  coarse_to_fine.topRightCorner<3, 1>().setConstant(0.5 * (factor - 1));
  coarse.index_to_mm = image.index_to_mm * coarse_to_fine;
  return coarse;
}

ImageVolume pad(const ImageVolume& image, int voxels) {
  ImageVolume padded;
  padded.source = image.source;
  for (std::size_t a = 0; a < 3; ++a) padded.dims[a] = image.dims[a] + 2 * voxels;
  padded.values.assign(static_cast<std::size_t>(padded.dims[0]) * static_cast<std::size_t>(padded.dims[1]) *
                           static_cast<std::size_t>(padded.dims[2]),
                       0.0f);
  const auto [nx, ny, nz] = image.dims;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) padded.values[padded.index(i + voxels, j + voxels, k + voxels)] = image.at(i, j, k);
  Eigen::Matrix4d shift = Eigen::Matrix4d::Identity();
  shift.topRightCorner<3, 1>().setConstant(-voxels);
  padded.index_to_mm = image.index_to_mm * shift;
  return padded;
}

void gaussian_blur(ImageVolume& image, double sigma_mm) {
  if (!(sigma_mm > 0)) return;
  const Eigen::Vector3d spacing = image.spacing_mm();
  std::vector<float> line;
  for (int axis = 0; axis < 3; ++axis) {
    const double sigma = sigma_mm / spacing[axis];
    const int radius = std::max(1, static_cast<int>(std::ceil(3 * sigma)));
    std::vector<float> kernel(static_cast<std::size_t>(2 * radius + 1));
    double sum = 0;
    for (std::size_t w = 0; w < kernel.size(); ++w) {
      const double r = static_cast<double>(w) - radius;
      sum += kernel[w] = static_cast<float>(std::exp(-0.5 * r * r / (sigma * sigma)));
    }
    for (float& w : kernel) w = static_cast<float>(w / sum);
    const auto n = image.dims[static_cast<std::size_t>(axis)];
    const std::size_t stride = axis == 0   ? 1
                               : axis == 1 ? static_cast<std::size_t>(image.dims[0])
                                           : static_cast<std::size_t>(image.dims[0]) * static_cast<std::size_t>(image.dims[1]);
    line.resize(static_cast<std::size_t>(n));
    const std::size_t lines = image.size() / static_cast<std::size_t>(n);
    for (std::size_t l = 0; l < lines; ++l) {
      // The first voxel of line l: l enumerates the other two axes.
      const std::size_t start = axis == 0 ? l * static_cast<std::size_t>(n)
                                : axis == 1
                                    ? (l / image.dims[0]) * image.dims[0] * static_cast<std::size_t>(n) + l % image.dims[0]
                                    : l;
      for (int p = 0; p < n; ++p) line[static_cast<std::size_t>(p)] = image.values[start + static_cast<std::size_t>(p) * stride];
      for (int p = 0; p < n; ++p) {
        float v = 0;  // zero beyond the grid: the mask is padded, so no mass leaves it
        const int first = std::max(-radius, -p), last = std::min(radius, n - 1 - p);
        const float* weight = kernel.data() + radius;  // weight[r], r in [-radius, radius]
        const float* value = line.data() + p;          // value[r]: the voxel r away
        for (int r = first; r <= last; ++r) v += weight[r] * value[r];
        image.values[start + static_cast<std::size_t>(p) * stride] = v;
      }
    }
  }
}

double integral_mm3(const ImageVolume& image) {
  double sum = 0;
  for (float v : image.values) sum += v;
  return sum * image.voxel_volume_mm3();
}

}  // namespace roifem::anatomy
