// SPDX-License-Identifier: GPL-3.0-or-later
// Result files (hdf5_file.hpp, xdmf.hpp, csv.hpp, displacement_field.hpp), read back through the
// HDF5 C API and plain text, independently of the writers.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "common/errors.hpp"
#include "common/format.hpp"
#include "common/version.hpp"
#include "fem/displacement_field.hpp"
#include "fem/dof_map.hpp"
#include "io/csv.hpp"
#include "io/hdf5_file.hpp"
#include "io/xdmf.hpp"

namespace roifem::io {
namespace {

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("roifem_io_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir / name;
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// A dataset read back by the C API: its dimensions and values.
std::pair<std::vector<hsize_t>, std::vector<double>> read_dataset(const fs::path& file, const char* name) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t d = H5Dopen2(f, name, H5P_DEFAULT);
  const hid_t space = H5Dget_space(d);
  std::vector<hsize_t> dims(static_cast<std::size_t>(H5Sget_simple_extent_ndims(space)));
  H5Sget_simple_extent_dims(space, dims.data(), nullptr);
  hsize_t count = 1;
  for (hsize_t n : dims) count *= n;
  std::vector<double> values(count);
  H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
  H5Sclose(space);
  H5Dclose(d);
  H5Fclose(f);
  return {dims, values};
}

TEST(Hdf5Writer, DatasetsAppendedRecordsAndAttributesReadBackThroughTheCApi) {
  const fs::path path = scratch("results.h5");
  {
    Hdf5Writer h5(path);
    h5.write("group/sub/values", std::vector<double>{1.0, 2.0, 3.0, 4.0, 5.0, 6.0}, {2, 3});
    AppendableDataset series = h5.appendable("series", {});
    AppendableDataset field = h5.appendable("fields/u", {2, 3}, 2);
    for (int k = 0; k < 5; ++k) {
      const double t = 0.1 * k;
      series.append(&t);
      const double record[6] = {double(k), 1.0 * k, 2.0 * k, 3.0 * k, 4.0 * k, 5.0 * k};
      field.append(record);
    }
    EXPECT_EQ(series.records(), 5u);
    h5.attribute("scenario", "a = 1");
    h5.close();
  }
  const auto [dims, values] = read_dataset(path, "/group/sub/values");
  EXPECT_EQ(dims, (std::vector<hsize_t>{2, 3}));
  EXPECT_EQ(values, (std::vector<double>{1, 2, 3, 4, 5, 6}));  // row-major, as written
  const auto [series_dims, series] = read_dataset(path, "/series");
  EXPECT_EQ(series_dims, (std::vector<hsize_t>{5}));
  EXPECT_DOUBLE_EQ(series[4], 0.4);
  const auto [field_dims, field] = read_dataset(path, "/fields/u");
  EXPECT_EQ(field_dims, (std::vector<hsize_t>{5, 2, 3}));
  EXPECT_EQ(field[4 * 6 + 5], 20.0);
  // The checksum filter is on the appended datasets.
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t d = H5Dopen2(f, "/fields/u", H5P_DEFAULT);
  const hid_t plist = H5Dget_create_plist(d);
  EXPECT_GT(H5Pget_nfilters(plist), 0);
  EXPECT_GT(H5Aexists(f, "scenario"), 0);
  H5Pclose(plist);
  H5Dclose(d);
  H5Fclose(f);
  fs::remove_all(path.parent_path());
}

TEST(Xdmf, DescribesOneGridPerTimePointingAtTheFieldsAndTheMesh) {
  const fs::path path = scratch("results.xdmf");
  write_xdmf(path, {.h5_name = "results.h5", .nodes = 7, .tets = 3, .times = {0.5, 1.0}, .fields = {"/fields/u0", "/fields/u1"}});
  const std::string xml = read_text(path);
  std::size_t grids = 0;
  for (std::size_t at = xml.find("GridType=\"Uniform\""); at != std::string::npos; at = xml.find("GridType=\"Uniform\"", at + 1))
    ++grids;
  EXPECT_EQ(grids, 2u);
  EXPECT_NE(xml.find("<Time Value=\"0.5\"/>"), std::string::npos) << xml;
  EXPECT_NE(xml.find("Dimensions=\"7 3\""), std::string::npos) << xml;
  EXPECT_NE(xml.find("Dimensions=\"3 4\""), std::string::npos) << xml;
  EXPECT_NE(xml.find("results.h5:/fields/u1"), std::string::npos) << xml;
  EXPECT_NE(xml.find("results.h5:/mesh/nodes_mm"), std::string::npos) << xml;
  EXPECT_EQ(xml.rfind("</Xdmf>\n"), xml.size() - 8);
  fs::remove_all(path.parent_path());
}

TEST(CsvWriter, TheTableAppearsOnlyWhenClosed) {
  const fs::path path = scratch("table.csv");
  {
    CsvWriter csv(path, "a,b");
    csv.row(format("%d,%.3f", 1, 0.5));
    EXPECT_FALSE(fs::exists(path));  // still under its temporary name
    csv.close();
  }
  // The first line gives roifem's version (CMake's project(VERSION), as --version prints it).
  EXPECT_EQ(read_text(path), "# roifem " + std::string(version()) + "\na,b\n1,0.500\n");
  EXPECT_TRUE(std::regex_match(std::string(version()), std::regex("[0-9]+\\.[0-9]+\\.[0-9]+")));
  const fs::path abandoned = scratch("abandoned.csv");
  {
    CsvWriter csv(abandoned, "a");
    csv.row("1");
  }  // destroyed without close(): nothing is left behind
  EXPECT_FALSE(fs::exists(abandoned));
  for (const auto& entry : fs::directory_iterator(path.parent_path()))
    EXPECT_EQ(entry.path().filename(), "table.csv") << "stray file " << entry.path();
  fs::remove_all(path.parent_path());
}

TEST(DisplacementField, IsInMillimetresWithPrescribedValuesAtConstrainedComponents) {
  // Two nodes: node 0 held in z, node 1 moved 2 mm in x.
  fem::Constraints constraints(2);
  constraints.prescribe(0, 2);
  constraints.prescribe(1, 0, 2e-3);
  const fem::DofMap dofs(constraints);
  ASSERT_EQ(dofs.num_free(), 4);
  const Vector u_free = Vector::LinSpaced(4, 1e-3, 4e-3);  // metres: x0, y0, y1, z1
  const std::vector<double> field = fem::displacement_field_mm(dofs, u_free);
  ASSERT_EQ(field.size(), 6u);
  const std::vector<double> expected{1.0, 2.0, 0.0, 2.0, 3.0, 4.0};
  for (std::size_t i = 0; i < 6; ++i) EXPECT_NEAR(field[i], expected[i], 1e-12) << i;
}

}  // namespace
}  // namespace roifem::io
