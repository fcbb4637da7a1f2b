// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// The static part's generalized coordinates beyond the static modes. Each reduction's row names
/// its maker (ReductionInfo::make_basis): none; the lowest fixed-interface modes of (K_ss, M_ss)
/// (Craig-Bampton, here); or vectors learnt from the full model's response (POD, pod_basis.hpp).
/// Each basis is M_ss-orthonormal with Phi^T K_ss Phi = W^2 diagonal, so the reduction treats them
/// alike.
#include "condensation/reduction.hpp"
#include "condensation/static_part_factor.hpp"
#include "model/second_order_system.hpp"
#include "model/spectrum.hpp"
#include "roi/roi.hpp"

namespace roifem::condensation {

/// What a basis maker gets: the reduction asked for, the full model and its partition, the static
/// part's factor (solve_K_ss) and lumped mass, and the static modes X = K_ss^-1 K_sI (POD trains
/// against them).
struct BasisRequest {
  const Reduction& reduction;
  const model::SecondOrderSystem& full;
  const roi::Partition& partition;
  const DenseMatrix& X;
  Vector M_s;
  model::SolveK solve_K_ss;
  Index static_dofs() const { return static_cast<Index>(partition.s.size()); }
};

/// The basis `reduction` asks for (empty when its row has no maker or the model no static part).
model::Modes static_basis(const Reduction& reduction, const model::SecondOrderSystem& full, const roi::Partition& partition,
                          StaticPartFactor& factor, const DenseMatrix& X);

/// Craig-Bampton's: the reduction's count of lowest fixed-interface modes, or every mode below its
/// cut-off when the count is 0.
model::Modes fixed_interface_modes(const BasisRequest& request);

}  // namespace roifem::condensation
