// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Static condensation across ranks: the ROI's Schur complement from the distributed K, computed by
/// MUMPS (ICNTL(19) = 1: centralized on rank 0; ICNTL(26) = 1: the reduced right-hand sides):
///   K~ = K_dd - K_ds K_ss^-1 K_sd,   f~_k = p_d,k - K_ds K_ss^-1 p_s,k   (each load pattern p_k),
/// the serial condensation/ (static_part_factor.hpp) on one rank, here from MUMPS's distributed
/// factorization of K with the ROI's dofs as Schur variables (eliminated last). MUMPS is called
/// directly: PETSc 3.18's MatFactorSetSchurIS refuses MUMPS Schur complements on more than one rank.
#include <vector>

#include "distributed/distributed_model.hpp"

namespace roifem::distributed {

struct DistributedCondensation {
  DenseMatrix K_tilde;          ///< on rank 0: #d x #d, in the order of the dofs given (empty elsewhere)
  std::vector<Vector> f_tilde;  ///< on rank 0: per load pattern of the model, #d
  double factor_s = 0;          ///< the analysis and factorization (wall, s)
  double factor_entries = 0;    ///< MUMPS's INFOG(29): entries in the factors, all ranks
  double peak_megabytes = 0;    ///< MUMPS's INFOG(21): the largest memory of one rank in the factorization (MB)
};

/// The condensation onto `roi_dofs` (the serial free numbering of model.frame, e.g.
/// roi::Partition::d). SolverError with MUMPS's INFOG(1..2) when the factorization fails (a
/// singular static part: INFOG(1) = -10).
DistributedCondensation condense_with_mumps(const DistributedModel& model, const std::vector<Index>& roi_dofs);

}  // namespace roifem::distributed
