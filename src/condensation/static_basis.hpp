#pragma once
/// The static part's generalized coordinates beyond the static modes, one provider per kind
/// (ReductionInfo::basis): none; the lowest fixed-interface modes of (K_ss, M_ss) (Craig-Bampton);
/// or vectors learnt from the full model's response (POD, pod_basis.hpp). Each is M_ss-orthonormal
/// with Phi^T K_ss Phi = W^2 diagonal, so the reduction treats them alike.
#include "condensation/reduction.hpp"
#include "condensation/static_part_factor.hpp"
#include "model/second_order_system.hpp"
#include "model/spectrum.hpp"
#include "roi/roi.hpp"

namespace roifem::condensation {

/// The basis `reduction` asks for (empty for none). X: the static modes K_ss^-1 K_sI (POD trains
/// against them). Throws InputError for a Craig-Bampton request without modes or a cut-off.
model::Modes static_basis(const Reduction& reduction, const model::SecondOrderSystem& full, const roi::Partition& partition,
                          StaticPartFactor& factor, const DenseMatrix& X);

}  // namespace roifem::condensation
