// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// SUNDIALS IDA (variable-order, variable-step BDF) on the residual form of the second-order system
///   F(t, y, y') = [u' - v;  M v' + C v + K u - f(t)] = 0,   y = [u; v],
/// with the Newton matrix dF/dy + c_j dF/dy' = [[c_j I, -I], [K, c_j M + C]] assembled as a sparse
/// matrix and factored by KLU (AMD ordering). BDF orders 1-5 (`max_order` 5), or capped at 2,
/// the highest A-stable BDF. IDA has no fixed-step mode: it is always error-controlled.
/// A nonlinear system (model/internal_force.hpp): f_int(u) replaces K u in F, and the tangent
/// K_t(u) replaces K in dF/dy whenever IDA's modified Newton rebuilds its matrix (KLU refactors on
/// its first analysis).
#include <memory>
#include <string>
#include <vector>

#include "integrators/integrator.hpp"
#include "integrators/integrator_info.hpp"
#include "integrators/step_control.hpp"
#include "integrators/sundials/ida_solver.hpp"

namespace roifem::integrators {

/// The factory's maker for the table's IDA rows (method_id: the maximum BDF order).
std::unique_ptr<Integrator> make_ida(const IntegratorInfo& info, const StepControl& control);
/// The table's rows of this method: ida-bdf5, ida-bdf2.
std::vector<IntegratorInfo> ida_rows();

class Ida final : public Integrator {
 public:
  Ida(std::string name, int max_order, StepControl control);
  std::string_view name() const override { return name_; }
  Stats stats() const override;
  bool takes_nonlinear() const override { return true; }

 private:
  void prepare(const model::SecondOrderSystem& system, const model::State& initial) override;
  void advance(double t_out, model::State& state) override;
  /// F = [u' - v; M v' + C v + K u - f(t)] (f_int(u) in place of K u on a nonlinear system).
  void residual(double t, const Eigen::Ref<const Vector>& y, const Eigen::Ref<const Vector>& yp, Eigen::Ref<Vector> r);
  /// dF/dy = [[0, -I], [K, C]] with K the stiffness at u: the system's, or the tangent K_t(u).
  SparseMatrix dF_dy(const SparseMatrix& K, const SparseMatrix* pattern_of) const;
  /// dF/dy at (t, y's u) on a nonlinear system (IdaSolver::Settings::update_dF_dy).
  void update_dF_dy(double t, const Eigen::Ref<const Vector>& y);

  std::string name_;
  int max_order_;
  StepControl control_;
  const model::SecondOrderSystem* system_ = nullptr;
  SparseMatrix dF_dy_, dF_dyp_;  ///< same pattern (union), so J = dF_dy + c_j dF_dyp keeps it
  Vector force_;
  Vector u_, f_int_;                          ///< a nonlinear system's u and f_int(u)
  SparseMatrix K_t_;                          ///< its tangent, in K's pattern
  std::unique_ptr<sundials::IdaSolver> ida_;  ///< after the matrices it refers to
};

}  // namespace roifem::integrators
