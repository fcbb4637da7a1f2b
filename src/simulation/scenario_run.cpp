// SPDX-License-Identifier: GPL-3.0-or-later
#include "simulation/scenario_run.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <ostream>

#include "common/atomic_file.hpp"
#include "common/errors.hpp"
#include "common/format.hpp"
#include "common/interrupt.hpp"
#include "common/number_text.hpp"
#include "common/timer.hpp"
#include "condensation/reduced_model.hpp"
#include "integrators/integrator_table.hpp"
#include "io/hdf5_file.hpp"
#include "io/xdmf.hpp"
#include "model/energy.hpp"
#include "model/fem_model.hpp"
#include "model/internal_force.hpp"
#include "simulation/deformation_check.hpp"
#include "simulation/results_recorder.hpp"
#include "simulation/run_loop.hpp"
#include "simulation/scenario_model.hpp"
#include "simulation/scenario_stepper.hpp"

namespace roifem::simulation {

namespace {

/// The DAE forms restart IDA at every kink of the tools' paths (ida_tool_dae.hpp): a sampled
/// trajectory has one per sample, each about as costly as starting afresh. Said before the run.
void print_restarts(const scenario::Scenario& sc, const ScenarioModel& built, std::ostream& log) {
  if (!integrators::integrator_info(sc.integrator).needs_tools) return;
  const double t_end = sc.dt * static_cast<double>(sc.steps);
  std::vector<double> kinks;
  for (const auto& tool : built.tools.tools())
    for (const double t : tool.path.kinks_after(0.0))
      if (t <= t_end) kinks.push_back(t);
  std::sort(kinks.begin(), kinks.end());
  const auto count = std::unique(kinks.begin(), kinks.end()) - kinks.begin();
  if (count <= 10) return;
  log << format(
      "%s restarts IDA at each of the %ld kinks of the tools' paths within the run (a trajectory's samples), each about as "
      "costly as a fresh start (tens of steps and Jacobians: about 1 s on the paper's 900-dof ROI); a trajectory with fewer "
      "samples, or a method on the eliminated form (trapezoid, ida-bdf5), costs a fraction of that\n",
      sc.integrator.c_str(), static_cast<long>(count));
}

void print_start(const scenario::Scenario& sc, const ScenarioModel& built, double setup_s, std::ostream& log) {
  const std::string stepping = sc.rtol ? format("%s error-controlled (rtol %g, atol %g m), output every %g s",
                                                sc.integrator.c_str(), *sc.rtol, sc.absolute_tolerance(), sc.dt)
                                       : format("%s, dt = %g s", sc.integrator.c_str(), sc.dt);
  const std::string copies =
      built.split_plan ? format(" (%lld of them copies for the splits)", static_cast<long long>(built.split_plan->num_copies()))
                       : std::string();
  log << format("%s: %lld nodes%s, %s model with %lld dofs (%s), %s, %ld steps; set up in %.2f s\n", sc.file.c_str(),
                static_cast<long long>(built.mesh.num_nodes()), copies.c_str(), built.condensation ? "condensed ROI" : "full",
                static_cast<long long>(built.system().size()), sc.roi ? sc.roi->describe().c_str() : "no ROI", stepping.c_str(),
                sc.steps, setup_s);
  if (!sc.material_regions.empty()) {
    const std::vector<Index> counts = built.full.materials.counts(built.mesh.num_tets());
    log << format("materials: %s on %lld tetrahedra", sc.material_name.c_str(), static_cast<long long>(counts[0]));
    for (std::size_t r = 0; r < sc.material_regions.size(); ++r) {
      const auto& region = sc.material_regions[r];
      log << format("; %s (%s, E = %.4g Pa, nu = %.4g) on %lld", region.set.c_str(), region.name.c_str(), region.material.young(),
                    region.material.poisson(), static_cast<long long>(counts[r + 1]));
    }
    log << '\n';
  }
  for (const auto& w : built.full.warnings) log << "warning: " << w << '\n';
  for (const auto& tool : built.tools.tools()) {
    const Vec3 d = tool.path.displacement / mm;
    log << format("tool '%s': %zu nodes, moved by (%.4g, %.4g, %.4g) mm over %g s\n", tool.name.c_str(), tool.nodes.size(), d.x(),
                  d.y(), d.z(), tool.path.ramp.duration);
  }
  print_restarts(sc, built, log);
}

void print_cuts(const scenario::Scenario& sc, const ScenarioStepper& stepper, std::ostream& log) {
  if (const cutting::SplitPlan* plan = stepper.cuts().split_plan()) {
    log << format(
        "cuts: %zu faces separated by %zu blade%s within the run, from t = %g s to t = %g s (at the start of the step that "
        "reaches them); the nodes they split take %lld copies\n",
        plan->faces.size(), sc.cuts.size(), sc.cuts.size() == 1 ? "" : "s", plan->faces.front().time, plan->faces.back().time,
        static_cast<long long>(plan->num_copies()));
    return;
  }
  const auto& schedule = stepper.cuts().schedule();
  if (schedule.empty()) return;
  log << format(
      "cuts: %zu tetrahedra crossed by %zu blade%s within the run, from t = %g s to t = %g s (removed at the start of "
      "the step that reaches them)\n",
      schedule.size(), sc.cuts.size(), sc.cuts.size() == 1 ? "" : "s", schedule.front().time, schedule.back().time);
}

void print_tool_forces(const ScenarioModel& built, const model::State& state, const model::EnergyLedger& ledger,
                       std::ostream& log) {
  if (built.tools.empty()) return;
  const Vector F = built.tools.forces(state.u, state.t);
  for (std::size_t a = 0; a < built.tools.tools().size(); ++a) {
    const Vec3 f = F.segment<3>(3 * static_cast<Index>(a)) * 1e3;
    log << format("tool '%s': force on the tissue (%.4g, %.4g, %.4g) mN at t = %g s\n", built.tools.tools()[a].name.c_str(),
                  f.x(), f.y(), f.z(), state.t);
  }
  const double scale = std::max(std::abs(ledger.tool_work()), std::abs(ledger.external_work()));
  log << format("tools' work %.4e J; energy balance |E + D%s - W - W_tools - E_0| / max(|W|, |W_tools|) = %.1e\n",
                ledger.tool_work(), ledger.cut() != 0 ? " + E_cut" : "",
                scale > 0 ? std::abs(ledger.balance_residual()) / scale : 0.0);
}

void print_deformation(const DeformationReport& r, const PeakDisplacement& peak, double dt, std::ostream& log) {
  if (r.peak_node < 0) {
    log << "peak displacement: none (nothing moved)\n";
    return;
  }
  log << format(
      "peak displacement %.4g mm at node %d (step %ld, t = %g s; over every node: the tools', the static part's); mesh's "
      "smallest extent %.4g mm, mean element edge "
      "%.3g mm\n",
      r.peak_m / mm, r.peak_node, peak.step(), static_cast<double>(peak.step()) * dt, r.smallest_extent_m / mm,
      r.mean_edge_m / mm);
  for (const auto& w : r.warnings) log << "warning: " << w << '\n';
}

/// InputError when the results of `steps` steps could not fit on the output's file system.
void check_results_fit(const scenario::Scenario& sc, const ScenarioModel& built, const std::filesystem::path& out) {
  const double steps = static_cast<double>(sc.steps);
  const double fields = sc.field_every > 0 ? std::floor(steps / static_cast<double>(sc.field_every)) + 1 : 0;
  const long restart_every = sc.restart_interval();
  const double points = (restart_every > 0 ? std::floor(steps / static_cast<double>(restart_every)) : 0) + 1;
  const double bytes = steps * ResultsRecorder::bytes_per_step(built) + fields * ResultsRecorder::bytes_per_field(built) +
                       points * ResultsRecorder::bytes_per_restart_point(built);
  std::error_code ec;
  const auto space = std::filesystem::space(std::filesystem::absolute(out).parent_path(), ec);
  if (ec || bytes <= static_cast<double>(space.available)) return;
  throw InputError(
      format("%s: key 'time.steps' = %ld is too many for the disk: its results would take about %.3g GB (%.0f bytes "
             "per step%s), and %s has %.3g GB free; fewer steps, or a larger output.field_every",
             sc.file.c_str(), sc.steps, bytes / 1e9, ResultsRecorder::bytes_per_step(built),
             fields > 0 ? format(" and %.0f per field", ResultsRecorder::bytes_per_field(built)).c_str() : "", out.c_str(),
             static_cast<double>(space.available) / 1e9));
}

/// The run loop with the recorder as its observer, from the step the stepper is at (0, or a
/// restart's). A divergence, a solver failure, an element that inverts or a signal keeps every
/// completed step, marked incomplete, beside (never in place of) a good results.h5.
RunSummary integrate(const scenario::Scenario& sc, ScenarioStepper& stepper, ResultsRecorder& recorder, PeakDisplacement& peak,
                     const std::filesystem::path& out, std::ostream& log) {
  const integrators::Integrator& integrator = stepper.integrator();
  if (stepper.steps_taken() == 0) {
    recorder.record(0, stepper.state(), 0.0);
    if (const auto held = integrator.constraints()) recorder.record_constraints(*held, stepper.state().t);
  }
  const InterruptGuard interrupts;
  try {
    return run(stepper, sc.steps - stepper.steps_taken(),
               {[&](long, const model::State& s, double seconds) {
                  const long k = stepper.steps_taken();
                  recorder.record(k, s, seconds);
                  if (const auto held = integrator.constraints()) recorder.record_constraints(*held, s.t);
                  if (recorder.checkpoint_due(k)) recorder.record_checkpoint(stepper.checkpoint(recorder.ledger()));
                },
                [&](long, const model::State& s, double) { peak.observe(stepper.steps_taken(), s); }},
               "run " + sc.file.filename().string());
  } catch (const Error& e) {
    if (!dynamic_cast<const SolverError*>(&e) && !dynamic_cast<const ModelError*>(&e) && !dynamic_cast<const Interrupted*>(&e))
      throw;
    recorder.abandon(e.what());
    log << "\nstopped: " << e.what() << "\nkept every completed step in " << (out / "results.incomplete.h5").string()
        << " (status: incomplete)\n";
    throw;
  }
}

/// [restart] (or --from, --step): the earlier run and its restart point, checked before anything
/// is written.
struct Restart {
  std::unique_ptr<EarlierRun> earlier;
  RunCheckpoint from;
};

Restart restart_point(const scenario::Scenario& sc) {
  Restart r{.earlier = std::make_unique<EarlierRun>(sc.restart->from, sc), .from = {}};
  r.from = r.earlier->checkpoint(sc.restart->step);
  if (r.earlier->integrator() != sc.integrator) r.from.integrator.reset();  // another method's own state means nothing here
  if (r.from.step >= sc.steps)
    throw InputError(format("%s: a restart at step %ld of a run of %ld steps has nothing left to run (time.steps: more)",
                            (sc.restart->where.empty() ? sc.file.string() : sc.restart->where).c_str(), r.from.step, sc.steps));
  return r;
}

/// The earlier run's steps 0..K into the recorder as it recorded them, its cuts replayed, and the
/// stepper at its restart point.
void restart(const scenario::Scenario& sc, const Restart& r, ScenarioStepper& stepper, ResultsRecorder& recorder,
             std::ostream& log) {
  const EarlierRun& earlier = *r.earlier;
  const RunCheckpoint& from = r.from;
  const std::string before = earlier.integrator();
  const bool exact = stepper.resume(from, [&](long k) { recorder.replay(k, earlier); });
  const std::string whence =
      format("%s, step %ld (t = %s s)", earlier.file().path().c_str(), from.step, number_text(from.state.t).c_str());
  recorder.resume(from, whence);
  log << "restarted from " << whence << ": steps 0.." << from.step << " as it recorded them, then "
      << (exact ? sc.integrator + " goes on exactly as the run that never stopped"
          : before != sc.integrator
              ? sc.integrator + " (the run went with " + before +
                    ") starts afresh from u, v at t = " + number_text(from.state.t) + " s"
              : sc.integrator + " starts afresh from u, v at t = " + number_text(from.state.t) +
                    " s (its step sizes and history are its library's own: the run goes on within its tolerances)")
      << "\n";
}

}  // namespace

ScenarioRunSummary run_scenario(const scenario::Scenario& sc, const std::filesystem::path& out, std::ostream& log) {
  const std::optional<Restart> restarting = sc.restart ? std::optional<Restart>(restart_point(sc)) : std::nullopt;
  check_output_directory(out);
  ScenarioRunSummary summary;
  Stopwatch setup_clock;
  // The model, the integrator and the grid, as the Python module's Simulation steps them (an
  // unknown integrator, or tolerances for a fixed-step method, fail before any work); the
  // recorder keeps the energies.
  ScenarioStepper stepper(sc, /*energy=*/false);
  ScenarioModel& built_model = stepper.model();
  const ScenarioModel* built = &built_model;
  const model::SecondOrderSystem& system = built->system();
  const model::State& state = stepper.state();
  summary.setup_s = setup_clock.seconds();
  summary.dofs = system.size();
  summary.roi_nodes = static_cast<Index>(built->roi_nodes.size());
  print_start(sc, *built, summary.setup_s, log);
  print_cuts(sc, stepper, log);
  check_results_fit(sc, *built, out);

  ResultsRecorder recorder(sc, *built, state, out);
  stepper.on_cut([&](const CutEvent& event, const model::State& at_cut) {
    recorder.record_cut(stepper.steps_taken() + 1, event, at_cut, stepper.cuts().still_there());
    for (const auto& w : event.warnings) log << "\nwarning: " << w << '\n';
  });
  if (restarting) restart(sc, *restarting, stepper, recorder, log);
  PeakDisplacement peak(*built);
  const RunSummary run_summary = integrate(sc, stepper, recorder, peak, out, log);
  for (const auto& stale : recorder.finish(run_summary.stats, stepper.checkpoint(recorder.ledger())))
    log << "removed " << stale.string() << ", an earlier run's that was stopped\n";

  const model::EnergyLedger& ledger = recorder.ledger();
  summary.steps = run_summary.steps;
  summary.stats = run_summary.stats;
  summary.step_s_median = median(run_summary.step_seconds);
  summary.final_kinetic_J = ledger.kinetic();
  summary.final_strain_J = ledger.strain();
  log << format("done: %ld steps, median %.4f ms per step; final kinetic %.3e J, strain %.3e J, work %.3e J, dissipated %.3e J\n",
                summary.steps, summary.step_s_median * 1e3, ledger.kinetic(), ledger.strain(), ledger.external_work(),
                ledger.dissipated());
  log << sc.integrator << "'s counters: " << integrators::stats_line(summary.stats) << '\n';
  if (!sc.cuts.empty()) {
    const double scale = std::max({std::abs(ledger.external_work()), std::abs(ledger.tool_work()), std::abs(ledger.cut())});
    const std::string what = stepper.cuts().split_plan() ? format("%zu faces separated, %zu nodes split",
                                                                  stepper.cuts().faces_separated(), stepper.cuts().nodes_split())
                                                         : format("%zu tetrahedra removed", stepper.cuts().schedule().size());
    log << format(
        "cuts: %s, taking %.4e J (E_cut); energy balance |E + D + E_cut - W - W_tools - E_0| / "
        "max(|W|, |W_tools|, |E_cut|) = %.1e; %s\n",
        what.c_str(), ledger.cut(), scale > 0 ? std::abs(ledger.balance_residual()) / scale : 0.0,
        summary.stats.system_changes > 0
            ? format("%s corrected its factor at %ld cuts%s", sc.integrator.c_str(), summary.stats.system_changes,
                     summary.stats.lin_setups > 1
                         ? format(" and factored K_eff afresh at %ld, where the correction would have cost more than the "
                                  "factor's own solve",
                                  summary.stats.lin_setups - 1)
                               .c_str()
                         : "")
                  .c_str()
            : format("%s restarted at each cut", sc.integrator.c_str()).c_str());
  }
  if (system.is_nonlinear())
    log << format("Newton (%s): %ld iterations, %.2f per step, %ld tangents factorized%s\n",
                  system.internal_force->describe().c_str(), summary.stats.nonlinear_iterations,
                  static_cast<double>(summary.stats.nonlinear_iterations) / static_cast<double>(std::max(1L, summary.steps)),
                  summary.stats.lin_setups,
                  summary.stats.failed_steps == 0 ? ""
                  : summary.stats.indefinite_steps == 0
                      ? format(" (%ld failed steps, retried)", summary.stats.failed_steps).c_str()
                      : format(" (%ld failed steps, retried; %ld Newton matrices indefinite, by LU)", summary.stats.failed_steps,
                               summary.stats.indefinite_steps)
                            .c_str());
  print_tool_forces(*built, state, ledger, log);
  if (const auto held = stepper.integrator().constraints())
    log << format("%s: the multipliers' tool forces differ from the residual's by at most %.1e of their peak; drift %.1e mm\n",
                  sc.integrator.c_str(), recorder.multiplier_disagreement(), held->position_drift / mm);
  const std::vector<mesh::Tet> tets_at_peak = stepper.cuts().tets_at(peak.state().t, built_model.mesh);
  print_deformation(check_deformation(built_model, peak, stepper.cuts().still_there(), &tets_at_peak), peak, sc.dt, log);
  log << "results: " << (out / "results.h5").string() << (recorder.has_fields() ? " (ParaView: results.xdmf)" : "") << '\n';
  return summary;
}

}  // namespace roifem::simulation
