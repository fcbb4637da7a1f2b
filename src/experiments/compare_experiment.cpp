// SPDX-License-Identifier: GPL-3.0-or-later
#include "experiments/compare_experiment.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <ostream>

#include "common/atomic_file.hpp"
#include "common/errors.hpp"
#include "common/format.hpp"
#include "common/interrupt.hpp"
#include "common/number_text.hpp"
#include "common/timer.hpp"
#include "experiments/roi_error.hpp"
#include "integrators/factory.hpp"
#include "integrators/stability.hpp"
#include "io/plots.hpp"
#include "model/internal_force.hpp"
#include "model/modal_reference.hpp"
#include "model/spectrum.hpp"
#include "simulation/progress.hpp"
#include "simulation/scenario_model.hpp"

namespace roifem::experiments {

namespace {

/// A method that integrates by the law's discrete gradient, on a force that forms none.
bool lacks_discrete_gradient(const integrators::IntegratorInfo& info, const model::SecondOrderSystem& system) {
  return info.needs_discrete_gradient && system.internal_force && !system.internal_force->has_discrete_gradient();
}

/// The exact solution (or a tight run's) on the output grid, and what a run is measured against.
struct Reference {
  std::string description;  ///< "the exact modal solution", or the tight run's method and tolerances
  std::vector<Vector> u;    ///< at t_k = k * interval, k = 1..K
  double final_energy = 0;
  double interval = 0;
  RoiNodeDofs nodes;                      ///< the integrated system's nodes, the same numbering in both
  const model::ToolSet* tools = nullptr;  ///< the model's tools (empty: none)
  std::vector<Vector> tool_forces;        ///< their exact forces at t_k
  double tool_force_peak = 0;             ///< max over k and components, N
};

struct RunError {
  double max_mm = 0, rms_mm = 0, energy_drift = 0;
  ToolFigures tools;
};

/// A run stopped for taking longer than --max-run-seconds (GSL's dense implicit steppers at tight
/// tolerances take hours on a few thousand dofs).
struct OverBudget {
  double t = 0;
};

/// Runs one integrator over the output grid; throws SolverError on divergence, OverBudget past
/// `budget_s` of wall time (heard inside a step: Integrator::set_time_limit).
RunError measure(integrators::Integrator& integrator, const model::SecondOrderSystem& system, const Reference& ref,
                 double budget_s) {
  const Stopwatch clock;
  model::State state = model::State::at_rest(system.size());
  integrator.set_time_limit(budget_s);
  integrator.reset(system, state);
  RunError e;
  double mean_square = 0, force_error = 0;
  for (std::size_t k = 0; k < ref.u.size(); ++k) {
    try {
      integrator.advance_to(static_cast<double>(k + 1) * ref.interval, state);
    } catch (const OverTime& stop) {
      throw OverBudget{stop.t};
    }
    if (clock.seconds() > budget_s) throw OverBudget{state.t};
    const RoiError at_k = roi_error(ref.nodes, state.u, ref.u[k]);
    e.max_mm = std::max(e.max_mm, at_k.max / mm);
    mean_square += at_k.rms * at_k.rms;
    if (ref.tool_forces.empty()) continue;
    // The tools' force as the method has it: its multipliers (DAE forms), or the residual of its state.
    const auto held = integrator.constraints();
    const Vector F = held ? held->forces : ref.tools->forces(state.u, state.t);
    force_error = std::max(force_error, (F - ref.tool_forces[k]).lpNorm<Eigen::Infinity>());
    if (held) {
      e.tools.position_drift_mm = std::max(e.tools.position_drift_mm, held->position_drift / mm);
      e.tools.velocity_drift_mm_s = std::max(e.tools.velocity_drift_mm_s, held->velocity_drift / mm);
    }
  }
  if (!ref.tool_forces.empty()) e.tools.force_error_rel = force_error / ref.tool_force_peak;
  e.rms_mm = std::sqrt(mean_square / static_cast<double>(std::max<std::size_t>(ref.u.size(), 1))) / mm;
  const double energy = kinetic_energy(system, state) + strain_energy(system, state);
  e.energy_drift = std::abs(energy - ref.final_energy) / ref.final_energy;
  return e;
}

/// The row of `name`: one of the options' extra rows, else the table's (InputError listing the table's names).
const integrators::IntegratorInfo& row_of(const CompareOptions& o, const std::string& name) {
  for (const auto& row : o.extra_rows)
    if (row.name == name) return row;
  return integrators::integrator_info(name);
}

/// Largest dt on the output grid's divisors (interval / m) not above `target`.
double grid_step(double interval, double target) { return interval / std::ceil(interval / target - 1e-9); }

/// Stable in practice: finite and bounded (10x the exact peak) over the window.
bool runs_stably(const integrators::IntegratorInfo& info, double dt, const model::SecondOrderSystem& system, double t_end,
                 double bound) {
  try {
    auto integrator = integrators::make_integrator(info, {.dt = dt, .watch_stability = false});  // past the limit on purpose
    model::State state = model::State::at_rest(system.size());
    integrator->reset(system, state);
    const long steps = std::min<long>(4000, std::lround(t_end / dt));
    for (long k = 1; k <= steps; k += 50) {
      integrator->advance_to(static_cast<double>(std::min(k + 49, steps)) * dt, state);
      if (state.u.lpNorm<Eigen::Infinity>() > bound) return false;
    }
    return true;
  } catch (const SolverError&) {
    return false;
  } catch (const ModelError&) {  // a nonlinear model's element inverted by an unstable step
    return false;
  }
}

/// What every run of one compare shares: the integrated system, its exact reference, the options.
struct Sweep {
  const scenario::Scenario& sc;
  const CompareOptions& o;
  const model::SecondOrderSystem& system;
  Reference ref;
  double t_end = 0, peak = 0;
  CompareResults results;
  std::ostream& log;
  std::size_t integrators = 0;  ///< in the sweep
  Stopwatch clock;              ///< since the sweep began
};

/// The exact modal solution where there is one (a linear model under linear ramps), else none (the
/// reason on `why_not`).
std::optional<model::ModalReference> modal_reference_of(const model::SecondOrderSystem& system, std::string& why_not) {
  if (system.is_nonlinear()) {
    why_not = "a nonlinear model (" + system.internal_force->describe() + ") has no modal solution";
    return std::nullopt;
  }
  try {
    return model::ModalReference(system, model::State::at_rest(system.size()));
  } catch (const InputError& e) {  // a smooth ramp, a sampled tool path
    why_not = e.what();
    return std::nullopt;
  }
}

/// The reference's displacements and tool forces from its states on the output grid.
Reference reference_of(std::string description, const std::vector<Vector>& u, const model::State& end,
                       const model::SecondOrderSystem& system, const simulation::ScenarioModel& built, double interval,
                       double& peak) {
  Reference ref;
  ref.description = std::move(description);
  ref.interval = interval;
  ref.nodes = same_numbering(built.node_positions());
  ref.u = u;
  peak = 0;
  for (const Vector& x : ref.u) peak = std::max(peak, x.lpNorm<Eigen::Infinity>());
  if (!built.tools.empty()) {
    ref.tools = &built.tools;
    for (std::size_t k = 0; k < ref.u.size(); ++k) {
      ref.tool_forces.push_back(built.tools.forces(ref.u[k], static_cast<double>(k + 1) * interval));
      ref.tool_force_peak = std::max(ref.tool_force_peak, ref.tool_forces.back().lpNorm<Eigen::Infinity>());
    }
  }
  ref.final_energy = kinetic_energy(system, end) + strain_energy(system, end);
  return ref;
}

Reference exact_reference(const model::SecondOrderSystem& system, const model::ModalReference& modal,
                          const simulation::ScenarioModel& built, double interval, long outputs, double t_end, double& peak) {
  std::vector<Vector> u;
  for (long k = 1; k <= outputs; ++k) u.push_back(modal.displacement(static_cast<double>(k) * interval));
  const model::State exact_end{t_end, u.back(), modal.velocity(t_end)};
  return reference_of("the exact modal solution", u, exact_end, system, built, interval, peak);
}

/// `name` error-controlled at rtol (atol rtol x 1 mm) over the output grid: its states there, and the last.
std::vector<Vector> tight_run(const std::string& name, const model::SecondOrderSystem& system, double rtol, double interval,
                              long outputs, model::State& end, std::ostream& log) {
  const integrators::IntegratorInfo& info = integrators::integrator_info(name);
  if (!info.adaptive)
    throw InputError("compare: the reference method " + name + " has no error control: name an adaptive one (--reference)");
  auto integrator = integrators::make_integrator(info, {.dt = interval, .adaptive = true, .rtol = rtol, .atol = rtol * 1e-3});
  end = model::State::at_rest(system.size());
  integrator->reset(system, end);
  std::vector<Vector> u;
  simulation::ProgressReporter progress(format("reference %s at rtol %g", name.c_str(), rtol), outputs, 2.0, "outputs", &log);
  for (long k = 1; k <= outputs; ++k) {
    integrator->advance_to(static_cast<double>(k) * interval, end);
    u.push_back(end.u);
    progress.update(k);
  }
  return u;
}

/// Without a modal solution: a tight run of the reference method, checked by a second one; their
/// largest difference over the output grid and the ROI nodes is the reference's own error bound.
Reference tight_reference(const CompareOptions& o, const model::SecondOrderSystem& system, const simulation::ScenarioModel& built,
                          double interval, long outputs, double& peak, double& agreement_mm, std::ostream& log) {
  const Stopwatch clock;
  model::State end;
  const std::vector<Vector> u = tight_run(o.reference, system, o.reference_rtol, interval, outputs, end, log);
  const double reference_s = clock.seconds();
  Reference ref = reference_of(format("%s at rtol %g, atol %g mm", o.reference.c_str(), o.reference_rtol, o.reference_rtol), u,
                               end, system, built, interval, peak);
  model::State check_end;
  const std::vector<Vector> check = tight_run(o.reference_check, system, o.reference_rtol, interval, outputs, check_end, log);
  agreement_mm = 0;
  for (std::size_t k = 0; k < u.size(); ++k) agreement_mm = std::max(agreement_mm, roi_error(ref.nodes, check[k], u[k]).max / mm);
  log << format(
      "  reference: %s (%.1f s); checked by %s at the same tolerances (%.1f s in all): they differ by at most %.3e "
      "mm, %.1e of the peak %.4g mm: errors below that are the reference's\n",
      ref.description.c_str(), reference_s, o.reference_check.c_str(), clock.seconds(), agreement_mm, agreement_mm / (peak / mm),
      peak / mm);
  return ref;
}

/// The highest frequency of the tangent over the reference's states (every tenth of the grid): on
/// a nonlinear model what limits an explicit method's step where the run is stiffest.
double highest_frequency_along(const model::SecondOrderSystem& system, const Reference& ref) {
  double highest = model::highest_frequency(system);  // the tangent at rest
  SparseMatrix K_t = system.K;
  Vector f(system.size());
  const std::size_t every = std::max<std::size_t>(1, ref.u.size() / 10);
  for (std::size_t k = every - 1; k < ref.u.size(); k += every) {
    system.internal_force->force_and_tangent(static_cast<double>(k + 1) * ref.interval, ref.u[k], f, K_t);
    highest = std::max(highest, model::highest_frequency(system, K_t));
  }
  return highest;
}

void write_compare_files(const CompareOptions& o, const CompareResults& results);

/// After each run: the files hold every run so far (a compare stopped or killed keeps them).
void after_run(Sweep& w) { write_compare_files(w.o, w.results); }

/// After each integrator's sweep: the time so far, and what the rest may take at that pace.
void report_pace(const Sweep& w, const std::string& name, std::size_t done, double integrator_s) {
  const double elapsed = w.clock.seconds();
  const std::size_t left = w.integrators - done;
  w.log << format("  (%s: %.1f s; %.0f s since the start%s)\n", name.c_str(), integrator_s, elapsed,
                  left == 0 ? ""
                            : format("; %zu integrator%s left, about %.0f s more at the pace so far", left, left == 1 ? "" : "s",
                                     elapsed / static_cast<double>(done) * static_cast<double>(left))
                                  .c_str())
        << std::flush;
}

/// Runs one integrator against the reference and keeps its row; false when the run went over the
/// time budget (and is left out of the table).
bool record_run(Sweep& w, const std::string& name, const std::string& mode, double dt_or_tol,
                std::unique_ptr<integrators::Integrator> integrator) {
  CompareRow row{.integrator = name, .mode = mode, .dt_or_tol = dt_or_tol, .theoretical_order = row_of(w.o, name).order};
  const bool nonlinear = w.system.is_nonlinear();
  Stopwatch run_clock;
  try {
    const RunError e = measure(*integrator, w.system, w.ref, w.o.max_run_s);
    row.err_max_mm = e.max_mm;
    row.err_rms_mm = e.rms_mm;
    row.energy_drift = e.energy_drift;
    row.tools = e.tools;
    // Growing without bound but still finite at the end of the window: unstable all the same.
    if (e.max_mm > 10 * w.peak / mm) {
      row.stable = false;
      row.status = "diverged: the error grew past 10x the exact peak displacement";
    }
  } catch (const SolverError& err) {
    row.stable = false;
    row.status = std::string("diverged: ") + err.what();
    w.log << "    " << err.what() << '\n';
  } catch (const ModelError& err) {  // a nonlinear model's element inverted: the run could not go on
    row.stable = false;
    row.status = std::string("stopped: ") + err.what();
    w.log << "    " << err.what() << '\n';
  } catch (const OverBudget& stop) {
    row.stable = false;
    row.wall_s = run_clock.seconds();
    row.status = format("stopped at t = %.3g s after %.1f s (over --max-run-seconds %g)", stop.t, row.wall_s, w.o.max_run_s);
    w.log << format("  %-20s %-8s %9.3g  %s; no error figures\n", name.c_str(), mode.c_str(), dt_or_tol, row.status.c_str());
    w.results.rows.push_back(row);
    after_run(w);
    return false;
  }
  row.wall_s = run_clock.seconds();
  const auto st = integrator->stats();
  row.stats = st;
  const std::string newton =
      nonlinear && st.nonlinear_iterations > 0
          ? format("  %.2f Newton/step, %ld Jacobians, %ld setups",
                   static_cast<double>(st.nonlinear_iterations) / static_cast<double>(std::max(1L, st.steps)), st.jac_evals,
                   st.lin_setups)
          : "";
  const std::string tool_figures =
      !w.ref.tool_forces.empty() && row.stable
          ? format("; tool force error %.3g mN (%.1e of the exact peak, %.4g mN), drift %.1e mm",
                   row.tools.force_error_rel * w.ref.tool_force_peak * 1e3, row.tools.force_error_rel,
                   w.ref.tool_force_peak * 1e3, row.tools.position_drift_mm)
          : "";
  w.log << format("  %-20s %-8s %9.3g  %8ld steps  %9.3f s  max error %s mm%s%s\n", name.c_str(), mode.c_str(), dt_or_tol,
                  row.stats.steps, row.wall_s, row.stable ? format("%.3e", row.err_max_mm).c_str() : "(diverged)", newton.c_str(),
                  tool_figures.c_str())
        << std::flush;  // a sweep runs for minutes: show each run as it ends
  w.results.rows.push_back(row);
  after_run(w);
  return true;
}

/// The order observed between the two smallest fixed steps that ran, beside the method's own, with
/// a word when they differ by more than a quarter.
void report_observed_order(Sweep& w, const integrators::IntegratorInfo& info) {
  std::vector<const CompareRow*> runs;
  for (const auto& r : w.results.rows)
    if (r.integrator == info.name && r.mode == "fixed" && r.finished() && r.stable && r.err_max_mm > 0) runs.push_back(&r);
  if (runs.size() < 2) return;
  std::sort(runs.begin(), runs.end(), [](const auto* a, const auto* b) { return a->dt_or_tol < b->dt_or_tol; });
  const CompareRow &fine = *runs[0], &coarse = *runs[1];
  const double order = std::log(coarse.err_max_mm / fine.err_max_mm) / std::log(coarse.dt_or_tol / fine.dt_or_tol);
  std::string verdict = "as theory says";
  if (order < info.order - 0.25)
    verdict =
        "below theory: the errors are not yet in the asymptotic range at these steps, or the load's kink (the end of "
        "its ramp) or round-off limits them";
  else if (order > info.order + 0.25)
    verdict = "above theory: the steps are not in the asymptotic range (the error's constant changes)";
  w.log << format("  %-20s observed order %.2f between dt = %.3g and %.3g s (theory %d): %s\n", info.name.c_str(), order,
                  fine.dt_or_tol, coarse.dt_or_tol, info.order, verdict.c_str());
}

/// Fixed steps: around the stability limit for an explicit method, else dt, dt/2, ...
void sweep_fixed_steps(Sweep& w, const integrators::IntegratorInfo& info, double limit) {
  std::vector<double> dts;
  if (std::isfinite(limit)) {
    for (double f : {1.05, 0.9, 0.45, 0.225}) dts.push_back(grid_step(w.sc.dt, f * limit));
    if (dts[0] == dts[1]) dts.erase(dts.begin());
  } else {
    for (int j = 0; j < w.o.fixed_levels; ++j) dts.push_back(w.sc.dt / std::pow(2.0, j));
  }
  for (double dt : dts) {
    if (w.t_end / dt > static_cast<double>(w.o.max_steps)) {
      w.log << format("  %-20s fixed    %9.3g  skipped: %.0f steps > --max-steps\n", info.name.c_str(), dt, w.t_end / dt);
      continue;
    }
    if (!record_run(w, info.name, "fixed", dt, integrators::make_integrator(info, {.dt = dt, .watch_stability = false})))
      break;  // smaller dt: longer still
  }
  report_observed_order(w, info);
}

void sweep_tolerances(Sweep& w, const integrators::IntegratorInfo& info, double limit) {
  for (double tol : w.o.tolerances) {
    const integrators::StepControl control{.dt = std::min(w.sc.dt, std::isfinite(limit) ? 0.5 * limit : w.sc.dt),
                                           .adaptive = true,
                                           .rtol = tol,
                                           .atol = tol * w.peak};
    if (!record_run(w, info.name, "adaptive", tol, integrators::make_integrator(info, control))) break;  // tighter: longer still
  }
}

/// Bisection between a stable and an unstable step, around the predicted limit.
void search_stability_limit(Sweep& w, const integrators::IntegratorInfo& info, double limit) {
  double lo = 0.25 * limit, hi = 2.0 * limit;
  if (runs_stably(info, hi, w.system, w.t_end, 10 * w.peak)) lo = hi;
  for (int k = 0; k < 10 && lo < hi; ++k) {
    const double mid = 0.5 * (lo + hi);
    (runs_stably(info, mid, w.system, w.t_end, 10 * w.peak) ? lo : hi) = mid;
  }
  w.results.stability.push_back(
      {.integrator = info.name, .omega_max = w.results.omega_max, .predicted_dt = limit, .measured_dt = lo});
  w.log << format("  %-20s stability limit: predicted %.4e s, largest stable found %.4e s (ratio %.3f)\n", info.name.c_str(),
                  limit, lo, lo / limit);
}

void write_compare_files(const CompareOptions& o, const CompareResults& results) {
  io::write_csv(o.out / "compare.csv", compare_columns(results.nonlinear), results.rows);
  io::write_csv(o.out / "stability.csv", stability_columns(), results.stability);
}

/// tools.csv, for a model with tools: per run with figures, the tools' force error and the drifts.
void write_tool_figures(const CompareOptions& o, const CompareResults& results) {
  io::write_csv(o.out / "tools.csv", tool_columns(), results.rows, [](const CompareRow& r) { return r.has_figures(); });
}

/// The cheapest run within 0.1 mm, and the cost per step relative to the trapezoidal rule.
void print_summary(const CompareResults& results, double dt, std::ostream& log) {
  const CompareRow* cheapest = nullptr;
  for (const auto& r : results.rows)
    if (r.stable && r.err_max_mm <= 0.1 && (!cheapest || r.wall_s < cheapest->wall_s)) cheapest = &r;
  if (cheapest)
    log << format("\ncheapest run within 0.1 mm max error: %s (%s %g): %.4f s, %ld steps, max error %.4f mm\n",
                  cheapest->integrator.c_str(), cheapest->mode.c_str(), cheapest->dt_or_tol, cheapest->wall_s,
                  cheapest->stats.steps, cheapest->err_max_mm);
  const CompareRow* trapezoid = nullptr;
  for (const auto& r : results.rows)
    if (r.integrator == "trapezoid" && r.mode == "fixed" && std::abs(r.dt_or_tol - dt) < 1e-12 * dt && r.stats.steps > 0)
      trapezoid = &r;
  if (!trapezoid) return;
  const double trapezoid_step = trapezoid->wall_s / static_cast<double>(trapezoid->stats.steps);
  log << "cost relative to the trapezoidal rule at dt = " << dt
      << " s: per step (wall time per step, the run's setup included) and in all (the run's wall time), for fixed steps at "
         "dt and adaptive ones at rtol 1e-6, from the same compare run:\n";
  log << format("  %-20s %-8s %10s %12s %8s\n", "integrator", "mode", "per step", "in all", "steps");
  for (const auto& r : results.rows)
    if (r.stable && r.stats.steps > 0 &&
        ((r.mode == "fixed" && std::abs(r.dt_or_tol - dt) < 1e-12 * dt) || (r.mode == "adaptive" && r.dt_or_tol == 1e-6)))
      log << format("  %-20s %-8s %9.2fx %11.3gx %8ld\n", r.integrator.c_str(), r.mode.c_str(),
                    r.wall_s / static_cast<double>(r.stats.steps) / trapezoid_step, r.wall_s / trapezoid->wall_s, r.stats.steps);
}

}  // namespace

CompareResults run_compare(const scenario::Scenario& sc, const CompareOptions& o, std::ostream& log) {
  scenario::refuse_run_only_tables(sc, "roifem compare");
  check_output_directory(o.out);
  const auto built = simulation::build_scenario_model(sc);
  const model::SecondOrderSystem& system = built->system();
  const double t_end =
      o.t_end > 0 ? std::min(o.t_end, sc.dt * static_cast<double>(sc.steps)) : sc.dt * static_cast<double>(sc.steps);
  const long outputs = std::lround(t_end / sc.dt);
  if (outputs < 1) throw InputError("compare: --t-end must cover at least one output step of " + number_text(sc.dt) + " s");
  std::vector<std::string> names = o.integrators;
  auto applies = [&](const integrators::IntegratorInfo& info) {
    return (!info.needs_tools || system.constrained) && (!info.needs_uncondensed || system.uncondensed) &&
           (!info.needs_nonlinear || system.is_nonlinear()) && (info.nonlinear || !system.is_nonlinear()) &&
           !lacks_discrete_gradient(info, system);
  };
  if (names.empty())  // every integrator that applies: the tools' DAE forms where there are tools, ...
    for (const auto& info : integrators::integrator_table())
      if (applies(info)) names.push_back(info.name);
  if (o.integrators.empty())
    for (const auto& info : o.extra_rows) names.push_back(info.name);
  for (const auto& name : names) {  // unknown names, and a DAE form that does not apply, fail before any work
    const integrators::IntegratorInfo& info = row_of(o, name);
    if (info.needs_tools && !system.constrained)
      throw InputError("compare: " + name + " integrates a model with tools ([[tool]]) as a DAE, and " + sc.file.string() +
                       (built->condensation
                            ? " reduces it by a basis learnt from its loads (POD): the DAE forms need another reduction"
                            : " has none"));
    if (info.needs_uncondensed && !system.uncondensed)
      throw InputError("compare: " + name + " integrates an ROI model with its static part uncondensed, and " + sc.file.string() +
                       (built->condensation ? " reduces it otherwise than by static condensation" : " has no [roi]"));
    if (!info.nonlinear && system.is_nonlinear())
      throw InputError("compare: " + name + " does not take a nonlinear model (" + system.internal_force->describe() + ") and " +
                       sc.file.string() + " has one: the methods that do are marked 'nonlinear' in `roifem run --help`");
    if (lacks_discrete_gradient(info, system))
      throw InputError("compare: " + name + " needs the law's discrete gradient, which " + system.internal_force->describe() +
                       " in " + sc.file.string() + " does not form (the nodal-pressure element at finite strain)");
  }
  for (const auto& name : {o.reference, o.reference_check}) integrators::integrator_info(name);  // named before any work

  const InterruptGuard interrupts;
  const Stopwatch clock;
  std::string no_modal;
  const std::optional<model::ModalReference> modal = modal_reference_of(system, no_modal);
  Sweep w{.sc = sc,
          .o = o,
          .system = system,
          .ref = {},
          .t_end = t_end,
          .peak = 0,
          .results = {},
          .log = log,
          .integrators = names.size()};
  log << format("compare: %s, %lld dofs, t_end = %g s on an output grid of %g s\n", sc.file.c_str(),
                static_cast<long long>(system.size()), t_end, sc.dt);
  w.results.nonlinear = system.is_nonlinear();
  // What the explicit methods' limits are predicted for: the modes, or (no modal solution) the
  // highest frequency with the damping's real eigenvalue -alpha (w = 0).
  Vector frequencies;
  double alpha = 0;
  if (modal) {
    w.ref = exact_reference(system, *modal, *built, sc.dt, outputs, t_end, w.peak);
    w.results.omega_max = model::highest_frequency(system);  // Lanczos: the same figure at any size
    frequencies = modal->frequencies();
    alpha = modal->alpha();
    log << format("  exact modal reference in %.1f s; lowest w = %.3f rad/s, highest w = %.1f rad/s, alpha = %g 1/s\n",
                  clock.seconds(), frequencies[0], w.results.omega_max, alpha);
  } else {
    log << "  no exact solution: " << no_modal << "; the reference is a tight run\n";
    w.ref = tight_reference(o, system, *built, sc.dt, outputs, w.peak, w.results.reference_agreement_mm, log);
    w.results.omega_max = system.is_nonlinear() ? highest_frequency_along(system, w.ref) : model::highest_frequency(system);
    alpha = model::mass_proportional_damping(system);
    if (!std::isfinite(alpha)) alpha = 0;
    frequencies = Vector{{0.0, w.results.omega_max}};
    log << format("  highest w = %.1f rad/s%s, alpha = %g 1/s\n", w.results.omega_max,
                  system.is_nonlinear() ? " (the tangent's, the largest along the reference run)" : "", alpha);
  }

  const std::size_t runs = names.size() * (static_cast<std::size_t>(o.fixed_levels) + o.tolerances.size());
  log << format(
      "  %zu integrators, up to %zu runs, each stopped after --max-run-seconds %g s (at most %.0f min in all); "
      "compare.csv grows as each run ends\n",
      names.size(), runs, o.max_run_s, static_cast<double>(runs) * o.max_run_s / 60);
  // Ctrl-C (SIGINT / SIGTERM) stops the sweep inside a run: the runs that ended are kept, the
  // tables written and the plots drawn, then the command exits as interrupted.
  std::optional<Interrupted> interrupted;
  try {
    for (std::size_t i = 0; i < names.size(); ++i) {
      const Stopwatch integrator_clock;
      const integrators::IntegratorInfo& info = row_of(o, names[i]);
      const double limit = integrators::predicted_stability_limit(info, frequencies, alpha);
      if (info.fixed_step) sweep_fixed_steps(w, info, limit);
      if (info.adaptive) sweep_tolerances(w, info, limit);
      if (std::isfinite(limit)) search_stability_limit(w, info, limit);
      report_pace(w, info.name, i + 1, integrator_clock.seconds());
      if (const int signal = InterruptGuard::signal_received())
        throw Interrupted(signal, "interrupted by signal " + std::to_string(signal) + " after " + info.name);
    }
  } catch (const Interrupted& e) {
    interrupted = e;
    log << "\nstopped: " << e.what() << "; the " << w.results.rows.size()
        << " runs that ended are kept, their tables written and plotted\n";
  }

  write_compare_files(o, w.results);
  if (!built->tools.empty()) write_tool_figures(o, w.results);
  print_summary(w.results, sc.dt, log);
  if (o.plots && io::run_plot_script("plot_compare.py", o.out, log, {"--reference", w.ref.description}))
    log << "plots: " << (o.out / "work_precision.png").string() << ", " << (o.out / "error_vs_dt.png").string() << '\n';
  log << "results: " << (o.out / "compare.csv").string() << ", " << (o.out / "stability.csv").string()
      << (built->tools.empty() ? "" : ", " + (o.out / "tools.csv").string()) << '\n';
  if (interrupted) throw *interrupted;
  return w.results;
}

}  // namespace roifem::experiments
