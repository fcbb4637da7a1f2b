#pragma once
/// ROI sizing for an error budget: the smallest ROI (the N free nodes nearest a target: a ball
/// around it) whose max error against the full dynamic model stays at or below E over a scenario's
/// whole run, for each reduction of the static part. The error is the paper's distance between
/// reduced and full displacement, maximized over steps and over a fixed set of evaluated nodes:
/// the scenario's own [roi] (the surgical site), the static part recovered where it lies outside
/// a smaller candidate ROI (so a 1-node ROI cannot pass by measuring itself only). Both models run
/// the scenario's integrator at its dt; the target is the centre of the scenario's [roi].
///
/// Search: an ascending scan over N = start_nodes, then N + max(1, resolution N), ... up to every
/// free node; the answer is the first N that holds. The error does not fall monotonically with N
/// (it jumps as the ROI boundary crosses the loaded walls or stiff regions), so no bisection: it
/// could step over the smallest answer.
#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

#include "condensation/reduction.hpp"
#include "scenario/scenario.hpp"

namespace roifem::experiments {

struct RoiSizeOptions {
  std::filesystem::path scenario;
  double max_error_mm = 0.5;
  std::vector<condensation::Reduction> reductions{
      {}, {.kind = condensation::ReductionKind::guyan}, {.kind = condensation::ReductionKind::craig_bampton, .modes = 10}};
  Index start_nodes = 1;
  double resolution = 0.02;  ///< relative spacing of the N tried beyond 50 nodes
  long timing_steps = 300;
  std::filesystem::path out;  ///< optional: DIR/roi_size.csv
};

struct RoiSizeRow {
  std::string reduction;
  bool found = false;  ///< false: even the largest ROI tried misses the budget
  Index nodes = 0, dofs = 0;
  double peak_max_mm = 0, step_s_median = 0;
  int evaluations = 0;  ///< reduced models built and run
};

struct RoiSizeResults {
  Vec3 target;  ///< m
  Index free_nodes = 0;
  double full_step_s_median = 0;
  std::vector<RoiSizeRow> rows;
};

/// Throws InputError for a scenario without an ROI target ([roi] kind = ball or nearest), a
/// non-positive budget or an unknown reduction.
RoiSizeResults run_roi_size(const RoiSizeOptions& options, std::ostream& log);

}  // namespace roifem::experiments
