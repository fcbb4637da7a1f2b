// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// `roifem-mpi run`: a scenario's full model (every free node dynamic; its [roi] and integrator are
/// roifem run's) integrated by the trapezoidal rule at its dt on P ranks (distributed_trapezoid.hpp),
/// written by rank 0 to DIR/results.h5 and DIR/results.xdmf in roifem run's layout:
///   /mesh/nodes_mm, /mesh/tets, /time_s, /step_wall_time_s,
///   /energy/{kinetic_J, strain_J, dissipated_J, external_work_J} (model/energy.hpp's ledger),
///   /ksp_iterations (per step), /fields/displacement_mm_NNNNNN every output.field_every steps,
///   attributes scenario, integrator ("trapezoid (PETSc, cg + gamg, rtol 1e-10, 2 ranks)"), status.
/// Written under a temporary name and moved into place when complete (common/atomic_file.hpp).
#include <filesystem>
#include <iosfwd>
#include <string>

#include <mpi.h>

#include "scenario/scenario.hpp"

namespace roifem::distributed {

struct DistributedRunSummary {
  long dofs = 0, steps = 0;
  int ranks = 1;
  std::string solver;
  double setup_s = 0;        ///< reading, partitioning, assembly, K_eff's factorization or preconditioner
  double step_s_median = 0;  ///< wall time per step
  double iterations_per_step = 0;
  double peak_rss_mb = 0;   ///< the largest resident memory of one rank (MB)
  double total_rss_mb = 0;  ///< the ranks' peak resident memories summed (MB)
  double now_rss_mb = 0;    ///< the largest resident memory of one rank at the end (MB)
  double final_strain_J = 0, final_kinetic_J = 0, final_work_J = 0, final_dissipated_J = 0;
};

/// Runs on every rank of `comm`; `log` is written by rank 0 only.
DistributedRunSummary run_distributed(const scenario::Scenario& scenario, const std::filesystem::path& out, std::ostream& log,
                                      MPI_Comm comm);

/// The resident sets of the ranks of `comm` (MB): their peaks so far (the largest and the sum) and
/// the largest now (after the transient peaks of reading the mesh with Gmsh, a factorization's
/// workspace).
struct ResidentMemory {
  double largest = 0, total = 0, largest_now = 0;
};
ResidentMemory peak_resident_megabytes(MPI_Comm comm);

}  // namespace roifem::distributed
