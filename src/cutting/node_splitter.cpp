// SPDX-License-Identifier: GPL-3.0-or-later
#include "cutting/node_splitter.hpp"

#include <algorithm>
#include <map>
#include <numeric>
#include <string>

#include "common/errors.hpp"

namespace roifem::cutting {

namespace {

int corner_of(const mesh::Tet& tet, int node) {
  for (int k = 0; k < 4; ++k)
    if (tet[static_cast<std::size_t>(k)] == node) return k;
  return -1;
}

}  // namespace

NodeSplitter::NodeSplitter(std::vector<mesh::Tet> tets, std::vector<std::array<Index, 4>> neighbours, Index num_nodes,
                           std::vector<std::vector<int>> copies, std::vector<bool> anchored)
    : original_(tets),
      tets_(std::move(tets)),
      neighbours_(std::move(neighbours)),
      separated_(tets_.size(), {false, false, false, false}),
      star_(static_cast<std::size_t>(num_nodes)),
      copies_(std::move(copies)),
      taken_(static_cast<std::size_t>(num_nodes), 0),
      next_copy_(num_nodes),
      anchored_(std::move(anchored)) {
  if (anchored_.empty()) anchored_.assign(tets_.size(), false);
  if (neighbours_.size() != tets_.size() || anchored_.size() != tets_.size())
    throw Error("internal: a node splitter's face neighbours do not match its mesh");
  for (std::size_t e = 0; e < tets_.size(); ++e)
    for (const int n : tets_[e]) star_[static_cast<std::size_t>(n)].push_back(static_cast<Index>(e));
}

std::vector<Rewire> NodeSplitter::separate(const std::vector<std::pair<Index, Index>>& faces) {
  std::vector<int> nodes;
  for (const auto& [a, b] : faces) {
    const auto& across = neighbours_[static_cast<std::size_t>(a)];
    const auto k = std::find(across.begin(), across.end(), b) - across.begin();
    if (k == 4) throw Error("internal: tetrahedra " + std::to_string(a) + " and " + std::to_string(b) + " share no face");
    separated_[static_cast<std::size_t>(a)][static_cast<std::size_t>(k)] = true;
    const auto& back = neighbours_[static_cast<std::size_t>(b)];
    separated_[static_cast<std::size_t>(b)][static_cast<std::size_t>(std::find(back.begin(), back.end(), a) - back.begin())] =
        true;
    for (int j = 0; j < 4; ++j)
      if (j != k) nodes.push_back(original_[static_cast<std::size_t>(a)][static_cast<std::size_t>(j)]);
  }
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  std::vector<Rewire> moved;
  for (const int n : nodes) split(n, moved);
  return moved;
}

void NodeSplitter::split(int node, std::vector<Rewire>& moved) {
  const std::vector<Index>& star = star_[static_cast<std::size_t>(node)];  // ascending
  // Pieces of the star: joined across its faces at the node that are not separated.
  std::vector<std::size_t> parent(star.size());
  std::iota(parent.begin(), parent.end(), std::size_t{0});
  const auto root = [&](std::size_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  const auto position = [&](Index e) {
    return static_cast<std::size_t>(std::lower_bound(star.begin(), star.end(), e) - star.begin());
  };
  for (std::size_t i = 0; i < star.size(); ++i) {
    const auto e = static_cast<std::size_t>(star[i]);
    const int at = corner_of(original_[e], node);
    for (int k = 0; k < 4; ++k) {
      const Index other = neighbours_[e][static_cast<std::size_t>(k)];
      if (k == at || other < 0 || separated_[e][static_cast<std::size_t>(k)]) continue;
      parent[root(i)] = root(position(other));
    }
  }
  // Each node the star's corners hold now (the node or its copies) stays with one of its pieces
  // (the lowest anchored tetrahedron's, else the lowest's); its other pieces each take a fresh copy.
  const auto held_at = [&](std::size_t i) {
    const auto e = static_cast<std::size_t>(star[i]);
    return tets_[e][static_cast<std::size_t>(corner_of(original_[e], node))];
  };
  std::map<int, std::size_t> keeper;  // held now -> the piece that keeps it
  for (std::size_t i = 0; i < star.size(); ++i)
    if (anchored_[static_cast<std::size_t>(star[i])]) keeper.try_emplace(held_at(i), root(i));
  for (std::size_t i = 0; i < star.size(); ++i) keeper.try_emplace(held_at(i), root(i));
  std::map<std::pair<int, std::size_t>, int> piece_node;  // (held now, piece) -> node it holds from now on
  for (std::size_t i = 0; i < star.size(); ++i) {
    const auto e = static_cast<std::size_t>(star[i]);
    const int at = corner_of(original_[e], node);
    const int held = tets_[e][static_cast<std::size_t>(at)];
    const auto [it, first] = piece_node.try_emplace({held, root(i)}, held);
    if (first) {
      if (keeper.at(held) != root(i)) {
        if (copies_.empty()) {
          it->second = static_cast<int>(next_copy_++);
        } else {
          auto& taken = taken_[static_cast<std::size_t>(node)];
          const auto& pool = copies_[static_cast<std::size_t>(node)];
          if (taken == pool.size())
            throw Error("internal: node " + std::to_string(node) + " splits more often than its " + std::to_string(pool.size()) +
                        " reserved copies allow");
          it->second = pool[taken++];
        }
        made_.emplace_back(it->second, node);
      }
    }
    if (it->second != held) {
      tets_[e][static_cast<std::size_t>(at)] = it->second;
      moved.push_back({static_cast<Index>(e), at, held, it->second});
    }
  }
}

}  // namespace roifem::cutting
