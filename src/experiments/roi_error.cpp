#include "experiments/roi_error.hpp"

#include <algorithm>
#include <string>

#include "common/errors.hpp"

namespace roifem::experiments {

RoiNodeDofs roi_node_dofs(const roi::Partition& p, const fem::DofMap& dofs) {
  std::vector<Index> position(static_cast<std::size_t>(dofs.num_free()), -1);
  for (std::size_t k = 0; k < p.d.size(); ++k) position[static_cast<std::size_t>(p.d[k])] = static_cast<Index>(k);
  RoiNodeDofs out;
  for (int n : p.roi_nodes) {
    std::array<Index, 3> reduced{}, full{};
    for (int c = 0; c < 3; ++c) {
      const int i = dofs.free_dof(n, c);
      if (i < 0) throw ModelError("ROI error: ROI node " + std::to_string(n) + " is partly fixed");
      full[static_cast<std::size_t>(c)] = i;
      reduced[static_cast<std::size_t>(c)] = position[static_cast<std::size_t>(i)];
    }
    out.in_reduced.push_back(reduced);
    out.in_full.push_back(full);
  }
  return out;
}

RoiNodeDofs full_node_dofs(const std::vector<int>& nodes, const fem::DofMap& dofs) {
  RoiNodeDofs out;
  for (int n : nodes) {
    std::array<Index, 3> full{};
    for (int c = 0; c < 3; ++c) {
      const int i = dofs.free_dof(n, c);
      if (i < 0) throw ModelError("ROI error: node " + std::to_string(n) + " is partly fixed");
      full[static_cast<std::size_t>(c)] = i;
    }
    out.in_full.push_back(full);
  }
  out.in_reduced = out.in_full;
  return out;
}

RoiError roi_error(const RoiNodeDofs& nodes, const Vector& u_reduced, const Vector& u_full) {
  RoiError e;
  if (nodes.in_reduced.empty()) return e;
  double sum = 0;
  for (std::size_t n = 0; n < nodes.in_reduced.size(); ++n) {
    Vec3 diff;
    for (std::size_t c = 0; c < 3; ++c) diff[static_cast<Index>(c)] = u_reduced[nodes.in_reduced[n][c]] - u_full[nodes.in_full[n][c]];
    const double distance = diff.norm();
    sum += distance;
    e.max = std::max(e.max, distance);
  }
  e.mean = sum / static_cast<double>(nodes.in_reduced.size());
  return e;
}

}  // namespace roifem::experiments
