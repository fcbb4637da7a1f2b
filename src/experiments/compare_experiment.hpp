// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// `roifem compare`: every integrator on one scenario, across a sweep of fixed steps and of
/// tolerances, against the exact modal solution (true errors). For explicit methods the sweep
/// brackets the stability limit predicted from the Butcher table, and a bisection finds the
/// largest stable step in practice.
/// Where there is no modal solution (a nonlinear model; a linear one under smooth ramps or sampled
/// tool paths) the reference is a tight run of a stated method (CompareOptions::reference, error-
/// controlled at reference_rtol), checked by a second method at the same tolerance, and compare
/// says by how much the two agree; on a nonlinear model the explicit methods' limits come from the
/// tangent's highest frequency along the reference run (its largest), and compare.csv gains the
/// Newton iterations. Writes DIR/compare.csv, DIR/stability.csv and, with tools,
/// DIR/tools.csv (their columns: compare_results.hpp's lists, which the Python module reads too),
/// rewritten as each run ends, and PNG plots.
#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

#include "experiments/compare_results.hpp"
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
  /// Without a modal solution: the reference method, error-controlled at reference_rtol (atol:
  /// reference_rtol x 1 mm), and the second method it is checked by at the same tolerances.
  std::string reference = "ida-bdf5", reference_check = "arkode-esdirk5";
  double reference_rtol = 1e-9;
};

CompareResults run_compare(const scenario::Scenario& scenario, const CompareOptions& options, std::ostream& log);

}  // namespace roifem::experiments
