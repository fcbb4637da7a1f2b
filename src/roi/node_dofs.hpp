// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Where each node's three displacement components sit among a system's unknowns: the full model's
/// free numbering (fem::DofMap), or a reduced ROI model's, whose first unknowns are the ROI dofs d
/// in order (roi::Partition). -1 marks a fixed component (or one the reduced system lacks).
#include <array>
#include <vector>

#include "common/types.hpp"
#include "fem/dof_map.hpp"
#include "roi/roi.hpp"

namespace roifem::roi {

using NodeDofs = std::vector<std::array<Index, 3>>;  ///< #nodes x 3

NodeDofs node_dofs_in_full(const std::vector<int>& nodes, const fem::DofMap& dofs);
NodeDofs node_dofs_in_reduced(const std::vector<int>& nodes, const Partition& partition, const fem::DofMap& dofs);

}  // namespace roifem::roi
