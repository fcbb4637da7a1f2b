// SPDX-License-Identifier: GPL-3.0-or-later
#include "roi/node_dofs.hpp"

namespace roifem::roi {

namespace {

/// Each node's components through `position` (free dof -> unknown, -1 where absent).
NodeDofs map_nodes(const std::vector<int>& nodes, const fem::DofMap& dofs, const std::vector<Index>* position) {
  NodeDofs out;
  out.reserve(nodes.size());
  for (int n : nodes) {
    std::array<Index, 3> p{};
    for (int c = 0; c < 3; ++c) {
      const int i = dofs.free_dof(n, c);
      p[static_cast<std::size_t>(c)] = i < 0 ? -1 : position ? (*position)[static_cast<std::size_t>(i)] : i;
    }
    out.push_back(p);
  }
  return out;
}

}  // namespace

NodeDofs node_dofs_in_full(const std::vector<int>& nodes, const fem::DofMap& dofs) { return map_nodes(nodes, dofs, nullptr); }

NodeDofs node_dofs_in_reduced(const std::vector<int>& nodes, const Partition& partition, const fem::DofMap& dofs) {
  std::vector<Index> position(static_cast<std::size_t>(dofs.num_free()), -1);
  for (std::size_t k = 0; k < partition.d.size(); ++k) position[static_cast<std::size_t>(partition.d[k])] = static_cast<Index>(k);
  return map_nodes(nodes, dofs, &position);
}

}  // namespace roifem::roi
