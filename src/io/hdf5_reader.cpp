// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/hdf5_reader.hpp"

#include <algorithm>

#include "common/errors.hpp"

namespace roifem::io {

Hdf5Reader::Hdf5Reader(const std::filesystem::path& path) : path_(path.string()) {
  if (!std::filesystem::is_regular_file(path)) throw InputError(path_ + ": no such results file");
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // roifem reports HDF5's errors itself
  if (H5Fis_hdf5(path_.c_str()) <= 0) throw InputError(path_ + ": not an HDF5 file");
  file_ = Handle(H5Fopen(path_.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (file_.get() < 0) throw InputError(path_ + ": cannot open it for reading");
}

bool Hdf5Reader::has(const std::string& name) const {
  // Each link on the way must exist before the next is asked for.
  std::size_t at = 0;
  do {
    at = name.find('/', at + 1);
    if (H5Lexists(file_.get(), name.substr(0, at).c_str(), H5P_DEFAULT) <= 0) return false;
  } while (at != std::string::npos);
  return true;
}

template <class T>
std::vector<T> Hdf5Reader::read(const std::string& name, hid_t type, std::vector<hsize_t>* shape) const {
  if (!has(name)) throw InputError(path_ + ": no dataset /" + name);
  const Handle set(H5Dopen2(file_.get(), name.c_str(), H5P_DEFAULT), H5Dclose);
  const Handle space(H5Dget_space(set.get()), H5Sclose);
  const int rank = H5Sget_simple_extent_ndims(space.get());
  if (set.get() < 0 || rank < 0) throw InputError(path_ + ": cannot read dataset /" + name);
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
  H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
  hsize_t count = 1;
  for (const hsize_t d : dims) count *= d;
  std::vector<T> data(count);
  if (count > 0 && H5Dread(set.get(), type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()) < 0)
    throw InputError(path_ + ": cannot read dataset /" + name + " (damaged?)");
  if (shape) *shape = dims;
  return data;
}

std::vector<double> Hdf5Reader::doubles(const std::string& name, std::vector<hsize_t>* shape) const {
  return read<double>(name, H5T_NATIVE_DOUBLE, shape);
}

std::vector<int> Hdf5Reader::ints(const std::string& name, std::vector<hsize_t>* shape) const {
  return read<int>(name, H5T_NATIVE_INT, shape);
}

std::string Hdf5Reader::attribute(const std::string& name) const {
  if (H5Aexists(file_.get(), name.c_str()) <= 0) return {};
  const Handle attr(H5Aopen(file_.get(), name.c_str(), H5P_DEFAULT), H5Aclose);
  const Handle type(H5Aget_type(attr.get()), H5Tclose);
  if (H5Tget_class(type.get()) != H5T_STRING || H5Tis_variable_str(type.get()) > 0)
    throw InputError(path_ + ": attribute " + name + " is not a text");
  std::string value(H5Tget_size(type.get()), '\0');
  if (H5Aread(attr.get(), type.get(), value.data()) < 0) throw InputError(path_ + ": cannot read attribute " + name);
  value.erase(std::find(value.begin(), value.end(), '\0'), value.end());
  return value;
}

std::string Hdf5Reader::text(const std::string& name) const {
  if (!has(name)) return attribute(name);
  const Handle set(H5Dopen2(file_.get(), name.c_str(), H5P_DEFAULT), H5Dclose);
  const Handle type(H5Dget_type(set.get()), H5Tclose);
  if (H5Tget_class(type.get()) != H5T_STRING || H5Tis_variable_str(type.get()) > 0)
    throw InputError(path_ + ": dataset /" + name + " is not a text");
  std::string value(H5Tget_size(type.get()), '\0');
  if (H5Dread(set.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, value.data()) < 0)
    throw InputError(path_ + ": cannot read dataset /" + name);
  value.erase(std::find(value.begin(), value.end(), '\0'), value.end());
  return value;
}

std::vector<std::string> Hdf5Reader::names(const std::string& group) const {
  std::vector<std::string> out;
  if (!has(group)) return out;
  const Handle g(H5Gopen2(file_.get(), group.c_str(), H5P_DEFAULT), H5Gclose);
  H5G_info_t info{};
  if (g.get() < 0 || H5Gget_info(g.get(), &info) < 0) throw InputError(path_ + ": cannot list group /" + group);
  for (hsize_t i = 0; i < info.nlinks; ++i) {
    const ssize_t size = H5Lget_name_by_idx(g.get(), ".", H5_INDEX_NAME, H5_ITER_INC, i, nullptr, 0, H5P_DEFAULT);
    std::string name(static_cast<std::size_t>(std::max<ssize_t>(size, 0)) + 1, '\0');
    H5Lget_name_by_idx(g.get(), ".", H5_INDEX_NAME, H5_ITER_INC, i, name.data(), name.size(), H5P_DEFAULT);
    name.resize(static_cast<std::size_t>(std::max<ssize_t>(size, 0)));
    out.push_back(name);
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace roifem::io
