// SPDX-License-Identifier: GPL-3.0-or-later
#include "integrators/ida_roi_dae.hpp"

#include <utility>

#include "common/errors.hpp"
#include "integrators/block_matrix.hpp"

namespace roifem::integrators {

IdaRoiDae::IdaRoiDae(const model::SecondOrderSystem& full, const roi::Partition& partition, StepControl control, int max_order,
                     std::shared_ptr<const model::InternalForce> law)
    : full_(full), partition_(partition), control_(control), max_order_(max_order), law_(std::move(law)) {
  const auto& d = partition_.d;
  const auto& s = partition_.s;
  if (d.empty()) throw ModelError("IDA ROI DAE: the ROI has no free dof");
  M_dd_ = roi::submatrix(full.M, d, d);
  C_dd_ = roi::submatrix(full.C, d, d);
  K_dd_ = roi::submatrix(full.K, d, d);
  K_ds_ = roi::submatrix(full.K, d, s);
  K_sd_ = roi::submatrix(full.K, s, d);
  K_ss_ = roi::submatrix(full.K, s, s);
  load_d_ = full.load.mapped(static_cast<Index>(d.size()), [&](const Vector& p) { return roi::gather(p, d); });
  load_s_ = full.load.mapped(static_cast<Index>(s.size()), [&](const Vector& p) { return roi::gather(p, s); });
  const Index nd = static_cast<Index>(d.size()), ns = static_cast<Index>(s.size());
  const std::vector<Index> sizes{nd, nd, ns};
  const SparseMatrix I = model::diagonal_matrix(Vector::Ones(nd));
  // y' enters only the first two row blocks: [I, 0, 0; 0, M_dd, 0; 0, 0, 0].
  const SparseMatrix dyp = assemble_blocks(sizes, {{0, 0, &I}, {1, 1, &M_dd_}});
  dF_dy_ = dF_dy(&dyp);
  dF_dyp_ = assemble_blocks(sizes, {{0, 0, &I}, {1, 1, &M_dd_}}, &dF_dy_);
  if (dF_dy_.nonZeros() != dF_dyp_.nonZeros()) throw Error("internal: IDA DAE Jacobian patterns differ");
  f_d_.resize(nd);
  f_s_.resize(ns);
  if (law_) {
    u_ = Vector::Zero(full.size());
    f_int_.resize(full.size());
    K_t_ = full.K;
  }
}

SparseMatrix IdaRoiDae::dF_dy(const SparseMatrix* pattern_of) const {
  const Index nd = K_dd_.rows(), ns = K_ss_.rows();
  const SparseMatrix I = model::diagonal_matrix(Vector::Ones(nd));
  return assemble_blocks({nd, nd, ns},
                         {{0, 1, &I, -1.0}, {1, 0, &K_dd_}, {1, 1, &C_dd_}, {1, 2, &K_ds_}, {2, 0, &K_sd_}, {2, 2, &K_ss_}},
                         pattern_of);
}

void IdaRoiDae::gather_full(const Eigen::Ref<const Vector>& y) {
  const Index nd = K_dd_.rows(), ns = K_ss_.rows();
  for (Index i = 0; i < nd; ++i) u_[partition_.d[static_cast<std::size_t>(i)]] = y[i];
  for (Index i = 0; i < ns; ++i) u_[partition_.s[static_cast<std::size_t>(i)]] = y[2 * nd + i];
}

void IdaRoiDae::update_dF_dy(double t, const Eigen::Ref<const Vector>& y) {
  gather_full(y);
  law_->force_and_tangent(t, u_, f_int_, K_t_);
  const auto& d = partition_.d;
  const auto& s = partition_.s;
  K_dd_ = roi::submatrix(K_t_, d, d);
  K_ds_ = roi::submatrix(K_t_, d, s);
  K_sd_ = roi::submatrix(K_t_, s, d);
  K_ss_ = roi::submatrix(K_t_, s, s);
  dF_dy_ = dF_dy(&dF_dyp_);  // dF/dy''s pattern already holds dF/dy's: the union is unchanged
}

void IdaRoiDae::residual(double t, const Eigen::Ref<const Vector>& y, const Eigen::Ref<const Vector>& yp, Eigen::Ref<Vector> r) {
  const Index nd = K_dd_.rows(), ns = K_ss_.rows();
  load_d_.evaluate(t, f_d_);
  load_s_.evaluate(t, f_s_);
  const auto u_d = y.head(nd), v_d = y.segment(nd, nd), u_s = y.tail(ns);
  r.head(nd) = yp.head(nd) - v_d;
  r.segment(nd, nd).noalias() = M_dd_ * yp.segment(nd, nd) + C_dd_ * v_d;
  if (law_) {  // K's blocks hold the last tangent: the force comes from the law
    gather_full(y);
    law_->force(t, u_, f_int_);
    r.segment(nd, nd) += roi::gather(f_int_, partition_.d);
    r.tail(ns) = roi::gather(f_int_, partition_.s);
  } else {
    r.segment(nd, nd).noalias() += K_dd_ * u_d + K_ds_ * u_s;
    r.tail(ns).noalias() = K_sd_ * u_d + K_ss_ * u_s;
  }
  r.segment(nd, nd) -= f_d_;
  r.tail(ns) -= f_s_;
}

void IdaRoiDae::reset(double t0) {
  const Index nd = K_dd_.rows(), ns = K_ss_.rows();
  t_ = t0;
  Vector differential(2 * nd + ns);
  differential.head(2 * nd).setOnes();  // differential: u_d, v_d
  differential.tail(ns).setZero();      // algebraic: u_s
  ida_.reset();
  ida_ = std::make_unique<sundials::IdaSolver>(
      sundials::IdaSolver::Settings{
          .name = "IDA ROI DAE",
          .rtol = control_.rtol,
          .atol = control_.atol,
          .max_order = max_order_,
          .differential = std::move(differential),
          .update_dF_dy =
              law_ ? std::function([this](double t, const Eigen::Ref<const Vector>& y) { update_dF_dy(t, y); }) : nullptr},
      [this](double t, const auto& y, const auto& yp, auto r) { residual(t, y, yp, r); }, dF_dy_, dF_dyp_);
  ida_->start(t0);  // at rest: y = y' = 0
  ida_->make_consistent(t0 + control_.dt);
}

void IdaRoiDae::advance_to(double t_out, Vector& u_d, Vector& u_s) {
  if (!ida_) throw Error("internal: IDA ROI DAE: advance_to before reset");
  t_ = ida_->advance_to(t_out);
  const Index nd = K_dd_.rows(), ns = K_ss_.rows();
  const auto y = ida_->y();
  u_d = y.head(nd);
  u_s = y.tail(ns);
}

Eigen::Map<const Vector> IdaRoiDae::velocity_d() const {
  const Index nd = K_dd_.rows();
  return {ida_->y().data() + nd, nd};
}

Stats IdaRoiDae::stats() const {
  if (!ida_) return {};
  Stats st = ida_->stats();
  if (law_) st.nonlinear_iterations = st.lin_solves;  // one linear solve per Newton iteration
  return st;
}

}  // namespace roifem::integrators
