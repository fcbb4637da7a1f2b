// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// XDMF 3 description of a time series of displacement fields stored in an HDF5 file, so that
/// ParaView plays the deformation (open the .xdmf; "Warp By Vector" on displacement_mm). A cut
/// mesh's topology varies in time: each time then names its own tetrahedra.
#include <filesystem>
#include <string>
#include <vector>

namespace roifem::io {

struct XdmfSeries {
  std::string h5_name;  ///< the HDF5 file's name relative to the .xdmf
  long nodes = 0, tets = 0;
  int nodes_per_tet = 4;  ///< 4 (Tetrahedron) or 10 (Tetrahedron_10, a quadratic mesh's)
  std::string nodes_dataset = "/mesh/nodes_mm", tets_dataset = "/mesh/tets";
  std::vector<double> times;        ///< s
  std::vector<std::string> fields;  ///< a (nodes x 3) dataset per time
  /// Per time, the tetrahedra dataset and its count where the topology varies (empty: the one above).
  std::vector<std::string> topologies;
  std::vector<long> topology_tets;
};

/// Writes the .xdmf atomically.
void write_xdmf(const std::filesystem::path& path, const XdmfSeries& series);

}  // namespace roifem::io
