#pragma once
/// How the static part of an ROI model is reduced (see static_condensation.hpp for the maths).
#include <cstdio>
#include <string>

#include "common/errors.hpp"
#include "common/types.hpp"

namespace roifem::condensation {

enum class ReductionKind { static_condensation, guyan, craig_bampton, pod };

struct Reduction {
  ReductionKind kind = ReductionKind::static_condensation;
  Index modes = 0;          ///< Craig-Bampton: fixed-interface modes kept, or 0 to use the cut-off; POD: vectors
  double cutoff_rad_s = 0;  ///< Craig-Bampton with modes == 0: every mode below this frequency
  double snapshot_dt_s = 0.05;  ///< POD: the full model's training run (step responses), step and length
  long snapshot_steps = 200;

  /// The same reduction with a POD basis trained on a run of `steps` steps of `dt` (the run it serves).
  Reduction trained_on(double dt, long steps) const {
    Reduction r = *this;
    r.snapshot_dt_s = dt;
    r.snapshot_steps = steps;
    return r;
  }

  /// "static", "guyan", "craig-bampton-10", "craig-bampton-below-50rad/s" or "pod-40".
  std::string label() const {
    switch (kind) {
      case ReductionKind::static_condensation: return "static";
      case ReductionKind::guyan: return "guyan";
      case ReductionKind::pod: return "pod-" + std::to_string(modes);
      case ReductionKind::craig_bampton: break;
    }
    if (modes > 0) return "craig-bampton-" + std::to_string(modes);
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "craig-bampton-below-%grad/s", cutoff_rad_s);
    return buffer;
  }
};

/// K from "PREFIXK" with K a positive integer, or 0.
inline Index positive_count_after(const std::string& label, const std::string& prefix) {
  if (label.rfind(prefix, 0) != 0 || label.size() == prefix.size() ||
      label.find_first_not_of("0123456789", prefix.size()) != std::string::npos)
    return 0;
  return std::stol(label.substr(prefix.size()));
}

/// The inverse of label() for "static", "guyan", "craig-bampton-K" and "pod-K" (training at the
/// default dt and steps); InputError otherwise.
inline Reduction parse_reduction(const std::string& label) {
  if (label == "static") return {};
  if (label == "guyan") return {.kind = ReductionKind::guyan};
  if (const Index modes = positive_count_after(label, "craig-bampton-"); modes > 0)
    return {.kind = ReductionKind::craig_bampton, .modes = modes};
  if (const Index vectors = positive_count_after(label, "pod-"); vectors > 0) return {.kind = ReductionKind::pod, .modes = vectors};
  throw InputError("unknown reduction '" + label +
                   "': use static, guyan, craig-bampton-K (K modes, K >= 1) or pod-K (K POD vectors, K >= 1)");
}

}  // namespace roifem::condensation
