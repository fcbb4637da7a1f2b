// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// The reduction of each operator onto the reduced coordinates y = [u_d; eta] (the ROI dofs, then
/// the static basis' coordinates), with T = [[I, 0], [-X P, Phi]] (P picks the interface):
///   K_r = diag(K_dd - P^T S P, W^2)                          (reduced_stiffness)
///   D_r = T^T D T for a lumped D = M or C of the full model:  (reduced_diagonal_operator)
///         D_dd plus the dense block [[X^T D_s X, -X^T D_s Phi], [sym, Phi^T D_s Phi]] on the
///         interface and eta, or D_dd alone for static condensation (no mass carried)
///   f_r = [f_d - P^T X^T f_s; Phi^T f_s] per load pattern, with K_ss^-1 f_s less its modal part
///         kept for recovering u_s                              (reduce_loads)
/// Each is kept split (sparse part plus dense block) for products.
#include "condensation/static_part_factor.hpp"
#include "model/load_history.hpp"
#include "model/second_order_system.hpp"
#include "model/spectrum.hpp"
#include "roi/roi.hpp"

namespace roifem::condensation {

/// The split matrix assembled: sparse part plus P^T B P.
SparseMatrix assembled(const model::SplitMatrix& A);

model::SplitMatrix reduced_stiffness(const SparseMatrix& K, const roi::Partition& partition, const DenseMatrix& schur,
                                     const Vector& omega);

/// `D_full` diagonal. Without `carries_mass` only D_dd, padded by zeros to the reduced size.
model::SplitMatrix reduced_diagonal_operator(const SparseMatrix& D_full, const roi::Partition& partition, const DenseMatrix& X,
                                             const model::Modes& basis, bool carries_mass);

struct ReducedLoads {
  model::LoadHistory reduced;          ///< f_r, per load term
  model::LoadHistory static_response;  ///< per load term: K_ss^-1 p_s less Phi W^-2 Phi^T p_s
};
ReducedLoads reduce_loads(const model::LoadHistory& load, const roi::Partition& partition, StaticPartFactor& factor,
                          const model::Modes& basis);

}  // namespace roifem::condensation
