// SPDX-License-Identifier: GPL-3.0-or-later
#include "anatomy/image_volume.hpp"

#include <nifti2_io.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <memory>

#include "common/errors.hpp"
#include "common/number_text.hpp"

namespace roifem::anatomy {

namespace {

struct NiftiFree {
  void operator()(nifti_image* image) const { nifti_image_free(image); }
};
using NiftiHandle = std::unique_ptr<nifti_image, NiftiFree>;

template <class T>
void convert(const void* data, std::vector<float>& out, double slope, double intercept) {
  const T* in = static_cast<const T*>(data);
  for (std::size_t n = 0; n < out.size(); ++n) out[n] = static_cast<float>(slope * static_cast<double>(in[n]) + intercept);
}

Eigen::Matrix4d affine(const nifti_dmat44& m) {
  Eigen::Matrix4d a;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) a(r, c) = m.m[r][c];
  return a;
}

/// InputError when the voxel data the header claims (nvox x nbyper bytes) cannot be in the file
/// libnifti reads it from: the .nii itself, or the .img beside a .hdr (for a two-file header in a
/// .nii, the .nii again), from vox_offset on, or its last bytes where vox_offset is negative; for a
/// .gz, deflate's largest ratio (1032:1) bounds it. libnifti allocates the claim before it reads: a
/// corrupt header would ask for terabytes.
void check_data_fits_the_file(const std::string& name, const nifti_image& header) {
  const std::unique_ptr<char, decltype(&std::free)> found(
      header.iname ? nifti_findimgname(header.iname, header.nifti_type) : nullptr, &std::free);
  if (!found)
    throw InputError(name + ": the header reads, but the file of its voxel data (" +
                     std::string(header.iname ? header.iname : "unnamed") + ", or a .img or .nii beside it) is not there");
  const std::string data_file = found.get();
  const auto file_bytes = static_cast<double>(std::filesystem::file_size(data_file));
  const bool compressed = nifti_is_gzfile(data_file.c_str()) != 0;
  const double offset = static_cast<double>(std::max<std::int64_t>(header.iname_offset, 0));
  const double claimed = static_cast<double>(header.nvox) * static_cast<double>(header.nbyper);
  const double room = compressed ? 1032.0 * file_bytes : file_bytes - offset;
  if (header.nvox >= 0 && header.nbyper > 0 && claimed <= room) return;
  const std::string file = data_file == name ? "the file" : "its data file " + data_file;
  throw InputError(name + ": the header claims " + std::to_string(header.nvox) + " voxels of " + std::to_string(header.nbyper) +
                   " bytes (" + number_text(claimed) + " bytes), and " + file + ", of " + number_text(file_bytes) + " bytes" +
                   (compressed ? " compressed, cannot hold them (a truncated file, or a corrupt header)"
                               : " with the data at byte " + number_text(offset) +
                                     ", does not hold them (a truncated file, or a corrupt header)"));
}

/// InputError unless the header's own voxel sizes pixdim[1..3] are positive and finite.
void check_voxel_sizes(const std::string& name) {
  int version = 0;
  std::unique_ptr<void, decltype(&std::free)> header(nifti_read_header(name.c_str(), &version, 1), &std::free);
  double pixdim[3] = {0, 0, 0};
  if (header && version == 1)
    for (int i = 0; i < 3; ++i) pixdim[i] = static_cast<const nifti_1_header*>(header.get())->pixdim[i + 1];
  else if (header && version == 2)
    for (int i = 0; i < 3; ++i) pixdim[i] = static_cast<const nifti_2_header*>(header.get())->pixdim[i + 1];
  for (int i = 0; i < 3; ++i)
    if (!(pixdim[i] > 0 && std::isfinite(pixdim[i])))
      throw InputError(name + ": header field pixdim[" + std::to_string(i + 1) + "] (the voxel size along " + "xyz"[i] + ") is " +
                       std::to_string(pixdim[i]) +
                       ", and neither sform_code nor qform_code gives a voxel-to-millimetre transform: the image has no size");
}

}  // namespace

float ImageVolume::nearest(const Eigen::Vector3d& mm, float outside) const {
  const Eigen::Vector3d ijk = to_index(mm);
  const int i = static_cast<int>(std::lround(ijk.x())), j = static_cast<int>(std::lround(ijk.y())),
            k = static_cast<int>(std::lround(ijk.z()));
  return inside(i, j, k) ? at(i, j, k) : outside;
}

