#pragma once
/// Static condensation of the static part onto the ROI (Bro-Nielsen; Hansen & Larsen 1998):
///   K~ = K_dd - K_ds K_ss^-1 K_sd,   f~(t) = f_d(t) - K_ds K_ss^-1 f_s(t),
///   u_s = K_ss^-1 (f_s - K_sd u_d)    (the static part follows the ROI instantly).
/// K_ss is factored once; only the interface columns are solved for:
///   X = K_ss^-1 K_sI (dense, #s x #I), S = K_sI^T X (dense, #I x #I),
/// so that K~ = K_dd - S on the interface block, f~ pattern = f_d - X^T f_s, u_s = z(t) - X u_I
/// with z(t) = sum_k r_k(t) K_ss^-1 p_k,s precomputed per load pattern. The condensed system keeps
/// K~ both assembled (for factorizations) and split as K_dd plus the dense block -S (for products). M and C of the ROI are
/// kept as they are (the static part has no inertia in this reduction).
#include "fem/dof_map.hpp"
#include "model/second_order_system.hpp"
#include "roi/roi.hpp"

namespace roifem::condensation {

struct CondensationTimings {
  double factorization_s = 0, interface_solve_s = 0, assembly_s = 0;
};

class StaticCondensation {
 public:
  /// Throws ModelError when K_ss is singular (a static piece held by no fixed node), naming the node.
  StaticCondensation(const model::SecondOrderSystem& full, const roi::Partition& partition, const fem::DofMap& dofs);

  /// The condensed system on the ROI dofs d.
  const model::SecondOrderSystem& system() const { return reduced_; }
  const roi::Partition& partition() const { return partition_; }
  /// u over all free dofs from the ROI's u_d at time t (u_s recovered).
  Vector expand(const Vector& u_d, double t) const;
  /// u_s alone.
  Vector recover_static(const Vector& u_d, double t) const;
  /// K_ds K_ss^-1 K_sd: the interface block subtracted from K_dd.
  const DenseMatrix& interface_schur() const { return schur_; }
  const CondensationTimings& timings() const { return timings_; }

 private:
  roi::Partition partition_;
  model::SecondOrderSystem reduced_;
  DenseMatrix X_;       ///< K_ss^-1 K_sI
  DenseMatrix schur_;   ///< K_sI^T X
  model::LoadHistory static_response_;  ///< K_ss^-1 p_k,s per load term
  CondensationTimings timings_;
};

}  // namespace roifem::condensation
