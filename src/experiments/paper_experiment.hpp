// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Hansen & Larsen (1998), the experiment of Section 5 reproduced: the 800-node brain, base fixed,
/// the walls of the surgical opening pulled apart by equal and opposite forces ramped over 0.5, 1
/// and 2 s and then held; dt = 0.05 s, 200 steps of the trapezoidal rule. The full dynamic model is
/// the reference for two condensed ROI models (306 and 228 nodes nearest the opening's centre).
/// Error per step: Euclidean distance between condensed and full displacements over the ROI nodes
/// (mean and max). Timing: per-step median over >= 1000 steps of each model.
/// Beyond the paper, each setup is also reduced with the static part's inertia kept (Guyan, and
/// Craig-Bampton with 5, 10 and 20 fixed-interface modes): the same errors and step costs, side by
/// side with the paper's plain static condensation.
/// Driven by spatulas instead (PaperDrive::spatulas): two rigid tools hold the walls' nodes and move
/// them apart by opening_mm over the same ramps; beyond the displacement errors, the error of the
/// force the surgeon feels (each spatula's force on the tissue, condensed against full).
#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "common/types.hpp"
#include "condensation/reduction.hpp"
#include "experiments/error_budget.hpp"

namespace roifem::experiments {

/// What widens the opening: the paper's two forces, or two spatulas that move its walls.
enum class PaperDrive { forces, spatulas };

struct PaperOptions {
  std::filesystem::path mesh;      ///< the 800-node brain (meshes/brain-800.msh)
  std::filesystem::path out;       ///< output directory
  std::string material = "paper";  ///< preset
  PaperDrive drive = PaperDrive::forces;
  double opening_mm = 4.0;  ///< static widening of the opening the force is chosen for, or the spatulas impose
  double dt = 0.05;         ///< s
  long steps = 200;
  std::vector<double> ramps_s{0.5, 1.0, 2.0};
  std::vector<Index> setup_nodes{306, 228};
  Vec3 roi_target_mm{0, 0, 40};    ///< centre of the opening (slit from z = 30 to 50 mm)
  std::string fixed_set = "base";  ///< the named set held fixed (an image brain: brainstem_cut)
  long timing_steps = 1000;
  long field_every = 10;  ///< full displacement field in results.h5 every k steps
  bool plots = true;
  /// The error budget (forces drive): space, time, reduction and model error side by side.
  bool error_budget = true;
  ErrorBudgetOptions budget;
  /// Reductions of the static part compared (the first is the paper's, static condensation).
  std::vector<condensation::Reduction> reductions{condensation::parse_reduction("static"),
                                                  condensation::parse_reduction("guyan"),
                                                  condensation::parse_reduction("craig-bampton-5"),
                                                  condensation::parse_reduction("craig-bampton-10"),
                                                  condensation::parse_reduction("craig-bampton-20"),
                                                  condensation::parse_reduction("craig-bampton-200"),
                                                  condensation::parse_reduction("pod-40")};
};

struct PaperCurve {  ///< one setup, one reduction, one ramp
  std::string setup;
  bool static_condensation = true;   ///< the paper's reduction
  std::string reduction = "static";  ///< its label
  double ramp_s = 0;
  std::vector<double> mean_mm, max_mm;  ///< per step 1..steps
  /// Spatulas only, per step: the largest of the spatulas' force errors |F_reduced - F_full| and
  /// the largest force |F_full| (mN).
  std::vector<double> force_err_mN, force_full_mN;
};

struct PaperTiming {
  std::string model;
  Index nodes = 0, dofs = 0;
  double step_s_median = 0, step_s_p99 = 0, setup_s = 0;
};

struct ReductionRow {               ///< one setup, one reduction, at the fastest (first) ramp
  std::string setup, reduction;     ///< reduction: its label
  bool static_condensation = true;  ///< the paper's reduction
  Index dofs = 0, extra_dofs = 0;   ///< of the reduced system; beyond the ROI's own
  double ramp_s = 0, peak_max_mm = 0, steady_mean_mm = 0;
  double step_s_median = 0, setup_s = 0;
  double peak_force_err_mN = 0;  ///< spatulas only
};

struct PaperResults {
  PaperDrive drive = PaperDrive::forces;
  double force_N = 0;                        ///< per wall: applied, or (spatulas) held at rest
  double opening_mm = 0;                     ///< static widening it gives
  std::vector<PaperCurve> curves;            ///< static condensation (the paper's), setup-major
  std::vector<PaperCurve> reduction_curves;  ///< every reduction (static included), every setup and ramp
  std::vector<ReductionRow> reductions;
  std::vector<PaperTiming> timing;     ///< full first, then the setups
  std::vector<Index> interface_nodes;  ///< per setup
  std::optional<ErrorBudget> budget;   ///< forces drive, when asked
};

/// Runs the experiment, writes errors.csv, timing.csv, results.h5, results.xdmf and (if asked and
/// Python with matplotlib is there) the PNG plots into options.out; progress and Table 2 go to `log`.
PaperResults run_paper_experiment(const PaperOptions& options, std::ostream& log);

/// Hansen & Larsen's Table 2 (1998 hardware): seconds per step.
inline constexpr double paper_full_step_s = 0.440, paper_setup1_step_s = 0.071, paper_setup2_step_s = 0.037;
/// The paper's Fig. 6: setup 1's max error at the 0.5 s ramp peaks at about 6 mm (mm).
inline constexpr double paper_peak_max_error_mm = 6.0;

}  // namespace roifem::experiments
