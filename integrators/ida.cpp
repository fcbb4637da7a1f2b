// SPDX-License-Identifier: GPL-3.0-or-later
#include "integrators/ida.hpp"

#include <utility>

#include "common/errors.hpp"
#include "integrators/block_matrix.hpp"
#include "integrators/integrator_info.hpp"
#include "model/internal_force.hpp"
#include "solvers/cholesky.hpp"

namespace roifem::integrators {

std::unique_ptr<Integrator> make_ida(const IntegratorInfo& info, const StepControl& control) {
  return std::make_unique<Ida>(info.name, info.method_id, control);
}

Ida::Ida(std::string name, int max_order, StepControl control)
    : name_(std::move(name)), max_order_(max_order), control_(control) {
  if (!(control_.rtol > 0 && control_.atol > 0)) throw InputError(name_ + ": tolerances rtol and atol must be positive");
}

void Ida::residual(double t, const Eigen::Ref<const Vector>& y, const Eigen::Ref<const Vector>& yp, Eigen::Ref<Vector> r) {
  const Index n = system_->size();
  system_->load.evaluate(t, force_);
  r.head(n) = yp.head(n) - y.tail(n);
  if (system_->internal_force) {
    u_ = y.head(n);
    system_->internal_force->force(t, u_, f_int_);
    r.tail(n) = f_int_;
  } else {
    system_->apply_stiffness(y.head(n), r.tail(n));
  }
  r.tail(n).noalias() += system_->M * yp.tail(n) + system_->C * y.tail(n) - force_;
}

SparseMatrix Ida::dF_dy(const SparseMatrix& K, const SparseMatrix* pattern_of) const {
  const Index n = system_->size();
  const SparseMatrix I = model::diagonal_matrix(Vector::Ones(n));
  return assemble_blocks({n, n}, {{0, 1, &I, -1.0}, {1, 0, &K}, {1, 1, &system_->C}}, pattern_of);
}

void Ida::update_dF_dy(double t, const Eigen::Ref<const Vector>& y) {
  u_ = y.head(system_->size());
  system_->internal_force->force_and_tangent(t, u_, f_int_, K_t_);
  dF_dy_ = dF_dy(K_t_, &dF_dyp_);  // dF/dy''s pattern already holds dF/dy's: the union is unchanged
}

Stats Ida::stats() const {
  if (!ida_) return {};
  Stats s = ida_->stats();
  if (system_->is_nonlinear()) s.nonlinear_iterations = s.lin_solves;  // one linear solve per Newton iteration
  return s;
}

void Ida::prepare(const model::SecondOrderSystem& system, const model::State& initial) {
  ida_.reset();  // before the matrices it refers to
  system_ = &system;
  const Index n = system.size();
  force_.resize(n);
  const SparseMatrix I = model::diagonal_matrix(Vector::Ones(n));
  const std::vector<Index> sizes{n, n};
  const SparseMatrix dyp = assemble_blocks(sizes, {{0, 0, &I}, {1, 1, &system.M}});
  dF_dy_ = dF_dy(system.K, &dyp);
  dF_dyp_ = assemble_blocks(sizes, {{0, 0, &I}, {1, 1, &system.M}}, &dF_dy_);
  sundials::IdaSolver::Settings settings{.name = name_, .rtol = control_.rtol, .atol = control_.atol, .max_order = max_order_};
  if (system.is_nonlinear()) {
    u_.resize(n);
    f_int_.resize(n);
    K_t_ = system.K;
    settings.update_dF_dy = [this](double t, const Eigen::Ref<const Vector>& y) { update_dF_dy(t, y); };
  }
  ida_ = std::make_unique<sundials::IdaSolver>(
      std::move(settings), [this](double t, const auto& y, const auto& yp, auto r) { residual(t, y, yp, r); }, dF_dy_, dF_dyp_);
  // Consistent initial values: y' = [v; M^-1 (f - C v - K u)].
  auto y = ida_->y(), yp = ida_->yp();
  y.head(n) = initial.u;
  y.tail(n) = initial.v;
  solvers::Cholesky mass;
  mass.compute(system.M);
  yp.head(n) = initial.v;
  Vector internal = system.K * initial.u;
  if (system.internal_force) system.internal_force->force(initial.t, initial.u, internal);
  yp.tail(n) = mass.solve(system.load.at(initial.t) - system.C * initial.v - internal);
  ida_->start(initial.t);
}

void Ida::advance(double t_out, model::State& state) {
  const double t_reached = ida_->advance_to(t_out);
  const Index n = system_->size();
  const auto y = ida_->y();
  state.t = t_reached;
  state.u = y.head(n);
  state.v = y.tail(n);
}

std::vector<IntegratorInfo> ida_rows() {
  auto row = [](const char* name, int max_order, const char* summary) {
    return IntegratorInfo{.name = name,
                          .family = Family::ida,
                          .order = max_order,
                          .adaptive = true,
                          .linear_solver = LinearSolver::klu,
                          .method_id = max_order,
                          .make = make_ida,
                          .summary = summary,
                          .nonlinear = true};
  };
  return {row("ida-bdf5", 5, "IDA, variable-order BDF 1-5 on the residual form, KLU"),
          row("ida-bdf2", 2, "IDA with BDF capped at order 2 (A-stable)")};
}

}  // namespace roifem::integrators
