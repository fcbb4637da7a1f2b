// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesh/tet_mesh.hpp"

#include "common/did_you_mean.hpp"

#include <algorithm>
#include <cmath>

#include "common/errors.hpp"

namespace roifem::mesh {

int MidsideNodes::at(int a, int b) const {
  const std::pair<int, int> key{std::min(a, b), std::max(a, b)};
  const auto it = std::lower_bound(edges.begin(), edges.end(), key);
  return it != edges.end() && *it == key ? static_cast<int>(first + (it - edges.begin())) : -1;
}

const NamedSet& TetMesh::set(const std::string& name) const {
  if (auto it = sets.find(name); it != sets.end()) return it->second;
  std::string known;
  std::vector<std::string> names;
  for (const auto& [n, s] : sets) {
    known += (known.empty() ? "" : ", ") + n;
    names.push_back(n);
  }
  throw InputError(source + ": no named set '" + name + "'" + did_you_mean(name, names) +
                   " (the mesh has: " + (known.empty() ? "no physical groups" : known) + ")");
}

double signed_volume(const TetMesh& mesh, Index e) {
  const Tet& t = mesh.tets[static_cast<std::size_t>(e)];
  const Vec3 x0 = mesh.node(t[0]);
  Mat3 J;
  J << mesh.node(t[1]) - x0, mesh.node(t[2]) - x0, mesh.node(t[3]) - x0;
  return J.determinant() / 6.0;
}

double total_volume(const TetMesh& mesh) {
  double v = 0;
  for (Index e = 0; e < mesh.num_tets(); ++e) v += signed_volume(mesh, e);
  return v;
}

double tet_quality(const TetMesh& mesh, Index e) {
  const Tet& t = mesh.tets[static_cast<std::size_t>(e)];
  double sum_l2 = 0;
  for (int a = 0; a < 4; ++a)
    for (int b = a + 1; b < 4; ++b) sum_l2 += (mesh.node(t[a]) - mesh.node(t[b])).squaredNorm();
  const double l_rms = std::sqrt(sum_l2 / 6.0);
  return 6.0 * std::sqrt(2.0) * signed_volume(mesh, e) / (l_rms * l_rms * l_rms);
}

std::vector<Triangle> boundary_faces(const TetMesh& mesh) {
  // Sort all faces by their sorted node triple; the unpaired ones are the boundary. Face k of a
  // positively oriented tetrahedron, listed as below, has its normal pointing outwards.
  static constexpr int face_nodes[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  struct Face {
    std::array<int, 3> key;
    Triangle oriented;
  };
  std::vector<Face> faces;
  faces.reserve(mesh.tets.size() * 4);
  for (const Tet& t : mesh.tets)
    for (const auto& f : face_nodes) {
      Face face{{}, {t[static_cast<std::size_t>(f[0])], t[static_cast<std::size_t>(f[1])], t[static_cast<std::size_t>(f[2])]}};
      face.key = face.oriented;
      std::sort(face.key.begin(), face.key.end());
      faces.push_back(face);
    }
  std::sort(faces.begin(), faces.end(), [](const Face& a, const Face& b) { return a.key < b.key; });
  std::vector<Triangle> boundary;
  for (std::size_t i = 0; i < faces.size();) {
    std::size_t j = i;
    while (j < faces.size() && faces[j].key == faces[i].key) ++j;
    if (j - i == 1) boundary.push_back(faces[i].oriented);
    i = j;
  }
  return boundary;
}

std::vector<int> boundary_nodes(const TetMesh& mesh) {
  std::vector<int> nodes;
  for (const Triangle& f : boundary_faces(mesh)) {
    nodes.insert(nodes.end(), f.begin(), f.end());
    if (mesh.is_quadratic())
      for (int k = 0; k < 3; ++k) nodes.push_back(mesh.midside.at(f[k], f[(k + 1) % 3]));
  }
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  return nodes;
}

std::vector<std::pair<int, int>> unique_edges(const TetMesh& mesh) {
  std::vector<std::pair<int, int>> edges;
  edges.reserve(6 * mesh.tets.size());
  for (const Tet& t : mesh.tets)
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b) edges.emplace_back(std::min(t[a], t[b]), std::max(t[a], t[b]));
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  return edges;
}

}  // namespace roifem::mesh
