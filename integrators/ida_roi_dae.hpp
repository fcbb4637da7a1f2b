// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// The ROI model without condensation, integrated by IDA as a DAE: ROI dofs are differential,
/// static dofs algebraic. With y = [u_d; v_d; u_s]:
///   u_d' - v_d                                   = 0
///   M_dd v_d' + C_dd v_d + K_dd u_d + K_ds u_s - f_d(t) = 0
///   K_sd u_d + K_ss u_s - f_s(t)                 = 0      (algebraic: IDASetId marks it 0)
/// Consistent initial values come from IDACalcIC (IDA_YA_YDP_INIT). Its ROI trajectory is the
/// condensed model's, to the integrator's tolerance: the condensation eliminates exactly u_s.
/// Newton matrix dF/dy + c_j dF/dy' assembled sparse, factored by KLU (AMD ordering).
#include <memory>

#include "integrators/integrator.hpp"
#include "integrators/step_control.hpp"
#include "integrators/sundials/ida_solver.hpp"
#include "model/internal_force.hpp"
#include "roi/roi.hpp"

namespace roifem::integrators {

class IdaRoiDae {
 public:
  /// `full`: the whole model over all free dofs; `partition`: its ROI split. `law`: a hybrid ROI's
  /// law over full's dofs (model::hybrid_law_uncondensed), f_int(t, u) in place of K u, its
  /// tangent in place of K in the Newton matrix (IDA's setup policy rebuilding it); null: linear.
  IdaRoiDae(const model::SecondOrderSystem& full, const roi::Partition& partition, StepControl control, int max_order = 5,
            std::shared_ptr<const model::InternalForce> law = nullptr);
  IdaRoiDae(const IdaRoiDae&) = delete;
  IdaRoiDae& operator=(const IdaRoiDae&) = delete;

  /// Starts at rest at t0 (u_d = v_d = 0); IDACalcIC makes u_s and the derivatives consistent.
  void reset(double t0);
  /// Advances to t_out; u_d (ROI) and u_s (static part) on return.
  void advance_to(double t_out, Vector& u_d, Vector& u_s);
  /// v_d (ROI) at the last advance_to: a view of IDA's own vector, copied by the caller into its
  /// storage (returning a Vector by value let `state.v = ...` move-assign, swapping the caller's
  /// buffer away: issue 54).
  Eigen::Map<const Vector> velocity_d() const;
  double t() const { return t_; }
  Stats stats() const;

 private:
  void residual(double t, const Eigen::Ref<const Vector>& y, const Eigen::Ref<const Vector>& yp, Eigen::Ref<Vector> r);
  /// dF/dy from the stiffness blocks.
  SparseMatrix dF_dy(const SparseMatrix* pattern_of) const;
  /// u over full's dofs from y's u_d and u_s.
  void gather_full(const Eigen::Ref<const Vector>& y);
  /// The law's Newton matrix at y: its tangent's blocks in place of K's.
  void update_dF_dy(double t, const Eigen::Ref<const Vector>& y);

  const model::SecondOrderSystem& full_;
  roi::Partition partition_;
  StepControl control_;
  int max_order_;
  SparseMatrix M_dd_, C_dd_, K_dd_, K_ds_, K_sd_, K_ss_;
  model::LoadHistory load_d_, load_s_;
  SparseMatrix dF_dy_, dF_dyp_;
  Vector f_d_, f_s_;
  std::shared_ptr<const model::InternalForce> law_;
  Vector u_, f_int_;  ///< the law's: over full's dofs
  SparseMatrix K_t_;
  std::unique_ptr<sundials::IdaSolver> ida_;  ///< after the matrices it refers to
  double t_ = 0;
};

}  // namespace roifem::integrators
