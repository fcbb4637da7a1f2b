// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Brain meshes for benchmarks: generated once per node count and cached as
/// $ROIFEM_MESH_CACHE/brain-N.msh (default: ./bench-meshes), never committed.
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "mesh/brain_mesh.hpp"

namespace roifem::bench {

inline std::filesystem::path brain_mesh_file(long nodes) {
  const char* dir = std::getenv("ROIFEM_MESH_CACHE");
  const std::filesystem::path cache = dir ? dir : "bench-meshes";
  std::filesystem::create_directories(cache);
  const auto file = cache / ("brain-" + std::to_string(nodes) + ".msh");
  if (!std::filesystem::exists(file)) mesh::generate_brain_mesh(nodes, file);
  return file;
}

/// Node counts from $ROIFEM_BENCH_SIZES ("800,20000,100000"), or the given default.
inline std::vector<long> bench_sizes(const std::string& fallback) {
  const char* env = std::getenv("ROIFEM_BENCH_SIZES");
  std::stringstream in(env ? env : fallback);
  std::vector<long> sizes;
  for (std::string item; std::getline(in, item, ',');)
    if (!item.empty()) sizes.push_back(std::stol(item));
  return sizes;
}

}  // namespace roifem::bench
