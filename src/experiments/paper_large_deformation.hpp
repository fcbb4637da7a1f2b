// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// `roifem paper --material-model neo-hookean`: the paper's experiment at large deformation. For
/// each drive (the forces, the spatulas) the full neo-Hookean model of the whole brain is the
/// reference, and three models are measured against it on each setup's ROI nodes, every ramp:
///   hybrid            the nonlinear ROI over the linear condensed remainder
///                     (model/hyperelastic_force.hpp): what the testbed offers at large deformation
///   linear condensed  the paper's model: static condensation of the linear model
///   full linear       the linear model of the whole brain: the dynamic model error alone
/// each by the trapezoidal rule at the paper's dt (Newton iterations on the nonlinear ones), under
/// the loads of the linear paper (paper_model.hpp). It prints the paper's four findings checked on
/// the hybrid, Table 2 with Newton iterations, the three models' errors, the spatulas' force errors,
/// and (forces) the error budget with two more columns: the dynamic model error and the hybrid's.
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "experiments/error_budget.hpp"
#include "experiments/paper_experiment.hpp"
#include "experiments/paper_results.hpp"

namespace roifem::experiments {

/// The models measured against the full neo-Hookean one.
enum class LargeDeformationModel { hybrid, linear_condensed, full_linear };
std::string_view model_name(LargeDeformationModel model);

struct LargeDeformationCurve {  ///< one drive, setup, model and ramp
  PaperDrive drive = PaperDrive::forces;
  std::string setup;
  LargeDeformationModel model = LargeDeformationModel::hybrid;
  double ramp_s = 0;
  std::vector<double> mean_mm, max_mm;              ///< per step 1..steps, over the setup's ROI nodes
  std::vector<double> force_err_mN, force_full_mN;  ///< spatulas: as PaperCurve's
  PaperCurve as_paper_curve() const;                ///< for the findings' checks
};

struct LargeDeformationTiming {  ///< one drive, one model, at the first ramp
  PaperDrive drive = PaperDrive::forces;
  std::string model;  ///< "full neo-hookean", "setup1 hybrid", ..., "full linear", "setup1 linear"
  Index nodes = 0, dofs = 0;
  double step_s_median = 0, step_s_p99 = 0;
  double newton_per_step = 0;  ///< 0 for a linear model (one solve per step)
  long indefinite_steps = 0;   ///< steps whose Newton matrix was indefinite (solved by LU)
};

struct LargeDeformationDrive {
  PaperDrive drive = PaperDrive::forces;
  double force_N = 0;                         ///< per wall: applied, or held at rest by the linear model
  double peak_mm = 0;                         ///< the reference's largest displacement over the ROI of setup 1, any ramp
  std::vector<LargeDeformationCurve> curves;  ///< setup-major, then model, then ramp
  std::vector<LargeDeformationTiming> timing;
  std::optional<ErrorBudget> budget;  ///< forces, when asked: with the model (dynamic) and hybrid columns
  /// Runs that stopped short (a step whose Newton iteration did not converge, an inverted element),
  /// each named with its reason; their curves cover the steps they took.
  std::vector<std::string> stopped;
};

struct LargeDeformationResults {
  double dt = 0, opening_mm = 0;
  std::vector<double> ramps_s;
  std::vector<LargeDeformationDrive> drives;
};

/// Runs the drives asked (each once), prints the report to `log` and writes
/// large_deformation.csv, large_deformation_timing.csv (and error_budget.csv) into options.out,
/// with large_deformation.png where Python's matplotlib is there.
LargeDeformationResults run_paper_large_deformation(const PaperOptions& options, const std::vector<PaperDrive>& drives,
                                                    std::ostream& log);

}  // namespace roifem::experiments
