// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// The ROI model condensed across ranks, as the serial code runs it: on one rank, the system
///   M_d u'' + alpha M_d u' + K~ u = sum_k r_k(t) f~_k
/// over the ROI dofs (in the order condensed), from MUMPS's K~ and f~ (mumps_condensation.hpp)
/// and the lumped mass of the ROI's dofs.
#include <vector>

#include "distributed/mumps_condensation.hpp"
#include "model/second_order_system.hpp"

namespace roifem::distributed {

/// On rank 0 (where `condensed` holds K~ and f~). `roi_dofs`: the serial free dofs condensed onto.
model::SecondOrderSystem condensed_roi_system(const DistributedModel& model, const DistributedCondensation& condensed,
                                              const std::vector<Index>& roi_dofs);

/// The ROI's free dofs (serial numbering, ascending: roi::Partition::d) of the nodes `roi_nodes`.
std::vector<Index> roi_free_dofs(const fem::DofMap& dofs, const std::vector<int>& roi_nodes);

}  // namespace roifem::distributed
