// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// A run's restart point (`roifem run --from DIR/results.h5 --step K`): everything the run carries
/// from step K to step K+1 that the scenario does not give again. The state (u, v, t) of the
/// integrated unknowns, the integrator's own (integrators::IntegratorCheckpoint: the trapezoidal
/// rule's acceleration, grid and counters; none for a method that restarts afresh), the counters of
/// the integrator's runs before its restarts at cuts, and the energy ledger's sums. The model,
/// its cuts so far and the tools' positions come from the scenario (a restart replays the cuts up
/// to step K; the tools' paths are functions of t).
/// In results.h5 under /restart/step_KKKKKK/: u, v, t, ledger, restarted_counters and, where the
/// integrator keeps one, integrator_numbers and integrator_vector_I.
#include <optional>
#include <vector>

#include "integrators/integrator.hpp"
#include "io/hdf5_file.hpp"
#include "io/hdf5_reader.hpp"

namespace roifem::simulation {

struct RunCheckpoint {
  long step = 0;
  model::State state;
  std::optional<integrators::IntegratorCheckpoint> integrator;
  integrators::Stats restarted;  ///< the integrator's runs before its restarts at cuts
  std::vector<double> ledger;    ///< model::EnergyLedger::sums()
};

/// /restart/step_KKKKKK/ in `h5`.
void write_checkpoint(io::Hdf5Writer& h5, const RunCheckpoint& checkpoint);
/// The steps `file` holds checkpoints of, ascending.
std::vector<long> checkpoint_steps(const io::Hdf5Reader& file);
/// The checkpoint of `step` (InputError naming the file and the steps it has when it has none there).
RunCheckpoint read_checkpoint(const io::Hdf5Reader& file, long step);

}  // namespace roifem::simulation
