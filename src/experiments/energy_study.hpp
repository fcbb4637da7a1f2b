// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// `roifem energy`: each method on one scenario, its energy ledger (model/energy.hpp) over the
/// run, so that how well each keeps the balance E + D = W (kinetic plus strain energy, plus what
/// damping took, equals the loads' work) can be compared: on an undamped nonlinear scenario the
/// trapezoidal rule's drifts, `energy-momentum` holds it to rounding, and the dissipative methods
/// (BDF, L-stable DIRK) lose energy by their numerical damping. There is no reference to measure
/// against: the ledger closes for the exact solution, so its residual is each method's energy
/// error (but see the output grid below).
///
/// The ledger is evaluated on the output grid (the loads' work by the trapezoidal rule between
/// outputs): for the fixed-step methods that is their own step, and its residual is their energy
/// error; for the adaptive ones it holds the grid's quadrature error of the work too while the
/// loads change (O(dt^2)), and only its change once they are constant is their own: the column
/// drift_after_ramps_rel.
///
/// Implicit fixed-step methods run at the scenario's dt; explicit and adaptive-only ones at
/// `rtol` (atol = rtol x 1 mm), on the scenario's output grid. A run that fails (Newton, an
/// inverted element, divergence) or passes `max_run_s` keeps its samples so far and says why.
/// Writes DIR/energy.csv (every output of every run) and DIR/energy_summary.csv (one row per
/// run), rewritten as each run ends, and DIR/energy_error.png.
#include <filesystem>
#include <iosfwd>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "io/result_table.hpp"
#include "scenario/scenario.hpp"

namespace roifem::experiments {

struct EnergyStudyOptions {
  std::filesystem::path out;
  std::vector<std::string> integrators;  ///< empty: every one that takes the scenario's model
  double t_end = 0;                      ///< s (0: the scenario's dt * steps)
  double rtol = 1e-6;                    ///< for the explicit and the adaptive-only methods
  double max_run_s = 120;                ///< a run taking longer is stopped (its samples kept)
  bool plots = true;
};

struct EnergyRow {
  std::string integrator, mode;  ///< mode: fixed or adaptive
  double dt_or_tol = 0;
  long steps = 0, newton_iterations = 0, jac_evals = 0, lin_setups = 0, outputs = 0;
  double wall_s = 0;
  double work_scale_J = 0;  ///< max |W| over the run: the energy the loads put in
  /// max and final |E + D - W - E_0| / work_scale over the outputs reached (NaN: none)
  double max_error = std::numeric_limits<double>::quiet_NaN(), final_error = std::numeric_limits<double>::quiet_NaN();
  /// max |balance(t) - balance(t_c)| / work_scale for t >= t_c, the loads constant from t_c on (the
  /// ramps' end): every method's own energy error, the grid's quadrature of the work being exact
  /// there. NaN: the loads change to the end, or the model has tools.
  double drift_after_ramps = std::numeric_limits<double>::quiet_NaN();
  std::string status = "ok";
};

/// One output of one run.
struct EnergySample {
  std::string integrator;
  double t = 0, kinetic = 0, strain = 0, dissipated = 0, work = 0, balance = 0;
};

struct EnergyStudy {
  std::vector<EnergyRow> rows;
  std::vector<EnergySample> samples;
};

std::span<const io::Column<EnergyRow>> energy_summary_columns();
std::span<const io::Column<EnergySample>> energy_sample_columns();

EnergyStudy run_energy_study(const scenario::Scenario& scenario, const EnergyStudyOptions& options, std::ostream& log);

}  // namespace roifem::experiments
