#include "simulation/scenario_run.hpp"

#include <ostream>

#include "common/atomic_file.hpp"
#include "common/errors.hpp"
#include "common/timer.hpp"
#include "condensation/reduced_model.hpp"
#include "integrators/factory.hpp"
#include "io/csv.hpp"
#include "io/hdf5_file.hpp"
#include "io/xdmf.hpp"
#include "model/energy.hpp"
#include "model/fem_model.hpp"
#include "simulation/deformation_check.hpp"
#include "simulation/interrupt.hpp"
#include "simulation/results_recorder.hpp"
#include "simulation/run_loop.hpp"
#include "simulation/scenario_model.hpp"

namespace roifem::simulation {

namespace {

using io::format;

void print_start(const scenario::Scenario& sc, const ScenarioModel& built, double setup_s, std::ostream& log) {
  const std::string stepping = sc.rtol ? format("%s error-controlled (rtol %g, atol %g m), output every %g s",
                                                sc.integrator.c_str(), *sc.rtol, sc.absolute_tolerance(), sc.dt)
                                       : format("%s, dt = %g s", sc.integrator.c_str(), sc.dt);
  log << format("%s: %lld nodes, %s model with %lld dofs (%s), %s, %ld steps; set up in %.2f s\n", sc.file.c_str(),
                static_cast<long long>(built.mesh.num_nodes()), built.condensation ? "condensed ROI" : "full",
                static_cast<long long>(built.system().size()), sc.roi ? sc.roi->describe().c_str() : "no ROI", stepping.c_str(),
                sc.steps, setup_s);
}

void print_deformation(const DeformationReport& r, const PeakDisplacement& peak, double dt, std::ostream& log) {
  if (r.peak_node < 0) {
    log << "peak displacement: none (nothing moved)\n";
    return;
  }
  log << format(
      "peak displacement %.4g mm at node %d (step %ld, t = %g s); mesh's smallest extent %.4g mm, mean element edge "
      "%.3g mm\n",
      r.peak_m / mm, r.peak_node, peak.step(), static_cast<double>(peak.step()) * dt, r.smallest_extent_m / mm,
      r.mean_edge_m / mm);
  for (const auto& w : r.warnings) log << "warning: " << w << '\n';
}

/// The run loop with the recorder as its observer. A divergence, a solver failure or a signal
/// keeps every completed step, marked incomplete, beside (never in place of) a good results.h5.
RunSummary integrate(const scenario::Scenario& sc, integrators::Integrator& integrator, model::State& state,
                     ResultsRecorder& recorder, PeakDisplacement& peak, const std::filesystem::path& out, std::ostream& log) {
  recorder.record(0, state, 0.0);
  const InterruptGuard interrupts;
  try {
    return run(integrator, state, sc.dt, sc.steps,
               {[&](long k, const model::State& s, double seconds) { recorder.record(k, s, seconds); },
                [&](long k, const model::State& s, double) { peak.observe(k, s); }},
               "run " + sc.file.filename().string());
  } catch (const Error& e) {
    if (!dynamic_cast<const SolverError*>(&e) && !dynamic_cast<const Interrupted*>(&e)) throw;
    recorder.abandon(e.what());
    log << "\nstopped: " << e.what() << "\nkept every completed step in " << (out / "results.incomplete.h5").string()
        << " (status: incomplete)\n";
    throw;
  }
}

}  // namespace

ScenarioRunSummary run_scenario(const scenario::Scenario& sc, const std::filesystem::path& out, std::ostream& log) {
  check_output_directory(out);
  // An unknown name, or tolerances for a fixed-step method, fail before any work.
  auto integrator = integrators::make_integrator(
      sc.integrator,
      {.dt = sc.dt, .adaptive = sc.rtol.has_value(), .rtol = sc.rtol.value_or(1e-6), .atol = sc.absolute_tolerance()});
  ScenarioRunSummary summary;
  Stopwatch setup_clock;
  const auto built = build_scenario_model(sc);
  const model::SecondOrderSystem& system = built->system();
  model::State state = model::State::at_rest(system.size());
  integrator->reset(system, state);
  summary.setup_s = setup_clock.seconds();
  summary.dofs = system.size();
  summary.roi_nodes = static_cast<Index>(built->roi_nodes.size());
  print_start(sc, *built, summary.setup_s, log);

  ResultsRecorder recorder(sc, *built, state, out);
  PeakDisplacement peak(*built);
  const RunSummary run_summary = integrate(sc, *integrator, state, recorder, peak, out, log);
  recorder.finish(run_summary.stats);

  const model::EnergyLedger& ledger = recorder.ledger();
  summary.steps = run_summary.steps;
  summary.stats = run_summary.stats;
  summary.step_s_median = median(run_summary.step_seconds);
  summary.final_kinetic_J = ledger.kinetic();
  summary.final_strain_J = ledger.strain();
  log << format("done: %ld steps, median %.4f ms per step; final kinetic %.3e J, strain %.3e J, work %.3e J, dissipated %.3e J\n",
                summary.steps, summary.step_s_median * 1e3, ledger.kinetic(), ledger.strain(), ledger.external_work(),
                ledger.dissipated());
  print_deformation(check_deformation(*built, peak), peak, sc.dt, log);
  log << "results: " << (out / "results.h5").string() << (recorder.has_fields() ? " (ParaView: results.xdmf)" : "") << '\n';
  return summary;
}

}  // namespace roifem::simulation
