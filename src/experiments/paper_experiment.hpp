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
#include <string>
#include <vector>

#include "common/types.hpp"
#include "condensation/reduction.hpp"
#include "experiments/error_budget.hpp"
#include "experiments/paper_results.hpp"

namespace roifem::experiments {

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

/// Runs the experiment, writes errors.csv, timing.csv, results.h5, results.xdmf and (if asked and
/// Python with matplotlib is there) the PNG plots into options.out; progress and Table 2 go to `log`.
PaperResults run_paper_experiment(const PaperOptions& options, std::ostream& log);

}  // namespace roifem::experiments
