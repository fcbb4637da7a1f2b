// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesh/quadratic_mesh.hpp"

#include <algorithm>

#include "common/errors.hpp"

namespace roifem::mesh {

namespace {

/// The set's nodes and the midpoints of the edges with both ends among them.
std::vector<int> set_nodes(const MidsideNodes& midside, const std::vector<int>& vertices) {
  std::vector<int> nodes = vertices;
  auto holds = [&](int n) { return std::binary_search(vertices.begin(), vertices.end(), n); };
  for (std::size_t k = 0; k < midside.edges.size(); ++k)
    if (holds(midside.edges[k].first) && holds(midside.edges[k].second))
      nodes.push_back(static_cast<int>(midside.first) + static_cast<int>(k));
  return nodes;  // sorted: the midpoints are numbered after every vertex, in edge order
}

}  // namespace

TetMesh with_midside_nodes(const TetMesh& linear) {
  if (linear.is_quadratic()) throw Error("internal: " + linear.source + " already has midside nodes");
  TetMesh q;
  q.source = linear.source;
  q.warnings = linear.warnings;
  q.tets = linear.tets;
  q.midside.first = linear.num_nodes();
  q.midside.edges = unique_edges(linear);
  const Index vertices = linear.num_nodes();
  q.nodes.resize(3, vertices + static_cast<Index>(q.midside.edges.size()));
  q.nodes.leftCols(vertices) = linear.nodes;
  for (std::size_t k = 0; k < q.midside.edges.size(); ++k) {
    const auto [a, b] = q.midside.edges[k];
    q.nodes.col(vertices + static_cast<Index>(k)) = 0.5 * (linear.node(a) + linear.node(b));
  }
  q.midside.of_tet.reserve(q.tets.size());
  for (const Tet& t : q.tets)
    q.midside.of_tet.push_back({q.midside.at(t[0], t[1]), q.midside.at(t[1], t[2]), q.midside.at(t[2], t[0]),
                                q.midside.at(t[0], t[3]), q.midside.at(t[1], t[3]), q.midside.at(t[2], t[3])});
  for (const auto& [name, set] : linear.sets) {
    NamedSet s = set;
    s.nodes = set_nodes(q.midside, set.nodes);
    q.sets.emplace(name, std::move(s));
  }
  return q;
}

}  // namespace roifem::mesh
