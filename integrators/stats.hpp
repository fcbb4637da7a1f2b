// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// An integrator's counters, and the one table of them that every report reads: results.h5's
/// counters attribute, the logs, compare's and energy's CSV columns, the Python dict and the
/// restart points (as SUNDIALS' PrintAllStats is its integrators' one printer).
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace roifem::integrators {

/// Counters every integrator reports (zero where the method has no such thing).
struct Stats {
  long steps = 0, rhs_evals = 0, jac_evals = 0, lin_setups = 0, lin_solves = 0, failed_steps = 0;
  long lin_iterations = 0;        ///< iterations of an iterative linear solver (trapezoid-cg)
  long nonlinear_iterations = 0;  ///< Newton iterations on a nonlinear system
  long indefinite_steps = 0;      ///< steps whose Newton matrix was indefinite (solved by LU, not Cholesky)
  double factorization_s = 0;     ///< seconds in linear-solver setups: orderings, analyses, factorizations
  long system_changes = 0;        ///< changes of the system taken in place (cuts), without a restart
  Stats& operator+=(const Stats& o);
  /// The counters as numbers, in the table's order (a restart point's), and back
  /// (factorization_s is a time: not kept).
  std::vector<double> counters() const;
  static Stats from_counters(const std::vector<double>& numbers, std::size_t first = 0);
};

/// One counter: its name (as files, logs and Python write it), what it counts, and its member.
struct StatsField {
  std::string_view name;
  std::string_view meaning;
  long Stats::*member;
};
/// Every counter of Stats, once (factorization_s, a time, apart).
std::span<const StatsField> stats_fields();
/// The field of that name (Error naming the names for an unknown one).
const StatsField& stats_field(std::string_view name);
/// "steps=12 rhs_evals=30 ...": every counter that is not zero, in the table's order (steps always).
std::string stats_line(const Stats& stats);

}  // namespace roifem::integrators
