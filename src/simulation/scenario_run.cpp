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
#include "simulation/interrupt.hpp"
#include "simulation/run_loop.hpp"
#include "simulation/scenario_model.hpp"

namespace roifem::simulation {

namespace {

using io::format;

/// Maps the integrated system's vector to all nodes (mm), recovering the static part if condensed.
class FieldMapper {
 public:
  FieldMapper(const fem::DofMap& dofs, const condensation::ReducedModel* condensation)
      : dofs_(dofs), condensation_(condensation) {}
  Vector free_displacement(const model::State& s) const {
    return condensation_ ? condensation_->expand(s.u, s.t) : s.u;
  }
  std::vector<double> field_mm(const model::State& s) const {
    const Vector full = dofs_.expand(free_displacement(s)) / mm;
    return {full.data(), full.data() + full.size()};
  }

 private:
  const fem::DofMap& dofs_;
  const condensation::ReducedModel* condensation_;
};

}  // namespace

ScenarioRunSummary run_scenario(const scenario::Scenario& sc, const std::filesystem::path& out, std::ostream& log) {
  check_output_directory(out);
  auto integrator = integrators::make_integrator(sc.integrator, sc.dt);  // an unknown name fails before any work
  ScenarioRunSummary summary;
  Stopwatch setup_clock;
  const auto built = build_scenario_model(sc);
  const mesh::TetMesh& mesh = built->mesh;
  const fem::DofMap& dofs = *built->full.dofs;
  const auto* condensation = built->condensation.get();
  const std::vector<int>& roi_nodes = built->roi_nodes;
  const model::SecondOrderSystem& system = built->system();
  const FieldMapper mapper(dofs, condensation);
  model::State state = model::State::at_rest(system.size());
  integrator->reset(system, state);
  summary.setup_s = setup_clock.seconds();
  summary.dofs = system.size();
  summary.roi_nodes = static_cast<Index>(roi_nodes.size());
  log << format("%s: %lld nodes, %s model with %lld dofs (%s), %s, dt = %g s, %ld steps; set up in %.2f s\n",
                sc.file.c_str(), static_cast<long long>(mesh.num_nodes()), condensation ? "condensed ROI" : "full",
                static_cast<long long>(system.size()), sc.roi ? sc.roi->describe().c_str() : "no ROI",
                sc.integrator.c_str(), sc.dt, sc.steps, summary.setup_s);

  // Where each ROI node's components sit in the integrated vector (-1: constrained).
  std::vector<Index> roi_position;
  if (condensation)
    for (const auto& p : built->node_positions()) roi_position.insert(roi_position.end(), p.begin(), p.end());

  AtomicFile file(out / "results.h5");
  io::Hdf5Writer h5(file.temporary_path());
  const auto n_nodes = static_cast<hsize_t>(mesh.num_nodes());
  io::write_mesh(h5, mesh);
  if (!roi_nodes.empty()) h5.write("roi/nodes", roi_nodes, {roi_nodes.size()});
  h5.attribute("scenario", sc.resolved_toml());
  h5.attribute("integrator", sc.integrator);
  auto time_s = h5.appendable("time_s", {});
  auto wall_s = h5.appendable("step_wall_time_s", {});
  auto kinetic = h5.appendable("energy/kinetic_J", {}), strain = h5.appendable("energy/strain_J", {});
  auto dissipated = h5.appendable("energy/dissipated_J", {}), work = h5.appendable("energy/external_work_J", {});
  std::optional<io::AppendableDataset> roi_series;
  if (!roi_nodes.empty()) roi_series.emplace(h5.appendable("roi/displacement_mm", {roi_nodes.size(), 3}, 16));
  io::XdmfSeries xdmf{.h5_name = "results.h5", .nodes = mesh.num_nodes(), .tets = mesh.num_tets()};

  model::EnergyLedger ledger(system, state);
  const long flush_every = 50;
  std::vector<double> roi_record(roi_position.size());
  auto record = [&](long k, const model::State& s, double seconds) {
    if (!s.u.allFinite())
      throw SolverError(format("%s: non-finite displacement at step %ld, t = %g s", sc.integrator.c_str(), k, s.t));
    if (k > 0) ledger.record(s);
    time_s.append(&s.t);
    wall_s.append(&seconds);
    const double energies[4] = {ledger.kinetic(), ledger.strain(), ledger.dissipated(), ledger.external_work()};
    kinetic.append(&energies[0]);
    strain.append(&energies[1]);
    dissipated.append(&energies[2]);
    work.append(&energies[3]);
    if (roi_series) {
      for (std::size_t i = 0; i < roi_position.size(); ++i)
        roi_record[i] = roi_position[i] < 0 ? 0.0 : s.u[roi_position[i]] / mm;
      roi_series->append(roi_record.data());
    }
    if (sc.field_every > 0 && k % sc.field_every == 0) {
      const std::string name = format("fields/displacement_mm_%06ld", k);
      h5.write(name, mapper.field_mm(s), {n_nodes, 3});
      xdmf.times.push_back(s.t);
      xdmf.fields.push_back("/" + name);
    }
    if (k % flush_every == 0) h5.flush();  // what a kill -9 cannot take away
  };
  record(0, state, 0.0);
  RunSummary run_summary;
  {
    const InterruptGuard interrupts;
    try {
      run_summary = run(*integrator, state, sc.dt, sc.steps, {record}, "run " + sc.file.filename().string());
    } catch (const Error& e) {
      // A divergence, a solver failure or a signal: keep every completed step, marked incomplete,
      // beside (never in place of) a good results.h5.
      if (!dynamic_cast<const SolverError*>(&e) && !dynamic_cast<const Interrupted*>(&e)) throw;
      h5.attribute("status", std::string("incomplete: ") + e.what());
      h5.close();
      file.commit_as(out / "results.incomplete.h5");
      if (!xdmf.times.empty()) {
        xdmf.h5_name = "results.incomplete.h5";
        io::write_xdmf(out / "results.incomplete.xdmf", xdmf);
      }
      log << "\nstopped: " << e.what() << "\nkept every completed step in " << (out / "results.incomplete.h5").string()
          << " (status: incomplete)\n";
      throw;
    }
  }

  const auto& st = run_summary.stats;
  h5.attribute("counters", format("steps=%ld rhs_evals=%ld jac_evals=%ld lin_setups=%ld lin_solves=%ld lin_iterations=%ld failed_steps=%ld",
                                  st.steps, st.rhs_evals, st.jac_evals, st.lin_setups, st.lin_solves, st.lin_iterations,
                                  st.failed_steps));
  h5.attribute("status", "complete");
  h5.close();
  file.commit();
  if (!xdmf.times.empty()) io::write_xdmf(out / "results.xdmf", xdmf);

  summary.steps = run_summary.steps;
  summary.stats = st;
  summary.step_s_median = median(run_summary.step_seconds);
  summary.final_kinetic_J = ledger.kinetic();
  summary.final_strain_J = ledger.strain();
  log << format("done: %ld steps, median %.4f ms per step; final kinetic %.3e J, strain %.3e J, work %.3e J, dissipated %.3e J\n",
                summary.steps, summary.step_s_median * 1e3, ledger.kinetic(), ledger.strain(), ledger.external_work(),
                ledger.dissipated());
  log << "results: " << (out / "results.h5").string() << (xdmf.times.empty() ? "" : " (ParaView: results.xdmf)") << '\n';
  return summary;
}

}  // namespace roifem::simulation
