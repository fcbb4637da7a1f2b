// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// `roifem-mpi condense`: the scenario's ROI condensed from the distributed K by MUMPS's Schur
/// complement (mumps_condensation.hpp), K~ = K_dd - K_ds K_ss^-1 K_sd and f~ = f_d - K_ds K_ss^-1 f_s
/// per load pattern, written by rank 0 to DIR/condensation.h5 (K_tilde, f_tilde, roi/nodes,
/// roi/free_dofs); the condensed model run once on rank 0 (its ROI peak); with `check_serial`
/// also the serial CHOLMOD condensation and the differences. `log` is written by rank 0 only.
#include <filesystem>
#include <iosfwd>

#include <mpi.h>

#include "scenario/scenario.hpp"

namespace roifem::distributed {

void condense_distributed(const scenario::Scenario& scenario, const std::filesystem::path& out, bool check_serial,
                          std::ostream& log, MPI_Comm comm);

}  // namespace roifem::distributed
