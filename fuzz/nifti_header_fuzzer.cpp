// SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer harness: any bytes as a NIfTI-1/2 file (.nii, uncompressed), written to a scratch
// file and read by roifem's reader, which hands the header to libnifti and checks what it reads
// (dimensions, voxel type, sizes, the voxel-to-millimetre transform). It may only answer with
// roifem::Error or an image whose size and transform it checked; anything else is a bug.
#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <string>

#include "anatomy/image_volume.hpp"
#include "common/errors.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string file = "/tmp/roifem-nifti-fuzz-" + std::to_string(getpid()) + ".nii";
  std::ofstream(file, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data), static_cast<long>(size));
  try {
    const roifem::anatomy::ImageVolume image = roifem::anatomy::read_nifti(file);
    const auto voxels = static_cast<std::size_t>(image.dims[0]) * static_cast<std::size_t>(image.dims[1]) *
                        static_cast<std::size_t>(image.dims[2]);
    if (image.values.size() != voxels || image.dims[0] < 2 || image.dims[1] < 2 || image.dims[2] < 2) std::abort();
    const double det = image.index_to_mm.topLeftCorner<3, 3>().determinant();
    if (!std::isfinite(det) || det == 0) std::abort();
  } catch (const roifem::Error&) {
  }
  return 0;
}
