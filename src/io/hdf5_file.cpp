// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/hdf5_file.hpp"

#include <algorithm>

#include "common/errors.hpp"
#include "common/version.hpp"

namespace roifem::io {

namespace {
/// HDF5 prints its error stack by default; roifem reports errors itself.
void silence_hdf5() { H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); }

/// File access with the metadata cache never evicting between flushes, so that the metadata on
/// disk is always the last flush's. Otherwise HDF5 may write a chunk index between two flushes that
/// points at a chunk rewritten after the flush (a checksummed chunk moves when it is rewritten) and
/// not yet on disk: a kill -9 then left the flushed steps unreadable ("addr overflow"; test
/// cli.run_stopped_by_sigKILL_keeps_its_steps, about one run in three). A results file's metadata
/// is a few kB, so holding it all costs nothing.
Handle flush_consistent_access() {
  Handle fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
  H5AC_cache_config_t config{};
  config.version = H5AC__CURR_CACHE_CONFIG_VERSION;
  if (H5Pget_mdc_config(fapl.get(), &config) < 0) return fapl;
  config.evictions_enabled = false;
  config.incr_mode = H5C_incr__off;
  config.flash_incr_mode = H5C_flash_incr__off;
  config.decr_mode = H5C_decr__off;
  H5Pset_mdc_config(fapl.get(), &config);
  return fapl;
}
}  // namespace

Hdf5Writer::Hdf5Writer(const std::filesystem::path& path) : path_(path.string()) {
  silence_hdf5();
  const Handle access = flush_consistent_access();
  file_ = Handle(H5Fcreate(path_.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, access.get()), H5Fclose);
  if (file_.get() < 0) throw InputError(path_ + ": cannot create HDF5 file");
  attribute("roifem_version", std::string(version()));
}

void Hdf5Writer::write_raw(const std::string& name, hid_t type, const void* data, const std::vector<hsize_t>& dims) {
  Handle lcpl(H5Pcreate(H5P_LINK_CREATE), H5Pclose);
  H5Pset_create_intermediate_group(lcpl.get(), 1);
  Handle space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), H5Sclose);
  Handle set(H5Dcreate2(file_.get(), name.c_str(), type, space.get(), lcpl.get(), H5P_DEFAULT, H5P_DEFAULT), H5Dclose);
  if (set.get() < 0 || H5Dwrite(set.get(), type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0)
    throw InputError(path_ + ": cannot write dataset /" + name);
}

void Hdf5Writer::write(const std::string& name, const std::vector<double>& data, const std::vector<hsize_t>& dims) {
  write_raw(name, H5T_NATIVE_DOUBLE, data.data(), dims);
}

void Hdf5Writer::write(const std::string& name, const std::vector<int>& data, const std::vector<hsize_t>& dims) {
  write_raw(name, H5T_NATIVE_INT, data.data(), dims);
}

void Hdf5Writer::attribute(const std::string& name, const std::string& value) {
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type.get(), value.empty() ? 1 : value.size());
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  Handle attr(H5Acreate2(file_.get(), name.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  if (attr.get() < 0 || H5Awrite(attr.get(), type.get(), value.c_str()) < 0)
    throw InputError(path_ + ": cannot write attribute " + name);
}

void Hdf5Writer::text(const std::string& name, const std::string& value) {
  if (value.size() <= largest_attribute_text) return attribute(name, value);
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type.get(), value.size());
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  Handle set(H5Dcreate2(file_.get(), name.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Dclose);
  if (set.get() < 0 || H5Dwrite(set.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, value.c_str()) < 0)
    throw InputError(path_ + ": cannot write dataset /" + name);
  attribute(name, "(" + std::to_string(value.size()) + " bytes, beyond an attribute's 64 KiB: in the dataset /" + name + ")");
}

AppendableDataset::AppendableDataset(hid_t file, const std::string& name, const std::vector<hsize_t>& record_shape,
                                     hsize_t records_per_chunk, const std::string& file_name)
    : record_shape_(record_shape), where_(file_name + ": dataset /" + name) {
  std::vector<hsize_t> dims{0}, max_dims{H5S_UNLIMITED}, chunk{std::max<hsize_t>(records_per_chunk, 1)};
  for (hsize_t d : record_shape) {
    dims.push_back(d);
    max_dims.push_back(d);
    chunk.push_back(d);
    record_size_ *= d;
  }
  Handle space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), max_dims.data()), H5Sclose);
  Handle dcpl(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
  H5Pset_chunk(dcpl.get(), static_cast<int>(chunk.size()), chunk.data());
  H5Pset_fletcher32(dcpl.get());
  Handle lcpl(H5Pcreate(H5P_LINK_CREATE), H5Pclose);
  H5Pset_create_intermediate_group(lcpl.get(), 1);
  set_ = Handle(H5Dcreate2(file, name.c_str(), H5T_NATIVE_DOUBLE, space.get(), lcpl.get(), dcpl.get(), H5P_DEFAULT), H5Dclose);
  if (set_.get() < 0) throw InputError(where_ + ": cannot create");
}

void AppendableDataset::append(const double* record) {
  std::vector<hsize_t> dims{records_ + 1}, start{records_}, count{1};
  for (hsize_t d : record_shape_) {
    dims.push_back(d);
    start.push_back(0);
    count.push_back(d);
  }
  if (H5Dset_extent(set_.get(), dims.data()) < 0) throw InputError(where_ + ": cannot extend (disk full?)");
  Handle file_space(H5Dget_space(set_.get()), H5Sclose);
  H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr);
  Handle memory_space(H5Screate_simple(static_cast<int>(count.size()), count.data(), nullptr), H5Sclose);
  if (H5Dwrite(set_.get(), H5T_NATIVE_DOUBLE, memory_space.get(), file_space.get(), H5P_DEFAULT, record) < 0)
    throw InputError(where_ + ": cannot write record " + std::to_string(records_) + " (disk full?)");
  ++records_;
}

void Hdf5Writer::flush() {
  if (H5Fflush(file_.get(), H5F_SCOPE_GLOBAL) < 0) throw InputError(path_ + ": cannot flush HDF5 file (disk full?)");
}

void Hdf5Writer::close() {
  if (file_.get() < 0) return;
  if (H5Fflush(file_.get(), H5F_SCOPE_GLOBAL) < 0) throw InputError(path_ + ": cannot flush HDF5 file (disk full?)");
  if (H5Fclose(file_.release()) < 0) throw InputError(path_ + ": cannot close HDF5 file (disk full?)");
}

void write_mesh(Hdf5Writer& h5, const mesh::TetMesh& mesh) {
  const Eigen::Matrix3Xd nodes_mm = mesh.nodes / mm;
  h5.write("mesh/nodes_mm", std::vector<double>(nodes_mm.data(), nodes_mm.data() + nodes_mm.size()),
           {static_cast<hsize_t>(mesh.num_nodes()), 3});
  const hsize_t per_tet = mesh.is_quadratic() ? 10 : 4;
  std::vector<int> tets;
  tets.reserve(mesh.tets.size() * per_tet);
  for (std::size_t e = 0; e < mesh.tets.size(); ++e) {
    tets.insert(tets.end(), mesh.tets[e].begin(), mesh.tets[e].end());
    if (mesh.is_quadratic()) tets.insert(tets.end(), mesh.midside.of_tet[e].begin(), mesh.midside.of_tet[e].end());
  }
  h5.write("mesh/tets", tets, {static_cast<hsize_t>(mesh.num_tets()), per_tet});
}

}  // namespace roifem::io
