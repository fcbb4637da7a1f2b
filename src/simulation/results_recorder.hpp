// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// The run loop's HDF5 observer for `roifem run`: appends every step's time, wall time, energies
/// (EnergyLedger), ROI displacement and, every field_every steps, the whole displacement field
/// (static part recovered) and, with tools, each tool's position and force on the tissue (N) and
/// their work, to results.h5 under a temporary name, flushes every 50 steps (what a
/// kill -9 cannot take away), and on finish() moves the file into place: results.h5 when
/// complete, results.incomplete.h5 (status attribute: why) beside a good one when not.
/// With cuts: energy/cut_J per step, /cuts/{removed_elements, removed_at_step, removed_at_s} (each
/// removed tetrahedron, the step at whose start it went, and that time), and after each cut the
/// remaining tetrahedra as /mesh/tets_from_step_NNNNNN, the topology of the fields from then on.
/// In split mode the mesh's last nodes are the copies (/cuts/copy_of: each one's original node),
/// /cuts/{split_nodes, split_copies, split_at_step, split_at_s} list each split (the node, the copy
/// taking a piece of its tetrahedra, when), and /mesh/tets_from_step_NNNNNN the corners after it.
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/atomic_file.hpp"
#include "integrators/integrator.hpp"
#include "io/hdf5_file.hpp"
#include "io/xdmf.hpp"
#include "model/energy.hpp"
#include "scenario/scenario.hpp"
#include "simulation/cuts/scenario_cuts.hpp"
#include "simulation/earlier_run.hpp"
#include "simulation/run_checkpoint.hpp"
#include "simulation/scenario_model.hpp"

namespace roifem::simulation {

class ResultsRecorder {
 public:
  /// Opens DIR/results.h5's temporary file and writes the mesh, the ROI nodes and the scenario.
  ResultsRecorder(const scenario::Scenario& scenario, const ScenarioModel& model, const model::State& initial,
                  const std::filesystem::path& out);
  /// The observer: step k's state and wall time (k = 0: the initial state).
  void record(long k, const model::State& state, double seconds);
  /// With a method that holds the tools' constraints itself (a DAE form): its multipliers' force
  /// per tool and its drift, after record() of the same step.
  void record_constraints(const integrators::ConstraintReport& report, double t);
  /// A cut at `at_cut`, the start of step `step` (ScenarioStepper::on_cut): the ledger books it;
  /// `still_there` (per tetrahedron, after it) is the topology of the fields from then on.
  void record_cut(long step, const CutEvent& event, const model::State& at_cut, const std::vector<bool>& still_there);
  /// Whether step k gets a restart point: every output.restart_every-th (a finished run's last is
  /// written by finish()).
  bool checkpoint_due(long k) const {
    const long every = scenario_.restart_interval();
    return every > 0 && k > 0 && k % every == 0;
  }
  /// Step k's restart point (run_checkpoint.hpp), after record() of the same step.
  void record_checkpoint(const RunCheckpoint& checkpoint);
  /// A restart: step k as `earlier` recorded it (every series' row, its field and its restart
  /// point, in the order record() writes them), for k = 0..K before the run goes on.
  void replay(long k, const EarlierRun& earlier);
  /// A restart: the ledger goes on from the restart point's sums, and the file says whence it came.
  void resume(const RunCheckpoint& checkpoint, const std::string& restarted_from);
  /// max over the steps of |F_multipliers - F_residual| / max |F_residual| (0 without a DAE form).
  double multiplier_disagreement() const { return force_peak_ > 0 ? force_gap_ / force_peak_ : 0.0; }
  /// Writes the counters, marks the file complete and moves it into place (with results.xdmf).
  /// Returns the stale results.incomplete.{h5,xdmf} of an earlier, stopped run that it removed.
  std::vector<std::filesystem::path> finish(const integrators::Stats& stats, const RunCheckpoint& last);
  /// Keeps every recorded step as results.incomplete.h5 (status: `why`) beside any good results.h5.
  void abandon(const std::string& why);
  const model::EnergyLedger& ledger() const { return ledger_; }
  /// The size of what the run writes (bytes, without HDF5's overhead): per step and per field.
  static double bytes_per_step(const ScenarioModel& model);
  static double bytes_per_field(const ScenarioModel& model) { return 24.0 * static_cast<double>(model.mesh.num_nodes()); }
  /// A restart point: u, v and an integrator's vector, per unknown.
  static double bytes_per_restart_point(const ScenarioModel& model) { return 24.0 * static_cast<double>(model.system().size()); }
  bool has_fields() const { return !xdmf_.times.empty(); }

 private:
  const scenario::Scenario& scenario_;
  const ScenarioModel& model_;
  std::filesystem::path out_;
  AtomicFile file_;
  io::Hdf5Writer h5_;
  io::AppendableDataset time_s_, wall_s_, kinetic_, strain_, dissipated_, work_;
  std::optional<io::AppendableDataset> roi_series_;
  std::optional<io::AppendableDataset> tool_work_;
  std::vector<io::AppendableDataset> tool_force_, tool_position_;  ///< per tool
  std::vector<io::AppendableDataset> multiplier_force_;            ///< per tool, with a DAE form
  std::optional<io::AppendableDataset> drift_;
  double force_gap_ = 0, force_peak_ = 0;
  std::vector<Index> roi_position_;  ///< each ROI node's components in the integrated vector (-1: constrained)
  std::vector<double> roi_record_;
  io::XdmfSeries xdmf_;
  model::EnergyLedger ledger_;
  std::optional<io::AppendableDataset> cut_energy_;
  std::vector<int> removed_elements_, removed_at_step_;
  std::vector<double> removed_at_s_;
  std::vector<int> split_nodes_, split_copies_, split_at_step_;
  std::vector<double> split_at_s_;
  std::string topology_ = "/mesh/tets";
  long topology_tets_ = 0;
  bool topology_varies_ = false;
  long last_checkpoint_ = -1;
  void write_cuts();
  /// Step k's displacement field (mm, #N x 3) at time t, and its XDMF entry.
  void write_field(long k, double t, const std::vector<double>& field_mm);
  /// The multipliers' series, made at the first report of a DAE form.
  void make_constraint_series();
};

/// Removes out/results.incomplete.{h5,xdmf}, left by an earlier run that was stopped, once a run
/// has written its complete results.h5 beside them; returns what it removed.
std::vector<std::filesystem::path> remove_stale_incomplete(const std::filesystem::path& out);

}  // namespace roifem::simulation
