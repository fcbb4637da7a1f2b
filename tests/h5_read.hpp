// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Reading a results file's dataset back in the tests, with HDF5's C API directly (independent of
/// the writer under test).
#include <gtest/gtest.h>
#include <hdf5.h>

#include <filesystem>
#include <string>
#include <vector>

namespace roifem::test {

/// Every value of dataset `name` (any shape, row-major), as doubles.
inline std::vector<double> read_h5(const std::filesystem::path& file, const std::string& name) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  EXPECT_GE(f, 0) << file;
  const hid_t d = H5Dopen2(f, name.c_str(), H5P_DEFAULT);
  EXPECT_GE(d, 0) << name;
  const hid_t space = H5Dget_space(d);
  const hssize_t n = H5Sget_simple_extent_npoints(space);
  std::vector<double> data(static_cast<std::size_t>(n));
  H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data());
  H5Sclose(space);
  H5Dclose(d);
  H5Fclose(f);
  return data;
}

}  // namespace roifem::test
