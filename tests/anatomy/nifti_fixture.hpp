// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Writes small NIfTI-1 files for the tests: the header laid out by hand from the NIfTI-1
// standard (348 bytes, then 4 bytes of extension flags, then the voxels), so that the reader is
// checked against files it did not write.
#include <array>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <vector>

namespace roifem::test {

/// How write_nifti lays the file out; the defaults make a sound single-file (.nii) image.
struct NiftiLayout {
  std::size_t truncate_to = 0;  ///< cut the file to this many bytes (0: whole)
  bool sform = true;            ///< false: sform_code 0, no voxel-to-millimetre transform
  bool two_file = false;        ///< magic "ni1" (header and voxels in two files) instead of "n+1"
  float vox_offset = 352;       ///< where the header says the voxels start
  bool pair = false;            ///< the header alone in `file` (a .hdr), the voxels in the .img beside it
};

/// A float32 image of nx x ny x nz voxels of `voxel_mm`, origin at `origin_mm`, value(i, j, k),
/// laid out as `layout` says.
inline void write_nifti(const std::filesystem::path& file, std::array<int, 3> dims, double voxel_mm,
                        std::array<double, 3> origin_mm, const std::function<float(int, int, int)>& value,
                        const NiftiLayout& layout = {}) {
  const bool sform = layout.sform;
  std::array<char, 352> header{};
  auto put = [&](std::size_t offset, auto v) { std::memcpy(header.data() + offset, &v, sizeof v); };
  put(0, std::int32_t{348});
  const std::int16_t ndim = dims[2] > 1 ? 3 : 2;
  const std::int16_t dim[8] = {
      ndim, static_cast<std::int16_t>(dims[0]), static_cast<std::int16_t>(dims[1]), static_cast<std::int16_t>(dims[2]), 1, 1, 1,
      1};
  std::memcpy(header.data() + 40, dim, sizeof dim);
  put(70, std::int16_t{16});  // DT_FLOAT32
  put(72, std::int16_t{32});  // bits per voxel
  const float pixdim[8] = {1, static_cast<float>(voxel_mm), static_cast<float>(voxel_mm), static_cast<float>(voxel_mm), 1, 1, 1,
                           1};
  std::memcpy(header.data() + 76, pixdim, sizeof pixdim);
  put(108, layout.vox_offset);                         // vox_offset
  put(112, 1.0f);                                      // scl_slope
  put(254, static_cast<std::int16_t>(sform ? 1 : 0));  // sform_code: scanner space, or none
  const float srow[12] = {static_cast<float>(voxel_mm),
                          0,
                          0,
                          static_cast<float>(origin_mm[0]),
                          0,
                          static_cast<float>(voxel_mm),
                          0,
                          static_cast<float>(origin_mm[1]),
                          0,
                          0,
                          static_cast<float>(voxel_mm),
                          static_cast<float>(origin_mm[2])};
  std::memcpy(header.data() + 280, srow, sizeof srow);
  std::memcpy(header.data() + 344, layout.two_file ? "ni1\0" : "n+1\0", 4);
  std::vector<float> voxels;  // those the file keeps: a truncated file claiming gigabytes stays small
  const std::size_t kept = layout.truncate_to > 0 ? (layout.truncate_to + sizeof(float) - 1) / sizeof(float) : SIZE_MAX;
  for (int k = 0; k < dims[2] && voxels.size() < kept; ++k)
    for (int j = 0; j < dims[1] && voxels.size() < kept; ++j)
      for (int i = 0; i < dims[0] && voxels.size() < kept; ++i) voxels.push_back(value(i, j, k));
  const auto* data = reinterpret_cast<const char*>(voxels.data());
  const std::size_t data_bytes = voxels.size() * sizeof(float);
  if (layout.pair) {
    std::ofstream(file, std::ios::binary).write(header.data(), 348);
    std::filesystem::path image = file;
    std::ofstream(image.replace_extension(".img"), std::ios::binary).write(data, static_cast<std::streamsize>(data_bytes));
    return;
  }
  std::vector<char> bytes(header.begin(), header.end());
  bytes.insert(bytes.end(), data, data + data_bytes);
  if (layout.truncate_to > 0) bytes.resize(layout.truncate_to);
  std::ofstream(file, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

}  // namespace roifem::test
