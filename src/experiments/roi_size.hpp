// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// ROI sizing for an error budget: how large an ROI (the N free nodes nearest a target: a ball
/// around it) must be so that its max error against the full dynamic model stays at or below E
/// over a scenario's whole run, for each reduction of the static part. The error is the paper's
/// distance between reduced and full displacement, maximized over steps and over a fixed set of
/// evaluated nodes: the scenario's own [roi] (the surgical site), the static part recovered where
/// it lies outside a smaller candidate ROI (so a 1-node ROI cannot pass by measuring itself only).
/// Both models run one integrator (the trapezoidal rule unless told otherwise) at the scenario's dt,
/// so that the difference is the reduction's alone; the target is the centre of the scenario's [roi].
/// On a neo-Hookean scenario the reference is the full neo-Hookean model and the ROI model the
/// hybrid (a nonlinear ROI over the linear condensed remainder: static condensation only), whose
/// error is split at every size tried: the full model with the hybrid's law uncondensed against the
/// reference (the linear remainder's error) and the hybrid against that model (the condensation's);
/// the answer then also says from which size the remainder's error stays below the condensation's.
///
/// The answer is the size from which every larger ROI stays within the budget. The error is not
/// monotone in N (it jumps as the ROI boundary crosses the loaded walls or stiff regions: on a 5k
/// brain a 1-node ROI erred 0.16 mm, 170-480 nodes 0.22 mm), so the first size that holds is not
/// the answer. Search: a coarse geometric grid (ratio 1 + coarse) from start_nodes to every free
/// node, all of it; then a fine grid (ratio 1 + resolution) between the largest coarse size that
/// misses and the next one, scanned downwards to the first miss. "Every larger ROI" means every
/// size tried above the answer: the coarse grid's, and the fine one's next to it. Sizes below the
/// answer that hold are reported as the non-monotone stretch.
#include <filesystem>
#include <iosfwd>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "condensation/reduction.hpp"
#include "io/result_table.hpp"
#include "scenario/scenario.hpp"

namespace roifem::experiments {

struct RoiSizeOptions {
  std::filesystem::path scenario;
  double max_error_mm = 0.5;
  std::vector<condensation::Reduction> reductions{condensation::parse_reduction("static"), condensation::parse_reduction("guyan"),
                                                  condensation::parse_reduction("craig-bampton-10")};
  std::string integrator = "trapezoid";  ///< runs the full reference and every reduced model, at the scenario's dt
  Index start_nodes = 1;
  double coarse = 0.25;       ///< ratio of the coarse grid's successive sizes, less one
  double resolution = 0.02;   ///< the same for the fine grid (at least one node apart)
  long timing_steps = 300;    ///< steps timed for the step column (the full model's and each answer's)
  std::filesystem::path out;  ///< optional: DIR/roi_size.csv and DIR/roi_size_runs.csv, rewritten as the search goes
};

/// One reduced model built and run.
struct RoiSizeProbe {
  Index nodes = 0;
  double peak_max_mm = 0;
  /// A neo-Hookean scenario's split of the hybrid's error (mm): the linear remainder's and the condensation's.
  std::optional<double> remainder_mm, condensation_mm;
  bool holds(double budget_mm) const { return peak_max_mm <= budget_mm; }
};

struct RoiSizeRow {
  std::string reduction;
  double max_error_mm = 0;    ///< the budget searched for
  bool found = false;         ///< false: even the whole brain as ROI misses the budget (it cannot: error 0)
  Index nodes = 0, dofs = 0;  ///< the answer: every size tried from `nodes` up holds
  double peak_max_mm = 0, step_s_median = 0;
  Index missing_from = 0, missing_to = 0;  ///< the sizes tried that miss, smallest and largest (0: none)
  Index holds_below = 0;                   ///< largest size below the misses that holds (0: none): non-monotone
  /// Neo-Hookean: the size from which every size tried has the linear remainder's error at or below
  /// the condensation's (0: none, or not measured).
  Index remainder_below_condensation_from = 0;
  std::vector<RoiSizeProbe> probes;  ///< every size tried, in the order tried
};

struct RoiSizeResults {
  Vec3 target;  ///< m
  Index free_nodes = 0;
  double full_step_s_median = 0;
  std::string scenario_roi;  ///< the scenario's own ROI, described
  Index scenario_roi_nodes = 0;
  double scenario_peak_max_mm = 0;  ///< its own error with its own reduction
  std::vector<RoiSizeRow> rows;
};

/// One size tried: a row of roi_size_runs.csv.
struct RoiSizeRun {
  const RoiSizeRow* row = nullptr;  ///< the search it belongs to
  RoiSizeProbe probe;
};
/// Every size `row` tried, in the order tried.
std::vector<RoiSizeRun> runs_of(const RoiSizeRow& row);

/// roi_size.csv, a row per reduction, and roi_size_runs.csv, a row per size tried: the one column
/// list of each, which the CSV files and the Python module's structured arrays read
/// (io/result_table.hpp).
std::span<const io::Column<RoiSizeRow>> roi_size_columns();
std::span<const io::Column<RoiSizeRun>> roi_size_run_columns();

/// Throws InputError for a scenario without an ROI target ([roi] kind = ball or nearest), a
/// non-positive budget or an unknown reduction or integrator.
RoiSizeResults run_roi_size(const RoiSizeOptions& options, std::ostream& log);

/// The sizes a search tries first: start, then each the previous times (1 + ratio), at least one
/// more, up to and including `last`.
std::vector<Index> geometric_sizes(Index start, Index last, double ratio);

}  // namespace roifem::experiments
