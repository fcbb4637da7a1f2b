// SPDX-License-Identifier: GPL-3.0-or-later
#include "simulation/cuts/cut_event.hpp"

#include <algorithm>
#include <numeric>

#include "common/number_text.hpp"

namespace roifem::simulation {

namespace {

/// Union-find over nodes, by the tetrahedra still there.
std::vector<int> pieces(const mesh::TetMesh& mesh, const std::vector<bool>& still_there) {
  std::vector<int> parent(static_cast<std::size_t>(mesh.num_nodes()));
  std::iota(parent.begin(), parent.end(), 0);
  const auto root = [&](int n) {
    while (parent[static_cast<std::size_t>(n)] != n)
      n = parent[static_cast<std::size_t>(n)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(n)])];
    return n;
  };
  for (std::size_t e = 0; e < still_there.size(); ++e)
    if (still_there[e])
      for (int k = 1; k < 4; ++k)
        parent[static_cast<std::size_t>(root(mesh.tets[e][static_cast<std::size_t>(k)]))] = root(mesh.tets[e][0]);
  for (int n = 0; n < static_cast<int>(parent.size()); ++n) parent[static_cast<std::size_t>(n)] = root(n);
  return parent;
}

std::string node_list(const std::vector<int>& nodes) {
  std::string out;
  for (std::size_t i = 0; i < nodes.size() && i < 10; ++i) out += (i ? ", " : "") + std::to_string(nodes[i]);
  if (nodes.size() > 10) out += ", ... (" + std::to_string(nodes.size()) + " in all)";
  return out;
}

}  // namespace

void warn_loose_pieces(const mesh::TetMesh& mesh, const std::vector<bool>& still_there, const std::vector<int>& touched_nodes,
                       const std::vector<bool>& supported, CutEvent& event) {
  const std::vector<int> piece = pieces(mesh, still_there);
  std::vector<int> touched;
  touched.reserve(touched_nodes.size());
  for (const int n : touched_nodes) touched.push_back(piece[static_cast<std::size_t>(n)]);
  std::sort(touched.begin(), touched.end());
  touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
  std::vector<bool> has_element(piece.size(), false);
  for (std::size_t e = 0; e < still_there.size(); ++e)
    if (still_there[e]) has_element[static_cast<std::size_t>(piece[static_cast<std::size_t>(mesh.tets[e][0])])] = true;
  for (const int root : touched) {
    if (!has_element[static_cast<std::size_t>(root)]) continue;  // a node with no element: held at rest
    std::vector<int> nodes;
    bool held = false;
    for (int n = 0; n < static_cast<int>(piece.size()); ++n)
      if (piece[static_cast<std::size_t>(n)] == root) {
        nodes.push_back(n);
        held = held || supported[static_cast<std::size_t>(n)];
      }
    if (!held)
      event.warnings.push_back("the cut at t = " + number_text(event.time) + " s set loose a piece of " +
                               std::to_string(nodes.size()) + " nodes (" + node_list(nodes) +
                               ") held by no support: it moves as a free body under its loads");
  }
}

}  // namespace roifem::simulation
