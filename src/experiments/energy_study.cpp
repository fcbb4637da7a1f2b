// SPDX-License-Identifier: GPL-3.0-or-later
#include "experiments/energy_study.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <ostream>

#include "common/atomic_file.hpp"
#include "common/errors.hpp"
#include "common/format.hpp"
#include "common/interrupt.hpp"
#include "common/number_text.hpp"
#include "common/timer.hpp"
#include "integrators/factory.hpp"
#include "integrators/integrator_table.hpp"
#include "io/plots.hpp"
#include "model/energy.hpp"
#include "model/internal_force.hpp"
#include "simulation/scenario_model.hpp"

namespace roifem::experiments {

namespace {

using io::Cell;
using io::Column;

/// A figure where the run reached an output; empty otherwise.
Cell error_figure(double value) { return std::isfinite(value) ? Cell(value) : Cell(); }

const std::array<Column<EnergyRow>, 14> summary{{
    {"integrator", "the method's name", [](const EnergyRow& r) -> Cell { return r.integrator; }},
    {"mode", "fixed (dt_or_tol: the step) or adaptive (dt_or_tol: rtol; atol = rtol x 1 mm)",
     [](const EnergyRow& r) -> Cell { return r.mode; }},
    {"dt_or_tol", "the fixed step in s, or rtol", [](const EnergyRow& r) -> Cell { return r.dt_or_tol; }},
    {"outputs", "outputs reached on the scenario's grid", [](const EnergyRow& r) -> Cell { return r.outputs; }},
    {"steps", "steps taken", [](const EnergyRow& r) -> Cell { return r.steps; }},
    {"newton_iterations", "Newton iterations on a nonlinear model (0 on a linear one)",
     [](const EnergyRow& r) -> Cell { return r.newton_iterations; }},
    {"jac_evals", "Jacobian (tangent) evaluations", [](const EnergyRow& r) -> Cell { return r.jac_evals; }},
    {"lin_setups", "linear-solver setups (factorizations)", [](const EnergyRow& r) -> Cell { return r.lin_setups; }},
    {"wall_s", "the run's wall time (s), its setup included", [](const EnergyRow& r) -> Cell { return r.wall_s; }},
    {"work_scale_J", "max |W| over the run: the loads' work, the scale of the errors (J)",
     [](const EnergyRow& r) -> Cell { return r.work_scale_J; }, "%.6e"},
    {"max_energy_error_rel", "max |E + D - W - E_0| / work_scale_J over the outputs reached",
     [](const EnergyRow& r) { return error_figure(r.max_error); }, "%.6e"},
    {"final_energy_error_rel", "|E + D - W - E_0| / work_scale_J at the last output reached",
     [](const EnergyRow& r) { return error_figure(r.final_error); }, "%.6e"},
    {"drift_after_ramps_rel",
     "max |balance(t) - balance(t_c)| / work_scale_J over t >= t_c, the loads constant from t_c: the method's own energy "
     "error, free of the output grid's quadrature (empty: the loads change to the end, or tools)",
     [](const EnergyRow& r) { return error_figure(r.drift_after_ramps); }, "%.6e"},
    {"status", "ok, or why the run stopped early", [](const EnergyRow& r) -> Cell { return r.status; }, "%.6g", true},
}};

const std::array<Column<EnergySample>, 7> samples{{
    {"integrator", "the method's name", [](const EnergySample& s) -> Cell { return s.integrator; }},
    {"t_s", "time (s)", [](const EnergySample& s) -> Cell { return s.t; }, "%.9g"},
    {"kinetic_J", "v^T M v / 2 (J)", [](const EnergySample& s) -> Cell { return s.kinetic; }, "%.12e"},
    {"strain_J", "the strain energy, W(u) on a nonlinear model (J)", [](const EnergySample& s) -> Cell { return s.strain; },
     "%.12e"},
    {"dissipated_J", "what damping took since t = 0 (J)", [](const EnergySample& s) -> Cell { return s.dissipated; }, "%.12e"},
    {"work_J", "the loads' and the tools' work since t = 0 (J)", [](const EnergySample& s) -> Cell { return s.work; }, "%.12e"},
    {"balance_J", "E + D - W - E_0: zero for the exact solution (J)", [](const EnergySample& s) -> Cell { return s.balance; },
     "%.6e"},
}};

/// The methods a study runs: those named, or every one that takes the model. A DAE form of the
/// tools (their forces from multipliers) is not one the ledger reads; named, it is refused.
std::vector<std::string> methods_of(const scenario::Scenario& sc, const EnergyStudyOptions& o,
                                    const model::SecondOrderSystem& sys) {
  const auto refusal = [&](const integrators::IntegratorInfo& info) -> std::string {
    if (info.needs_tools) return "holds the tools as constraints, whose work the energy ledger does not read: name another";
    if (info.needs_uncondensed && !sys.uncondensed) return "integrates an [roi] by static condensation only, and this has none";
    if (sys.is_nonlinear() && !info.nonlinear)
      return "does not take a nonlinear model (" + sys.internal_force->describe() +
             "); the methods that do are marked [nonlinear] in roifem run --help";
    if (info.needs_discrete_gradient && sys.internal_force && !sys.internal_force->has_discrete_gradient())
      return "needs the law's discrete gradient, which " + sys.internal_force->describe() +
             " does not form (the nodal-pressure element at finite strain)";
    return "";
  };
  std::vector<std::string> names;
  if (o.integrators.empty()) {
    for (const auto& info : integrators::integrator_table())
      if (refusal(info).empty() && (!info.needs_nonlinear || sys.is_nonlinear())) names.push_back(info.name);
    return names;
  }
  for (const auto& name : o.integrators) {
    const auto& info = integrators::integrator_info(name);  // InputError with "did you mean" on an unknown name
    if (const std::string why = refusal(info); !why.empty()) {
      std::string message = "energy: ";
      message.append(name).append(" ").append(why).append(" (").append(sc.file.string()).append(")");
      throw InputError(message);
    }
    names.push_back(name);
  }
  return names;
}

struct Run {
  EnergyRow row;
  std::vector<EnergySample> samples;
};

/// When the loads stop changing: the end of the last ramp (infinite with tools, whose paths the
/// study does not read).
double loads_constant_from(const model::SecondOrderSystem& sys, const model::ToolSet& tools) {
  if (!tools.empty()) return INFINITY;
  double t = 0;
  for (const auto& term : sys.load.terms()) t = std::max(t, term.ramp.duration);
  return t;
}

Run run_one(const integrators::IntegratorInfo& info, const model::SecondOrderSystem& sys, const model::ToolSet& tools, double dt,
            long outputs, const EnergyStudyOptions& o) {
  Run run;
  EnergyRow& row = run.row;
  row.integrator = info.name;
  const bool fixed = info.fixed_step && !info.is_explicit;
  row.mode = fixed ? "fixed" : "adaptive";
  row.dt_or_tol = fixed ? dt : o.rtol;
  const integrators::StepControl control{.dt = dt, .adaptive = !fixed, .rtol = o.rtol, .atol = o.rtol * 1e-3};
  const Stopwatch clock;
  const InterruptGuard interrupts;
  std::unique_ptr<integrators::Integrator> method;
  try {
    method = integrators::make_integrator(info, control);
    model::State s = model::State::at_rest(sys.size());
    method->set_time_limit(o.max_run_s);
    method->reset(sys, s);
    model::EnergyLedger ledger(sys, s, tools.empty() ? nullptr : &tools);
    for (long k = 1; k <= outputs; ++k) {
      method->advance_to(static_cast<double>(k) * dt, s);
      ledger.record(s);
      run.samples.push_back({.integrator = info.name,
                             .t = s.t,
                             .kinetic = ledger.kinetic(),
                             .strain = ledger.strain(),
                             .dissipated = ledger.dissipated(),
                             .work = ledger.external_work() + ledger.tool_work(),
                             .balance = ledger.balance_residual()});
      row.outputs = k;
      if (const int signal = InterruptGuard::signal_received())
        throw Interrupted(signal, "interrupted by signal " + std::to_string(signal) + " at t = " + number_text(s.t) + " s");
      if (clock.seconds() > o.max_run_s && k < outputs) {
        row.status = format("stopped at t = %s s: over --max-run-seconds %g", number_text(s.t).c_str(), o.max_run_s);
        break;
      }
    }
  } catch (const Interrupted&) {
    throw;
  } catch (const OverTime& stop) {
    row.status = format("stopped at t = %s s: over --max-run-seconds %g", number_text(stop.t).c_str(), o.max_run_s);
  } catch (const Error& e) {
    row.status = e.what();
  }
  row.wall_s = clock.seconds();
  if (method) {
    const integrators::Stats st = method->stats();
    row.steps = st.steps;
    row.newton_iterations = st.nonlinear_iterations;
    row.jac_evals = st.jac_evals;
    row.lin_setups = st.lin_setups;
  }
  for (const auto& sample : run.samples) row.work_scale_J = std::max(row.work_scale_J, std::abs(sample.work));
  if (!run.samples.empty() && row.work_scale_J > 0) {
    row.max_error = 0;
    for (const auto& sample : run.samples) row.max_error = std::max(row.max_error, std::abs(sample.balance) / row.work_scale_J);
    row.final_error = std::abs(run.samples.back().balance) / row.work_scale_J;
    const double t_c = loads_constant_from(sys, tools);
    const auto first = std::find_if(run.samples.begin(), run.samples.end(),
                                    [&](const EnergySample& sample) { return sample.t >= t_c - 1e-9 * dt; });
    if (first != run.samples.end() && first + 1 != run.samples.end()) {
      row.drift_after_ramps = 0;
      for (auto it = first; it != run.samples.end(); ++it)
        row.drift_after_ramps = std::max(row.drift_after_ramps, std::abs(it->balance - first->balance) / row.work_scale_J);
    }
  }
  return run;
}

void write_files(const EnergyStudyOptions& o, const EnergyStudy& study) {
  io::write_csv(o.out / "energy_summary.csv", energy_summary_columns(), study.rows);
  io::write_csv(o.out / "energy.csv", energy_sample_columns(), study.samples);
}

std::string figure_text(double value) { return std::isfinite(value) ? format("%.2e", value) : "-"; }

}  // namespace

std::span<const Column<EnergyRow>> energy_summary_columns() { return summary; }
std::span<const Column<EnergySample>> energy_sample_columns() { return samples; }

EnergyStudy run_energy_study(const scenario::Scenario& sc, const EnergyStudyOptions& o, std::ostream& log) {
  scenario::refuse_run_only_tables(sc, "roifem energy");
  if (!(o.rtol > 0) || !(o.rtol < 1)) throw InputError("energy: --rtol must lie in (0, 1), not " + number_text(o.rtol));
  if (!(o.max_run_s > 0)) throw InputError("energy: --max-run-seconds must be positive, not " + number_text(o.max_run_s));
  if (!(o.t_end >= 0) || !std::isfinite(o.t_end))
    throw InputError("energy: --t-end must be 0 or positive, not " + number_text(o.t_end));
  check_output_directory(o.out);
  const auto built = simulation::build_scenario_model(sc);
  const model::SecondOrderSystem& sys = built->system();
  const double t_end = o.t_end > 0 ? o.t_end : sc.dt * static_cast<double>(sc.steps);
  const long outputs = std::lround(t_end / sc.dt);
  if (outputs < 1) throw InputError("energy: --t-end must cover at least one output step of " + number_text(sc.dt) + " s");
  if (sys.load.terms().empty() && built->tools.empty())
    throw InputError("energy: " + sc.file.string() +
                     " has no [[load]] and no [[tool]]: from rest nothing moves, and the ledger has no scale");
  const std::vector<std::string> names = methods_of(sc, o, sys);
  log << format("energy: %s, %lld dofs%s, %ld outputs of %g s to t = %g s; %zu method%s, each stopped after %g s\n",
                sc.file.c_str(), static_cast<long long>(sys.size()),
                sys.is_nonlinear() ? (", " + sys.internal_force->describe()).c_str() : ", linear", outputs, sc.dt, t_end,
                names.size(), names.size() == 1 ? "" : "s", o.max_run_s)
      << std::flush;
  EnergyStudy study;
  for (const auto& name : names) {
    Run run = run_one(integrators::integrator_info(name), sys, built->tools, sc.dt, outputs, o);
    const EnergyRow& r = run.row;
    log << format("  %-24s %-8s %9.3g %7ld steps %7.2f Newton/step %8.2f s  max |E + D - W - E0| / W %s, after the ramps %s%s\n",
                  r.integrator.c_str(), r.mode.c_str(), r.dt_or_tol, r.steps,
                  r.steps > 0 ? static_cast<double>(r.newton_iterations) / static_cast<double>(r.steps) : 0.0, r.wall_s,
                  figure_text(r.max_error).c_str(), figure_text(r.drift_after_ramps).c_str(),
                  r.status == "ok" ? "" : ("  (" + r.status + ")").c_str())
        << std::flush;
    study.rows.push_back(std::move(run.row));
    study.samples.insert(study.samples.end(), run.samples.begin(), run.samples.end());
    write_files(o, study);  // a study stopped or killed keeps the runs so far
  }
  if (o.plots && io::run_plot_script("plot_energy.py", o.out, log))
    log << "plot: " << (o.out / "energy_error.png").string() << '\n';
  log << "results: " << (o.out / "energy_summary.csv").string() << ", " << (o.out / "energy.csv").string() << '\n';
  return study;
}

}  // namespace roifem::experiments
