#pragma once
/// The error measure of Hansen & Larsen (1998): per step, the Euclidean distance between a reduced
/// model's and the full model's displacement at each ROI node, as the mean and the max over the ROI.
#include <array>
#include <vector>

#include "common/types.hpp"
#include "fem/dof_map.hpp"
#include "roi/roi.hpp"

namespace roifem::experiments {

/// Per ROI node, its three dof positions in the reduced system (d numbering) and in the full free
/// numbering. Throws ModelError for a partly fixed ROI node (no distance is defined there).
struct RoiNodeDofs {
  std::vector<std::array<Index, 3>> in_reduced, in_full;
};
RoiNodeDofs roi_node_dofs(const roi::Partition& partition, const fem::DofMap& dofs);
/// The same for any nodes, both numberings the full free one (to compare two full fields).
RoiNodeDofs full_node_dofs(const std::vector<int>& nodes, const fem::DofMap& dofs);

struct RoiError {
  double mean = 0, max = 0;  ///< m
};
RoiError roi_error(const RoiNodeDofs& nodes, const Vector& u_reduced, const Vector& u_full);

}  // namespace roifem::experiments
