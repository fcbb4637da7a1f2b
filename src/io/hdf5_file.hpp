// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// A small RAII layer over the HDF5 C API: every hid_t is closed by its owner, errors become
/// roifem::InputError naming the file and the object. Datasets are row-major as HDF5 stores them.
#include <hdf5.h>

#include <filesystem>
#include <string>
#include <vector>

#include "mesh/tet_mesh.hpp"

namespace roifem::io {

/// An owned HDF5 identifier, closed with the matching H5?close.
class Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Handle() = default;
  Handle(hid_t id, Closer close) : id_(id), close_(close) {}
  Handle(Handle&& o) noexcept : id_(o.id_), close_(o.close_) { o.id_ = H5I_INVALID_HID; }
  Handle& operator=(Handle&& o) noexcept {
    std::swap(id_, o.id_);
    std::swap(close_, o.close_);
    return *this;
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle() {
    if (id_ >= 0 && close_) close_(id_);
  }
  hid_t get() const { return id_; }
  /// Gives up ownership without closing.
  hid_t release() {
    const hid_t id = id_;
    id_ = H5I_INVALID_HID;
    return id;
  }

 private:
  hid_t id_ = H5I_INVALID_HID;
  Closer close_ = nullptr;
};

/// A dataset that grows along its first dimension, one record at a time: chunked one record per
/// chunk group, with the Fletcher32 checksum filter, so a reader detects a corrupted chunk.
class AppendableDataset {
 public:
  /// `record_shape`: the shape of one record ({} for a scalar series, {n, 3} for a field).
  AppendableDataset(hid_t file, const std::string& name, const std::vector<hsize_t>& record_shape, hsize_t records_per_chunk,
                    const std::string& file_name);
  /// Appends one record of prod(record_shape) doubles.
  void append(const double* record);
  hsize_t records() const { return records_; }

 private:
  Handle set_;
  std::vector<hsize_t> record_shape_;
  hsize_t record_size_ = 1, records_ = 0;
  std::string where_;
};

class Hdf5Writer {
 public:
  /// Creates (truncates) `path`.
  explicit Hdf5Writer(const std::filesystem::path& path);
  /// Creates intermediate groups as needed ("a/b/c").
  void write(const std::string& name, const std::vector<double>& data, const std::vector<hsize_t>& dims);
  void write(const std::string& name, const std::vector<int>& data, const std::vector<hsize_t>& dims);
  /// An extendible dataset in this file.
  AppendableDataset appendable(const std::string& name, const std::vector<hsize_t>& record_shape,
                               hsize_t records_per_chunk = 64) {
    return AppendableDataset(file_.get(), name, record_shape, records_per_chunk, path_);
  }
  /// Writes what is buffered to disk (the file stays open).
  void flush();
  /// A string attribute on the root group.
  void attribute(const std::string& name, const std::string& value);
  /// A text of any length: the attribute `name` where it fits HDF5's attribute header (64 KiB);
  /// beyond, the scalar string dataset /name, the attribute saying so (a scenario with some 400
  /// [[cut]] tables).
  void text(const std::string& name, const std::string& value);
  static constexpr std::size_t largest_attribute_text = 60000;
  /// Flushes and closes (also done by the destructor, which cannot report errors).
  void close();

 private:
  void write_raw(const std::string& name, hid_t type, const void* data, const std::vector<hsize_t>& dims);
  std::string path_;
  Handle file_;
};

/// Writes /mesh/nodes_mm (N x 3) and /mesh/tets (E x 4, 0-based; a quadratic mesh's E x 10, its
/// corners then the midpoints of edges 01 12 20 03 13 23, VTK's and XDMF's Tetrahedron_10 order):
/// what XDMF files point at.
void write_mesh(Hdf5Writer& h5, const mesh::TetMesh& mesh);

}  // namespace roifem::io
