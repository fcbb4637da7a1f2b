// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Helpers shared by the tests: a temporary directory, small hand-written mesh files and the
/// distorted box of the patch tests.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "mesh/box_mesh.hpp"
#include "mesh/mesh_checks.hpp"

namespace roifem::test {

/// A fresh directory under the system temp dir, removed with its contents on destruction.
class TempDir {
 public:
  TempDir() {
    std::random_device rd;
    path_ = std::filesystem::temp_directory_path() / ("roifem-test-" + std::to_string(rd()) + std::to_string(rd()));
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

inline std::filesystem::path write_file(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path) << text;
  return path;
}

/// A one-tetrahedron mesh in MSH 2.2 ASCII with the nodes in the given order (1-based tags).
inline std::string single_tet_msh(const std::string& node_block, const std::string& element_nodes) {
  return "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n" + node_block + "$EndNodes\n$Elements\n1\n1 4 2 1 1 " +
         element_nodes + "\n$EndElements\n";
}

inline const std::string unit_tet_nodes = "1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n";

/// A 1 x 0.8 x 0.6 m box meshed by Gmsh at element size h, each interior node moved at random by
/// up to 0.04 m in each coordinate (seeded), checked: a distorted mesh on which an element must
/// still reproduce what it is exact for.
inline mesh::TetMesh distorted_box(double h, unsigned seed) {
  mesh::TetMesh box = mesh::unstructured_box_mesh(1.0, 0.8, 0.6, h);
  const std::vector<int> boundary = mesh::boundary_nodes(box);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.04, 0.04);
  for (int n = 0; n < box.num_nodes(); ++n)
    if (!std::binary_search(boundary.begin(), boundary.end(), n)) box.nodes.col(n) += Vec3(jitter(rng), jitter(rng), jitter(rng));
  mesh::check_mesh(box);
  return box;
}

}  // namespace roifem::test
