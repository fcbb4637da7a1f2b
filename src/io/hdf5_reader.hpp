// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Reading back what Hdf5Writer wrote (a restart reads its run's results.h5): datasets as doubles
/// or ints with their shape, row-major, and texts (Hdf5Writer::text: an attribute, or a dataset
/// where it was too long for one). Errors are InputError naming the file and the object.
#include <hdf5.h>

#include <filesystem>
#include <string>
#include <vector>

#include "io/hdf5_file.hpp"

namespace roifem::io {

class Hdf5Reader {
 public:
  /// Opens `path` read-only (InputError when it is missing or not an HDF5 file).
  explicit Hdf5Reader(const std::filesystem::path& path);
  const std::string& path() const { return path_; }
  /// Whether the dataset (or group) `name` exists ("a/b/c").
  bool has(const std::string& name) const;
  /// Every value of dataset `name`, row-major; `shape` receives its dimensions.
  std::vector<double> doubles(const std::string& name, std::vector<hsize_t>* shape = nullptr) const;
  std::vector<int> ints(const std::string& name, std::vector<hsize_t>* shape = nullptr) const;
  /// The string attribute `name` of the root group ("" when it has none).
  std::string attribute(const std::string& name) const;
  /// A text Hdf5Writer::text wrote: the dataset /name where there is one, else the attribute.
  std::string text(const std::string& name) const;
  /// The names in group `group` (sorted).
  std::vector<std::string> names(const std::string& group) const;

 private:
  template <class T>
  std::vector<T> read(const std::string& name, hid_t type, std::vector<hsize_t>* shape) const;
  std::string path_;
  Handle file_;
};

}  // namespace roifem::io