ImageVolume read_nifti(const std::filesystem::path& file) {
  const std::string name = file.string();
  if (std::filesystem::is_directory(file)) throw InputError(name + ": is a directory, not an image file (.nii or .nii.gz)");
  if (!std::filesystem::is_regular_file(file)) throw InputError(name + ": no such image file");
  if (!std::ifstream(file)) throw InputError(name + ": cannot open the image file for reading");
  nifti_set_debug_level(0);  // libnifti prints to stderr; the error below says what went wrong
  {
    const NiftiHandle header(nifti_image_read(name.c_str(), 0));
    if (!header) throw InputError(name + ": not a readable NIfTI-1 or NIfTI-2 image (.nii or .nii.gz)");
    check_data_fits_the_file(name, *header);  // before libnifti allocates what the header claims
  }
  NiftiHandle image(nifti_image_read(name.c_str(), 1));
  if (!image) throw InputError(name + ": the header reads but the voxel data does not (a truncated file?)");
  if (!image->data)
    throw InputError(name + ": the header reads but the voxel data does not (a truncated file? " + std::to_string(image->nvox) +
                     " voxels expected)");
  if (image->nx < 2 || image->ny < 2 || image->nz < 2)
    throw InputError(name + ": a " + std::to_string(image->nx) + " x " + std::to_string(image->ny) + " x " +
                     std::to_string(image->nz) +
                     " image; a volume needs at least 2 voxels along each axis (a 2D slice "
                     "cannot be meshed)");
  if (image->nvox != image->nx * image->ny * image->nz)
    throw InputError(name + ": has " + std::to_string(image->nvox / (image->nx * image->ny * image->nz)) +
                     " volumes (a time series or a vector image); give a single 3D volume");

  ImageVolume volume;
  volume.source = name;
  volume.dims = {static_cast<int>(image->nx), static_cast<int>(image->ny), static_cast<int>(image->nz)};
  volume.values.resize(static_cast<std::size_t>(image->nvox));
  const double slope = image->scl_slope == 0 || !std::isfinite(image->scl_slope) ? 1.0 : image->scl_slope;
  const double intercept = std::isfinite(image->scl_inter) ? image->scl_inter : 0.0;
  switch (image->datatype) {
    case DT_UINT8:
      convert<std::uint8_t>(image->data, volume.values, slope, intercept);
      break;
    case DT_INT8:
      convert<std::int8_t>(image->data, volume.values, slope, intercept);
      break;
    case DT_INT16:
      convert<std::int16_t>(image->data, volume.values, slope, intercept);
      break;
    case DT_UINT16:
      convert<std::uint16_t>(image->data, volume.values, slope, intercept);
      break;
    case DT_INT32:
      convert<std::int32_t>(image->data, volume.values, slope, intercept);
      break;
    case DT_UINT32:
      convert<std::uint32_t>(image->data, volume.values, slope, intercept);
      break;
    case DT_FLOAT32:
      convert<float>(image->data, volume.values, slope, intercept);
      break;
    case DT_FLOAT64:
      convert<double>(image->data, volume.values, slope, intercept);
      break;
    default:
      throw InputError(name + ": voxel type '" + nifti_datatype_string(image->datatype) +
                       "' is not supported (integers, float32 or float64)");
  }

  // The sform is the scanner-independent (template) space, the qform the scanner's; without
  // either (ANALYZE-style), the voxel sizes alone. libnifti reads a voxel size <= 0 as 1 mm: the
  // header's own pixdim must say it.
  if (image->sform_code <= 0 && image->qform_code <= 0) check_voxel_sizes(name);
  if (image->sform_code > 0)
    volume.index_to_mm = affine(image->sto_xyz);
  else if (image->qform_code > 0)
    volume.index_to_mm = affine(image->qto_xyz);
  else
    volume.index_to_mm.diagonal().head<3>() << image->dx, image->dy, image->dz;
  const double det = volume.index_to_mm.topLeftCorner<3, 3>().determinant();
  if (!std::isfinite(det) || std::abs(det) < 1e-12)
    throw InputError(name + ": its voxel-to-millimetre transform (sform/qform) is singular");
  return volume;
}

}  // namespace roifem::anatomy
