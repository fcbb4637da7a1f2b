// SPDX-License-Identifier: GPL-3.0-or-later
#include "experiments/roi_error.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "common/errors.hpp"

namespace roifem::experiments {

namespace {

void require_whole(const roi::NodeDofs& nodes, const std::vector<int>& ids, const char* what) {
  for (std::size_t n = 0; n < nodes.size(); ++n)
    for (Index i : nodes[n])
      if (i < 0) throw ModelError(std::string("ROI error: ") + what + std::to_string(ids[n]) + " is partly fixed");
}

}  // namespace

RoiNodeDofs roi_node_dofs(const roi::Partition& p, const fem::DofMap& dofs) {
  RoiNodeDofs out{roi::node_dofs_in_reduced(p.roi_nodes, p, dofs), roi::node_dofs_in_full(p.roi_nodes, dofs)};
  require_whole(out.in_full, p.roi_nodes, "ROI node ");
  return out;
}

RoiNodeDofs full_node_dofs(const std::vector<int>& nodes, const fem::DofMap& dofs) {
  RoiNodeDofs out = same_numbering(roi::node_dofs_in_full(nodes, dofs));
  require_whole(out.in_full, nodes, "node ");
  return out;
}

RoiNodeDofs same_numbering(roi::NodeDofs nodes) {
  RoiNodeDofs out;
  out.in_full = nodes;
  out.in_reduced = std::move(nodes);
  return out;
}

RoiError roi_error(const RoiNodeDofs& nodes, const Vector& u_reduced, const Vector& u_full) {
  RoiError e;
  if (nodes.in_reduced.empty()) return e;
  double sum = 0, sum2 = 0;
  for (std::size_t n = 0; n < nodes.in_reduced.size(); ++n) {
    Vec3 diff = Vec3::Zero();
    for (std::size_t c = 0; c < 3; ++c) {
      const Index r = nodes.in_reduced[n][c], f = nodes.in_full[n][c];
      if (r >= 0 && f >= 0) diff[static_cast<Index>(c)] = u_reduced[r] - u_full[f];
    }
    const double distance = diff.norm();
    sum += distance;
    sum2 += diff.squaredNorm();
    e.max = std::max(e.max, distance);
  }
  const auto count = static_cast<double>(nodes.in_reduced.size());
  e.mean = sum / count;
  e.rms = std::sqrt(sum2 / (3 * count));
  return e;
}

}  // namespace roifem::experiments
