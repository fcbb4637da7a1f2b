// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// `roifem compare`: every integrator on one scenario, across a sweep of fixed steps and of
/// tolerances, against the exact modal solution (true errors). For explicit methods the sweep
/// brackets the stability limit predicted from the Butcher table, and a bisection finds the
/// largest stable step in practice. Writes DIR/compare.csv
///   integrator,mode,dt_or_tol,steps,rhs_evals,jac_evals,lin_setups,lin_solves,wall_s,
///   err_max_mm,err_rms_mm,stable,energy_drift
/// (errors over the output grid and the system's nodes; energy_drift = |E - E_exact| / E_exact at
/// the end; a diverged run has stable = 0 and empty error fields), DIR/stability.csv and PNG plots;
/// with tools also DIR/tools.csv (the tools' force error and the DAE forms' constraint drifts).
#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

#include "integrators/integrator_table.hpp"
#include "scenario/scenario.hpp"

namespace roifem::experiments {

struct CompareOptions {
  std::filesystem::path out;
  std::vector<std::string> integrators;  ///< empty: all (the table's that apply, then extra_rows)
  /// Integrators beyond the table, by the same rules (roifem-mpi compare: PETSc's TS methods).
  std::vector<integrators::IntegratorInfo> extra_rows;
  double t_end = 0;      ///< s of simulated time (0: the scenario's dt * steps)
  int fixed_levels = 5;  ///< dt = T/2^0 .. T/2^(levels-1), T the scenario's dt
  std::vector<double> tolerances{1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8};
  long max_steps = 200000;  ///< fixed-step runs needing more are skipped
  double max_run_s = 60;    ///< a run taking longer is stopped: its row keeps the reason, no figures (tighter ones not run)
  bool plots = true;
};

/// With tools: the tools' force against the exact one, and the DAE forms' constraint drifts.
struct ToolFigures {
  double force_error_rel = 0;
  double position_drift_mm = 0, velocity_drift_mm_s = 0;
};

struct CompareRow {
  std::string integrator, mode;
  double dt_or_tol = 0;
  long steps = 0, rhs_evals = 0, jac_evals = 0, lin_setups = 0, lin_solves = 0;
  double wall_s = 0, err_max_mm = 0, err_rms_mm = 0, energy_drift = 0;
  ToolFigures tools;  ///< with tools (tools.csv)
  bool stable = true;
  /// "ok", "diverged: <the solver's message>" or "stopped at t = ... s after ... s (--max-run-seconds)":
  /// a run that did not finish keeps its row, with this reason, and no error figures.
  std::string status = "ok";
  bool finished() const { return status == "ok"; }
};

struct StabilityRow {
  std::string integrator;
  double predicted_dt = 0, measured_dt = 0;
};

struct CompareResults {
  std::vector<CompareRow> rows;
  std::vector<StabilityRow> stability;
  double omega_max = 0;  ///< rad/s, of the integrated system
};

CompareResults run_compare(const scenario::Scenario& scenario, const CompareOptions& options, std::ostream& log);

}  // namespace roifem::experiments
