// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// How the static part of an ROI model is reduced (see reduced_model.hpp for the maths). The kinds,
/// their text forms (scenario key, CLI and plot labels, descriptions) and the maker of each one's
/// basis live in one table, reduction_table(), that the reduced model, the scenario reader, the CLI,
/// `roifem paper` and the README read. A kind is its row: adding a reduction adds a row (and, for a
/// new kind of basis, the files of its maker).
#include <span>
#include <string>
#include <string_view>

#include "common/types.hpp"

namespace roifem::model {
struct Modes;
}

namespace roifem::condensation {

struct BasisRequest;  // static_basis.hpp

/// Makes a reduction's extra generalized coordinates of the static part (static_basis.hpp).
using BasisMaker = model::Modes (*)(const BasisRequest&);

struct ReductionInfo {
  std::string_view key;             ///< scenario: [roi] reduction = "<key>"; CLI label: <key> or <key>-K
  bool counted = false;             ///< the CLI label takes a count K (modes or vectors): scenario key `modes`
  bool takes_cutoff = false;        ///< instead of K, every mode below a frequency: scenario key `cutoff_rad_s`
  bool carries_mass = false;        ///< the static part's inertia moves with the ROI (needs a lumped M, C)
  BasisMaker make_basis = nullptr;  ///< nullptr: no coordinates beyond the static modes
  bool learns_from_loads = false;   ///< the basis is learnt from the model's own response to its loads (POD)
  std::string_view description;
};

/// Every kind, the paper's (static condensation) first.
std::span<const ReductionInfo> reduction_table();
/// The row with this key; Error (a programming error) when none has it.
const ReductionInfo& reduction_named(std::string_view key);
/// "static, guyan, craig-bampton, pod".
std::string reduction_key_list();
/// The CLI labels' forms: "static, guyan, craig-bampton-K, pod-K".
std::string reduction_label_forms();
/// The keys of the rows with `flag` set, quoted: "\"craig-bampton\" (or \"pod\")".
std::string quoted_keys(bool ReductionInfo::*flag);

struct Reduction {
  const ReductionInfo* kind = &reduction_table().front();  ///< a row of reduction_table()
  Index modes = 0;              ///< Craig-Bampton: fixed-interface modes kept, or 0 to use the cut-off; POD: vectors
  double cutoff_rad_s = 0;      ///< Craig-Bampton with modes == 0: every mode below this frequency
  double snapshot_dt_s = 0.05;  ///< POD: the full model's training run (step responses), step and length
  long snapshot_steps = 200;

  const ReductionInfo& info() const { return *kind; }
  bool is_static_condensation() const { return kind == &reduction_table().front(); }
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
