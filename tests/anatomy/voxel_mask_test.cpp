// SPDX-License-Identifier: GPL-3.0-or-later
// The image side of real brains: NIfTI reading (against files written by hand from the standard),
// mask cleaning, block averaging and blurring (each checked on a case whose answer is known).
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <regex>

#include "anatomy/image_volume.hpp"
#include "anatomy/nifti_fixture.hpp"
#include "anatomy/voxel_mask.hpp"
#include "common/errors.hpp"
#include "test_support.hpp"

namespace roifem::anatomy {
namespace {

/// The message of the InputError that f() throws ("<no InputError>" if none).
template <class F>
std::string input_error_of(F f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "<no InputError>";
}
#define EXPECT_INPUT_ERROR(call, pattern)                                    \
  do {                                                                       \
    const std::string message = input_error_of([&] { (void)(call); });       \
    EXPECT_TRUE(std::regex_search(message, std::regex(pattern))) << message; \
  } while (false)

/// A file in this process's own scratch directory (two test runs at once share no path).
std::filesystem::path scratch(const std::string& name) {
  static const test::TempDir dir;
  return dir / name;
}

TEST(NiftiReader, ReadsValuesAndTheSformAffine) {
  const auto file = scratch("ramp.nii");
  test::write_nifti(file, {4, 5, 6}, 2.0, {-10, 20, 30},
                    [](int i, int j, int k) { return static_cast<float>(i + 10 * j + 100 * k); });
  const ImageVolume image = read_nifti(file);
  EXPECT_EQ(image.dims, (std::array<int, 3>{4, 5, 6}));
  EXPECT_EQ(image.at(3, 2, 1), 123.0f);
  EXPECT_TRUE(image.to_mm(Eigen::Vector3d(1, 2, 3)).isApprox(Eigen::Vector3d(-8, 24, 36)));
  EXPECT_DOUBLE_EQ(image.voxel_volume_mm3(), 8.0);
  EXPECT_EQ(image.nearest(Eigen::Vector3d(-8.4, 24.6, 36)), 321.0f);
}

TEST(NiftiReader, NamesAMissingATruncatedAndA2dImage) {
  EXPECT_INPUT_ERROR(read_nifti(scratch("none.nii")), "none.nii: no such image file");
  const auto truncated = scratch("truncated.nii");
  test::write_nifti(truncated, {8, 8, 8}, 1.0, {0, 0, 0}, [](int, int, int) { return 1.0f; }, {.truncate_to = 352 + 100});
  EXPECT_INPUT_ERROR(read_nifti(truncated),
                     "truncated.nii: the header claims 512 voxels of 4 bytes \\(2048 bytes\\), and the file, of 452 bytes "
                     "with the data at byte 352, does not hold them \\(a truncated file");
  const auto flat = scratch("slice.nii");
  test::write_nifti(flat, {8, 8, 1}, 1.0, {0, 0, 0}, [](int, int, int) { return 1.0f; });
  EXPECT_INPUT_ERROR(read_nifti(flat), "slice.nii: a 8 x 8 x 1 image; .*a 2D slice");
}

TEST(NiftiReader, BoundsTheDataOfATwoFileHeaderWithANegativeOffsetByTheFile) {
  // A two-file header ("ni1") in a .nii: libnifti reads the voxels from the .nii itself, and a
  // negative vox_offset means "the last bytes of the file". Found by libFuzzer: such a header
  // claiming 2 GiB passed the bound (the file's size less a negative offset) and libnifti allocated
  // it before it read.
  const auto corrupt = scratch("negative-offset.nii");
  test::write_nifti(corrupt, {1024, 1024, 512}, 1.0, {0, 0, 0}, [](int, int, int) { return 1.0f; },
                    {.truncate_to = 352 + 64, .two_file = true, .vox_offset = -2147483648.0f});
  EXPECT_INPUT_ERROR(
      read_nifti(corrupt),
      "negative-offset.nii: the header claims 536870912 voxels of 4 bytes \\(2.14748365e\\+09 bytes\\), and the file, "
      "of 416 bytes with the data at byte 0, does not hold them");
  // The same claim, sound: the voxels at the end of the file are read.
  const auto sound = scratch("negative-offset-sound.nii");
  test::write_nifti(sound, {4, 5, 6}, 1.0, {0, 0, 0},
                    [](int i, int j, int k) { return static_cast<float>(i + 10 * j + 100 * k); },
                    {.two_file = true, .vox_offset = -1});
  EXPECT_EQ(read_nifti(sound).at(3, 2, 1), 123.0f);
}

TEST(NiftiReader, ReadsAHdrImgPairAndBoundsItsDataByTheImg) {
  // ANALYZE-style pairs: the header in the .hdr (348 bytes), the voxels in the .img. The bound
  // is the .img's size, not the header's.
  const auto pair = scratch("pair.hdr");
  test::write_nifti(pair, {4, 5, 6}, 2.0, {0, 0, 0}, [](int i, int j, int k) { return static_cast<float>(i + 10 * j + 100 * k); },
                    {.two_file = true, .vox_offset = 0, .pair = true});
  EXPECT_EQ(read_nifti(pair).at(3, 2, 1), 123.0f);
  std::filesystem::resize_file(scratch("pair.img"), 100);
  EXPECT_INPUT_ERROR(read_nifti(pair),
                     "pair.hdr: the header claims 120 voxels of 4 bytes \\(480 bytes\\), and its data file "
                     ".*pair.img, of 100 bytes with the data at byte 0, does not hold them");
  std::filesystem::remove(scratch("pair.img"));
  EXPECT_INPUT_ERROR(read_nifti(pair),
                     "pair.hdr: the header reads, but the file of its voxel data \\(.*pair.img, or a .img "
                     "or .nii beside it\\) is not there");
}

TEST(NiftiReader, NamesAVoxelSizeOfZeroWithoutATransform) {
  // libnifti reads pixdim 0 as 1 mm: such an image was meshed at 1 mm voxels without a word.
  const auto sizeless = scratch("sizeless.nii");
  test::write_nifti(sizeless, {8, 8, 8}, 0.0, {0, 0, 0}, [](int, int, int) { return 1.0f; }, {.sform = false});
  EXPECT_INPUT_ERROR(read_nifti(sizeless),
                     "sizeless.nii: header field pixdim\\[1\\] \\(the voxel size along x\\) is 0.000000, and neither "
                     "sform_code nor qform_code gives a voxel-to-millimetre transform");
  const auto sized = scratch("sized.nii");  // the same without an sform, sized: read by its voxel sizes
  test::write_nifti(sized, {8, 8, 8}, 2.0, {0, 0, 0}, [](int, int, int) { return 1.0f; }, {.sform = false});
  EXPECT_DOUBLE_EQ(read_nifti(sized).voxel_volume_mm3(), 8.0);
}

/// A 20^3 grid: a ball of radius 6 around (10, 10, 10) with a hollow of radius 2 at its centre,
/// and a single loose voxel in a corner.
ImageVolume hollow_ball_with_a_speck() {
  ImageVolume grid;
  grid.dims = {20, 20, 20};
  grid.values.assign(8000, 0.0f);
  for (int k = 0; k < 20; ++k)
    for (int j = 0; j < 20; ++j)
      for (int i = 0; i < 20; ++i) {
        const double r = std::sqrt((i - 10.0) * (i - 10.0) + (j - 10.0) * (j - 10.0) + (k - 10.0) * (k - 10.0));
        grid.values[grid.index(i, j, k)] = r <= 6 && r > 2 ? 50.0f : 0.0f;
      }
  grid.values[grid.index(1, 1, 1)] = 50.0f;
  return grid;
}

TEST(MaskCleanup, DropsLoosePiecesAndFillsHoles) {
  const ImageVolume image = hollow_ball_with_a_speck();
  std::size_t ball = 0, hollow = 0;
  for (int k = 0; k < 20; ++k)
    for (int j = 0; j < 20; ++j)
      for (int i = 0; i < 20; ++i) {
        const double r2 = (i - 10.0) * (i - 10.0) + (j - 10.0) * (j - 10.0) + (k - 10.0) * (k - 10.0);
        ball += r2 <= 36 ? 1 : 0;
        hollow += r2 <= 4 ? 1 : 0;
      }
  const MaskCleanup clean = clean_mask(image, 0);
  EXPECT_EQ(clean.dropped_pieces, 1u);
  EXPECT_EQ(clean.dropped_voxels, 1u);
  EXPECT_EQ(clean.filled_voxels, hollow);
  EXPECT_EQ(clean.voxels, ball);
  EXPECT_EQ(clean.mask.at(10, 10, 10), 1.0f);
  EXPECT_EQ(clean.mask.at(1, 1, 1), 0.0f);
}

TEST(MaskCleanup, NamesAnEmptyMask) {
  ImageVolume empty;
  empty.dims = {4, 4, 4};
  empty.values.assign(64, 3.0f);
  empty.source = "dark.nii";
  EXPECT_INPUT_ERROR(clean_mask(empty, 5), "dark.nii: no voxel is above the mask threshold 5");
}

TEST(VoxelGrid, BlurAndAveragingKeepTheMaskVolume) {
  ImageVolume mask = clean_mask(hollow_ball_with_a_speck(), 0).mask;
  mask.index_to_mm.diagonal().head<3>().setConstant(0.5);
  const double volume = integral_mm3(mask);
  ImageVolume coarse = block_average(mask, 3);
  EXPECT_NEAR(integral_mm3(coarse), volume, 1e-6 * volume);  // float sums
  // The coarse voxel (3, 3, 3) covers fine voxels 9..11: its centre is fine voxel 10.
  EXPECT_TRUE(coarse.to_mm(Eigen::Vector3d(3, 3, 3)).isApprox(mask.to_mm(Eigen::Vector3d(10, 10, 10))));
  ImageVolume padded = pad(coarse, 4);
  EXPECT_TRUE(padded.to_mm(Eigen::Vector3d(7, 7, 7)).isApprox(coarse.to_mm(Eigen::Vector3d(3, 3, 3))));
  gaussian_blur(padded, 1.0);
  EXPECT_NEAR(integral_mm3(padded), volume, 1e-5 * volume);
  EXPECT_GT(padded.at(7, 7, 7), 0.9f);
}

TEST(VoxelGrid, CutAndCarveClearWhatTheySay) {
  ImageVolume mask = clean_mask(hollow_ball_with_a_speck(), 0).mask;
  const double plane = cut_bottom(mask, 3);  // the ball's lowest voxel is at k = 4
  EXPECT_DOUBLE_EQ(plane, 7.0);
  for (int j = 0; j < 20; ++j)
    for (int i = 0; i < 20; ++i) EXPECT_EQ(mask.at(i, j, 6), 0.0f);
  EXPECT_EQ(mask.at(10, 10, 7), 1.0f);
  const std::size_t cleared = carve_box(mask, Eigen::Vector3d(9.5, 0, 12), Eigen::Vector3d(10.5, 20, 20));
  EXPECT_EQ(mask.at(10, 10, 14), 0.0f);
  EXPECT_EQ(mask.at(11, 10, 14), 1.0f);
  EXPECT_GT(cleared, 0u);
}

}  // namespace
}  // namespace roifem::anatomy
