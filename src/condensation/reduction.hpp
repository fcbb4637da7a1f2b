#pragma once
/// How the static part of an ROI model is reduced (see reduced_model.hpp for the maths). The kinds
/// and their text forms (scenario key, CLI and plot labels, descriptions) live in one table,
/// reduction_table(), that the scenario reader, the CLI, `roifem paper` and the README read.
#include <span>
#include <string>
#include <string_view>

#include "common/types.hpp"

namespace roifem::condensation {

enum class ReductionKind { static_condensation, guyan, craig_bampton, pod };

/// Where a reduction's extra generalized coordinates of the static part come from.
enum class StaticBasis { none, fixed_interface_modes, pod };

struct ReductionInfo {
  ReductionKind kind;
  std::string_view key;  ///< scenario: [roi] reduction = "<key>"; CLI label: <key> or <key>-K
  bool counted;          ///< the CLI label takes a count K (modes or vectors): scenario key `modes`
  bool takes_cutoff;     ///< instead of K, every mode below a frequency: scenario key `cutoff_rad_s`
  bool carries_mass;     ///< the static part's inertia moves with the ROI (needs a lumped M, C)
  StaticBasis basis;
  std::string_view description;
};

/// Every kind, the paper's first.
std::span<const ReductionInfo> reduction_table();
const ReductionInfo& reduction_info(ReductionKind kind);
/// "static, guyan, craig-bampton, pod".
std::string reduction_key_list();
/// The keys of the rows with `flag` set, quoted: "\"craig-bampton\" (or \"pod\")".
std::string quoted_keys(bool ReductionInfo::*flag);

struct Reduction {
  ReductionKind kind = ReductionKind::static_condensation;
  Index modes = 0;              ///< Craig-Bampton: fixed-interface modes kept, or 0 to use the cut-off; POD: vectors
  double cutoff_rad_s = 0;      ///< Craig-Bampton with modes == 0: every mode below this frequency
  double snapshot_dt_s = 0.05;  ///< POD: the full model's training run (step responses), step and length
  long snapshot_steps = 200;

  const ReductionInfo& info() const { return reduction_info(kind); }
  bool is_static_condensation() const { return kind == ReductionKind::static_condensation; }
  /// The same reduction with a POD basis trained on a run of `steps` steps of `dt` (the run it serves).
  Reduction trained_on(double dt, long steps) const {
    Reduction r = *this;
    r.snapshot_dt_s = dt;
    r.snapshot_steps = steps;
    return r;
  }
  /// "static", "guyan", "craig-bampton-10", "craig-bampton-below-50rad/s" or "pod-40".
  std::string label() const;
};

/// The inverse of label() for "static", "guyan", "craig-bampton-K" and "pod-K" (training at the
/// default dt and steps); InputError listing the forms otherwise.
Reduction parse_reduction(const std::string& label);

}  // namespace roifem::condensation
