// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Where the paper's error comes from, on the ROI nodes, per setup and ramp, side by side:
///   space      the paper mesh's full model against a finer reference of the same body and load
///              (the brain regenerated at reference_nodes nodes, with a chosen element), both
///              integrated alike (trapezoidal rule, the same dt); the reference is read at each ROI
///              node's position (mesh/point_locator.hpp)
///   time       the trapezoidal rule at the paper's dt against the exact modal solution of the same
///              mesh (model/modal_reference.hpp)
///   reduction  condensed against full: the paper's own error
///   model      small strain against geometrically nonlinear (CalculiX NLGEOM,
///              experiments/model_error.hpp), static at the full load
/// and, where the large-deformation paper supplies them (paper_large_deformation.hpp):
///   model (dynamic)  the full linear model against the full neo-Hookean one, in time
///   hybrid           the hybrid ROI against the full neo-Hookean model: what is left of the model
///                    error and the reduction's when the ROI takes the law (not a source: not ranked)
/// Both models run once, from rest under the load rising at unit slope; every ramp's response
/// follows by superposition, exactly for the trapezoidal rule's linear recurrence (ramps that are
/// multiples of dt). Each as the peak over the run of the largest nodal distance over the ROI, and the steady mean
/// (the ROI mean after step 100, as the paper's table).
#include <filesystem>
#include <functional>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "common/types.hpp"
#include "fem/element.hpp"
#include "model/fem_model.hpp"

namespace roifem::experiments {

struct ErrorBudgetOptions {
  Index reference_nodes = 20000;  ///< 0: no space error
  fem::Element reference_element = fem::Element::nodal_pressure;
  bool model_error = true;  ///< CalculiX, when installed
  /// Where the reference's response and CalculiX's answer are kept between runs (io/result_cache.hpp;
  /// empty: nowhere): a second run with the same inputs reads them, bit for bit, in seconds.
  std::filesystem::path cache;
};

struct ErrorCurve {  ///< per step 1..steps, mm
  std::vector<double> mean, max;
  double peak() const;         ///< the largest max
  double steady_mean() const;  ///< the mean of `mean` after step 100 (all steps when fewer)
};

struct BudgetEntry {  ///< one setup, one ramp
  std::string setup;
  double ramp_s = 0;
  ErrorCurve space, time, reduction;
  std::optional<double> model_max_mm, model_mean_mm;  ///< static, full load
  std::optional<ErrorCurve> model_dynamic, hybrid;    ///< the large-deformation paper's
  std::string dominant;                               ///< by peak
  double dominance = 0;                               ///< its peak over the next largest
};

struct ErrorBudget {
  Index reference_nodes = 0;
  std::string reference_element;
  double reference_opening_error_pct = 0;  ///< the paper mesh's static opening against the reference's
  std::vector<BudgetEntry> entries;        ///< setup-major
  std::string model_note;                  ///< why there is no model error, when there is none
};

/// What the paper's run supplies: its mesh and full model (forces drive: two opposite set forces
/// of force_N on the walls), the setups' ROI nodes, and each setup's reduction error per ramp.
struct BudgetInput {
  const model::FemModel* full = nullptr;
  std::vector<std::string> fixed_sets{"base"};
  double force_N = 0, dt = 0;
  long steps = 0;
  std::vector<double> ramps_s;
  std::vector<std::pair<std::string, std::vector<int>>> setups;  ///< name, ROI nodes
  /// Per setup (same order) and ramp: the reduction's error curve.
  std::vector<std::vector<ErrorCurve>> reduction;
  /// The same for the dynamic model error and the hybrid's (empty: not measured).
  std::vector<std::vector<ErrorCurve>> model_dynamic, hybrid;
};

/// The full model's trapezoidal run from rest under its loads rising at unit slope (f t): what
/// `read` gives of every node's displacement (3N, m) at each step 0..steps.
std::vector<Vector> unit_slope_run(const model::FemModel& full, double dt, long steps,
                                   const std::function<Vector(const Vector&)>& read);
/// The same with a progress line on a terminal (`label`) and, after the first tenth of the steps,
/// a line on `log` with the time it has taken and an estimate of the rest.
std::vector<Vector> unit_slope_run(const model::FemModel& full, double dt, long steps,
                                   const std::function<Vector(const Vector&)>& read, const std::string& label, std::ostream& log);
/// The response at steps 1..steps to the loads ramped over T, from the unit-slope one: the
/// trapezoidal rule's recurrence is linear and time-invariant and starts from rest, so with
/// min(t / T, 1) = (t - max(t - T, 0)) / T it superposes exactly, u_k = (w_k - w_{k-m}) / T for
/// T = m dt. One run then serves every ramp. Throws InputError for a T that is not a positive
/// multiple of dt.
std::vector<Vector> ramp_response(const std::vector<Vector>& w, double T, double dt);

ErrorBudget measure_error_budget(const BudgetInput& input, const ErrorBudgetOptions& options, const std::filesystem::path& out,
                                 std::ostream& log);
void print_error_budget(const ErrorBudget& budget, std::ostream& log);
/// error_budget.csv: per setup, ramp and step, each source's mean and max (mm).
void write_error_budget_csv(const ErrorBudget& budget, double dt, const std::filesystem::path& out);

}  // namespace roifem::experiments
