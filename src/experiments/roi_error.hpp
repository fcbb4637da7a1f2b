// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// The error measure of Hansen & Larsen (1998): per step, the Euclidean distance between a reduced
/// model's and the full model's displacement at each ROI node, as the mean and the max over the ROI.
#include <vector>

#include "common/types.hpp"
#include "fem/dof_map.hpp"
#include "roi/node_dofs.hpp"
#include "roi/roi.hpp"

namespace roifem::experiments {

/// The same nodes in two systems' numberings (roi/node_dofs.hpp): the model measured and the
/// reference it is measured against.
struct RoiNodeDofs {
  roi::NodeDofs in_reduced, in_full;
};
/// The ROI nodes in the reduced system (d numbering) and in the full free numbering. Throws
/// ModelError for a partly fixed ROI node (the paper's distance is not defined there).
RoiNodeDofs roi_node_dofs(const roi::Partition& partition, const fem::DofMap& dofs);
/// The same for any nodes, both numberings the full free one (to compare two full fields).
RoiNodeDofs full_node_dofs(const std::vector<int>& nodes, const fem::DofMap& dofs);
/// Nodes in one numbering shared by both fields (two solutions of the same system); fixed
/// components (-1) count as equal.
RoiNodeDofs same_numbering(roi::NodeDofs nodes);

struct RoiError {
  double mean = 0, max = 0;  ///< m, of the nodes' distances
  double rms = 0;            ///< m, root mean square over the nodes' 3 components
};
RoiError roi_error(const RoiNodeDofs& nodes, const Vector& u_reduced, const Vector& u_full);

}  // namespace roifem::experiments
