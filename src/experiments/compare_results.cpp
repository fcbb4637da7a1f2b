// SPDX-License-Identifier: GPL-3.0-or-later
#include "experiments/compare_results.hpp"

#include <array>

namespace roifem::experiments {

namespace {

using io::Cell;
using io::Column;

/// A figure only where the run has them (finished, stably); empty otherwise.
Cell figure(const CompareRow& r, double value) { return r.has_figures() ? Cell(value) : Cell(); }

const std::array<Column<CompareRow>, 15> compare{{
    {"integrator", "the method's name", [](const CompareRow& r) -> Cell { return r.integrator; }},
    {"mode", "fixed (dt_or_tol: the step) or adaptive (dt_or_tol: rtol)", [](const CompareRow& r) -> Cell { return r.mode; }},
    {"dt_or_tol", "the fixed step in s, or the relative tolerance rtol (atol = rtol x the exact peak, m)",
     [](const CompareRow& r) -> Cell { return r.dt_or_tol; }},
    {"theoretical_order", "the method's order of accuracy",
     [](const CompareRow& r) -> Cell { return static_cast<long>(r.theoretical_order); }},
    {"steps", "steps taken", [](const CompareRow& r) -> Cell { return r.stats.steps; }},
    {"rhs_evals", "right-hand side (or residual) evaluations", [](const CompareRow& r) -> Cell { return r.stats.rhs_evals; }},
    {"jac_evals", "Jacobian evaluations", [](const CompareRow& r) -> Cell { return r.stats.jac_evals; }},
    {"lin_setups", "linear-solver setups (factorizations)", [](const CompareRow& r) -> Cell { return r.stats.lin_setups; }},
    {"lin_solves", "linear solves", [](const CompareRow& r) -> Cell { return r.stats.lin_solves; }},
    {"wall_s", "the run's wall time (s), its setup included", [](const CompareRow& r) -> Cell { return r.wall_s; }},
    {"err_max_mm", "the largest nodal error against the exact solution over the output grid (mm)",
     [](const CompareRow& r) { return figure(r, r.err_max_mm); }, "%.6e"},
    {"err_rms_mm", "the RMS nodal error over the output grid (mm)", [](const CompareRow& r) { return figure(r, r.err_rms_mm); },
     "%.6e"},
    {"stable", "1 stable, 0 diverged; empty for a run stopped before its end",
     [](const CompareRow& r) -> Cell { return r.status.starts_with("stopped") ? Cell() : Cell(r.stable); }},
    {"energy_drift_rel", "|E(t_end) - E_exact(t_end)| / E_exact(t_end)",
     [](const CompareRow& r) { return figure(r, r.energy_drift); }, "%.6e"},
    {"status", "ok, or why the run has no figures", [](const CompareRow& r) -> Cell { return r.status; }, "%.6g", true},
}};

/// The same with the Newton iterations after the linear solves: a nonlinear system's compare.csv.
const std::array<Column<CompareRow>, 16> compare_nonlinear{{
    compare[0],
    compare[1],
    compare[2],
    compare[3],
    compare[4],
    compare[5],
    compare[6],
    compare[7],
    compare[8],
    {"newton_iterations", "Newton iterations in all (a nonlinear system)",
     [](const CompareRow& r) -> Cell { return r.stats.nonlinear_iterations; }},
    compare[9],
    compare[10],
    compare[11],
    compare[12],
    compare[13],
    compare[14],
}};

const std::array<Column<StabilityRow>, 4> stability{{
    {"integrator", "the explicit method", [](const StabilityRow& s) -> Cell { return s.integrator; }},
    {"omega_max_rad_s", "the integrated system's highest frequency (rad/s)",
     [](const StabilityRow& s) -> Cell { return s.omega_max; }},
    {"predicted_dt_s", "the largest stable step by the Butcher table's stability function (s)",
     [](const StabilityRow& s) -> Cell { return s.predicted_dt; }, "%.6e"},
    {"largest_stable_dt_s", "the largest step found stable in practice by bisection (s)",
     [](const StabilityRow& s) -> Cell { return s.measured_dt; }, "%.6e"},
}};

// The tools' force error: max |F - F_exact| / max |F_exact| over the outputs (F: the multipliers'
// force for the DAE forms, the residual of the state otherwise); the drifts max |H u - G| and
// |H v - G'| of the DAE forms (0 by construction where the tools are eliminated).
const std::array<Column<CompareRow>, 6> tools{{
    compare[0],
    compare[1],
    compare[2],
    {"tool_force_err_rel", "max |F - F_exact| / max |F_exact| over the outputs",
     [](const CompareRow& r) -> Cell { return r.tools.force_error_rel; }, "%.6e"},
    {"position_drift_mm", "max |H u - G| of a DAE form (mm)",
     [](const CompareRow& r) -> Cell { return r.tools.position_drift_mm; }, "%.6e"},
    {"velocity_drift_mm_s", "max |H v - G'| of a DAE form (mm/s)",
     [](const CompareRow& r) -> Cell { return r.tools.velocity_drift_mm_s; }, "%.6e"},
}};

}  // namespace

std::span<const Column<CompareRow>> compare_columns(bool nonlinear) {
  return nonlinear ? std::span<const Column<CompareRow>>(compare_nonlinear) : std::span<const Column<CompareRow>>(compare);
}
std::span<const Column<StabilityRow>> stability_columns() { return stability; }
std::span<const Column<CompareRow>> tool_columns() { return tools; }

}  // namespace roifem::experiments
