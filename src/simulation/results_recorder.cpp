// SPDX-License-Identifier: GPL-3.0-or-later
#include "simulation/results_recorder.hpp"

#include <algorithm>

#include "common/errors.hpp"
#include "common/format.hpp"

namespace roifem::simulation {

namespace {

constexpr long flush_every = 50;

io::Hdf5Writer& with_header(io::Hdf5Writer& h5, const scenario::Scenario& sc, const ScenarioModel& model) {
  io::write_mesh(h5, model.mesh);
  if (!model.roi_nodes.empty()) h5.write("roi/nodes", model.roi_nodes, {model.roi_nodes.size()});
  h5.text("scenario", sc.resolved_toml());
  h5.attribute("integrator", sc.integrator);
  return h5;
}

}  // namespace

ResultsRecorder::ResultsRecorder(const scenario::Scenario& scenario, const ScenarioModel& model, const model::State& initial,
                                 const std::filesystem::path& out)
    : scenario_(scenario),
      model_(model),
      out_(out),
      file_(out / "results.h5"),
      h5_(file_.temporary_path()),
      time_s_(with_header(h5_, scenario, model).appendable("time_s", {})),
      wall_s_(h5_.appendable("step_wall_time_s", {})),
      kinetic_(h5_.appendable("energy/kinetic_J", {})),
      strain_(h5_.appendable("energy/strain_J", {})),
      dissipated_(h5_.appendable("energy/dissipated_J", {})),
      work_(h5_.appendable("energy/external_work_J", {})),
      xdmf_{.h5_name = "results.h5",
            .nodes = model.mesh.num_nodes(),
            .tets = model.mesh.num_tets(),
            .nodes_per_tet = model.mesh.is_quadratic() ? 10 : 4},
      ledger_(model.system(), initial, &model.tools) {
  topology_tets_ = model.mesh.num_tets();
  if (!scenario.cuts.empty()) cut_energy_.emplace(h5_.appendable("energy/cut_J", {}));
  if (model.split_plan) h5_.write("cuts/copy_of", model.split_plan->copy_of, {model.split_plan->copy_of.size()});
  if (!model.roi_nodes.empty()) roi_series_.emplace(h5_.appendable("roi/displacement_mm", {model.roi_nodes.size(), 3}, 16));
  roi_position_ = model.roi_components();
  roi_record_.resize(roi_position_.size());
  if (model.tools.empty()) return;
  tool_work_.emplace(h5_.appendable("energy/tool_work_J", {}));
  for (const auto& tool : model.tools.tools()) {
    h5_.write("tools/" + tool.name + "/nodes", tool.nodes, {tool.nodes.size()});
    tool_force_.push_back(h5_.appendable("tools/" + tool.name + "/force_N", {3}));
    tool_position_.push_back(h5_.appendable("tools/" + tool.name + "/displacement_mm", {3}));
  }
}

double ResultsRecorder::bytes_per_step(const ScenarioModel& model) {
  const double scalars = 6 + (model.tools.empty() ? 0 : 1 + 6 * model.tools.count());  // time, wall, 4 energies; tools
  return 8 * scalars + 24.0 * static_cast<double>(model.roi_nodes.size());
}

void ResultsRecorder::record(long k, const model::State& s, double seconds) {
  if (k > 0) ledger_.record(s);
  time_s_.append(&s.t);
  wall_s_.append(&seconds);
  const double energies[4] = {ledger_.kinetic(), ledger_.strain(), ledger_.dissipated(), ledger_.external_work()};
  kinetic_.append(&energies[0]);
  strain_.append(&energies[1]);
  dissipated_.append(&energies[2]);
  work_.append(&energies[3]);
  if (cut_energy_) {
    const double cut = ledger_.cut();
    cut_energy_->append(&cut);
  }
  if (tool_work_) {
    const double work = ledger_.tool_work();
    tool_work_->append(&work);
    const Vector& forces = ledger_.tool_forces();  // the ledger's, of this state
    const Vector positions = model_.tools.positions(s.t) / mm;
    for (std::size_t a = 0; a < tool_force_.size(); ++a) {
      tool_force_[a].append(forces.data() + 3 * a);
      tool_position_[a].append(positions.data() + 3 * a);
    }
  }
  if (roi_series_) {
    for (std::size_t i = 0; i < roi_position_.size(); ++i)
      roi_record_[i] = roi_position_[i] < 0 ? 0.0 : s.u[roi_position_[i]] / mm;
    roi_series_->append(roi_record_.data());
  }
  if (scenario_.field_every > 0 && k % scenario_.field_every == 0) {
    const Vector u_free = model_.condensation ? model_.condensation->expand(s.u, s.t) : s.u;
    const Vector field_mm = model_.full.displacement(u_free, s.t) / mm;
    write_field(k, s.t, std::vector<double>(field_mm.data(), field_mm.data() + field_mm.size()));
  }
  if (k % flush_every == 0) h5_.flush();
}

void ResultsRecorder::write_field(long k, double t, const std::vector<double>& field_mm) {
  const std::string name = format("fields/displacement_mm_%06ld", k);
  h5_.write(name, field_mm, {static_cast<hsize_t>(model_.mesh.num_nodes()), 3});
  xdmf_.times.push_back(t);
  xdmf_.fields.push_back("/" + name);
  if (topology_varies_) {
    xdmf_.topologies.push_back(topology_);
    xdmf_.topology_tets.push_back(topology_tets_);
  }
}

void ResultsRecorder::record_checkpoint(const RunCheckpoint& checkpoint) {
  if (checkpoint.step == last_checkpoint_) return;
  write_checkpoint(h5_, checkpoint);
  last_checkpoint_ = checkpoint.step;
}

void ResultsRecorder::make_constraint_series() {
  for (const auto& tool : model_.tools.tools())
    multiplier_force_.push_back(h5_.appendable("tools/" + tool.name + "/multiplier_force_N", {3}));
  drift_.emplace(h5_.appendable("tools/position_drift_mm", {}));
}

void ResultsRecorder::replay(long k, const EarlierRun& earlier) {
  const auto copy = [&](io::AppendableDataset& to, const std::string& name) {
    const double* row = earlier.row(name, k);
    if (row == nullptr) throw InputError(earlier.file().path() + ": no dataset /" + name + " to go on from");
    to.append(row);
  };
  copy(time_s_, "time_s");
  copy(wall_s_, "step_wall_time_s");
  copy(kinetic_, "energy/kinetic_J");
  copy(strain_, "energy/strain_J");
  copy(dissipated_, "energy/dissipated_J");
  copy(work_, "energy/external_work_J");
  if (cut_energy_) copy(*cut_energy_, "energy/cut_J");
  if (tool_work_) {
    copy(*tool_work_, "energy/tool_work_J");
    for (std::size_t a = 0; a < tool_force_.size(); ++a) {
      const std::string& name = model_.tools.tools()[a].name;
      copy(tool_force_[a], "tools/" + name + "/force_N");
      copy(tool_position_[a], "tools/" + name + "/displacement_mm");
    }
    if (earlier.row("tools/position_drift_mm", 0) != nullptr) {
      if (multiplier_force_.empty()) make_constraint_series();
      for (std::size_t a = 0; a < multiplier_force_.size(); ++a)
        copy(multiplier_force_[a], "tools/" + model_.tools.tools()[a].name + "/multiplier_force_N");
      copy(*drift_, "tools/position_drift_mm");
    }
  }
  if (roi_series_) copy(*roi_series_, "roi/displacement_mm");
  if (earlier.has_field(k)) write_field(k, *earlier.row("time_s", k), earlier.field(k));
  if (checkpoint_due(k) && earlier.file().has(format("restart/step_%06ld", k)))
    record_checkpoint(read_checkpoint(earlier.file(), k));
  if (k % flush_every == 0) h5_.flush();
}

void ResultsRecorder::resume(const RunCheckpoint& checkpoint, const std::string& restarted_from) {
  ledger_.resume(checkpoint.state, checkpoint.ledger);
  h5_.attribute("restarted_from", restarted_from);
}

void ResultsRecorder::record_constraints(const integrators::ConstraintReport& report, double t) {
  if (model_.tools.empty()) return;
  if (multiplier_force_.empty()) make_constraint_series();
  for (std::size_t a = 0; a < multiplier_force_.size(); ++a) multiplier_force_[a].append(report.forces.data() + 3 * a);
  const double drift_mm = report.position_drift / mm;
  drift_->append(&drift_mm);
  if (t > 0) {
    const Vector& residual = ledger_.tool_forces();  // record() of the same step came first
    force_gap_ = std::max(force_gap_, (report.forces - residual).lpNorm<Eigen::Infinity>());
    force_peak_ = std::max(force_peak_, residual.lpNorm<Eigen::Infinity>());
  }
}

void ResultsRecorder::record_cut(long step, const CutEvent& event, const model::State& at_cut,
                                 const std::vector<bool>& still_there) {
  ledger_.account_cut(at_cut, event.energy_removed());
  if (event.elements.empty() && event.moved.empty()) return;  // faces opened, the topology unchanged yet
  for (const auto& [node, copy] : event.splits) {
    split_nodes_.push_back(node);
    split_copies_.push_back(copy);
    split_at_step_.push_back(static_cast<int>(step));
    split_at_s_.push_back(event.time);
  }
  for (const Index e : event.elements) {
    removed_elements_.push_back(static_cast<int>(e));
    removed_at_step_.push_back(static_cast<int>(step));
    removed_at_s_.push_back(event.time);
  }
  // The remaining tetrahedra: the topology of every field from this step on.
  std::vector<int> tets;
  for (std::size_t e = 0; e < still_there.size(); ++e)
    if (still_there[e]) tets.insert(tets.end(), model_.mesh.tets[e].begin(), model_.mesh.tets[e].end());
  topology_ = format("/mesh/tets_from_step_%06ld", step);
  topology_tets_ = static_cast<long>(tets.size() / 4);
  h5_.write(topology_.substr(1), tets, {tets.size() / 4, 4});
  if (!topology_varies_) {  // the fields before the first cut: the whole mesh
    topology_varies_ = true;
    xdmf_.topologies.assign(xdmf_.times.size(), xdmf_.tets_dataset);
    xdmf_.topology_tets.assign(xdmf_.times.size(), xdmf_.tets);
  }
}

void ResultsRecorder::write_cuts() {
  if (!split_nodes_.empty()) {
    h5_.write("cuts/split_nodes", split_nodes_, {split_nodes_.size()});
    h5_.write("cuts/split_copies", split_copies_, {split_copies_.size()});
    h5_.write("cuts/split_at_step", split_at_step_, {split_at_step_.size()});
    h5_.write("cuts/split_at_s", split_at_s_, {split_at_s_.size()});
  }
  if (removed_elements_.empty()) return;
  h5_.write("cuts/removed_elements", removed_elements_, {removed_elements_.size()});
  h5_.write("cuts/removed_at_step", removed_at_step_, {removed_at_step_.size()});
  h5_.write("cuts/removed_at_s", removed_at_s_, {removed_at_s_.size()});
}

std::vector<std::filesystem::path> ResultsRecorder::finish(const integrators::Stats& st, const RunCheckpoint& last) {
  record_checkpoint(last);  // a finished run can be made longer from its last step
  write_cuts();
  h5_.attribute("counters", integrators::stats_line(st));
  h5_.attribute("status", "complete");
  h5_.close();
  file_.commit();
  if (has_fields()) io::write_xdmf(out_ / "results.xdmf", xdmf_);
  return remove_stale_incomplete(out_);
}

std::vector<std::filesystem::path> remove_stale_incomplete(const std::filesystem::path& out) {
  std::vector<std::filesystem::path> removed;
  for (const char* name : {"results.incomplete.h5", "results.incomplete.xdmf"}) {
    std::error_code ec;
    if (std::filesystem::remove(out / name, ec)) removed.push_back(out / name);
  }
  return removed;
}

void ResultsRecorder::abandon(const std::string& why) {
  write_cuts();
  h5_.attribute("status", "incomplete: " + why);
  h5_.close();
  file_.commit_as(out_ / "results.incomplete.h5");
  if (has_fields()) {
    xdmf_.h5_name = "results.incomplete.h5";
    io::write_xdmf(out_ / "results.incomplete.xdmf", xdmf_);
  }
}

}  // namespace roifem::simulation
