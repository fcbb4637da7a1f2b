// SPDX-License-Identifier: GPL-3.0-or-later
#include "integrators/ida.hpp"

#include <utility>

#include "common/errors.hpp"
#include "integrators/block_matrix.hpp"
#include "integrators/integrator_info.hpp"
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
  system_->apply_stiffness(y.head(n), r.tail(n));
  r.tail(n).noalias() += system_->M * yp.tail(n) + system_->C * y.tail(n) - force_;
}

void Ida::prepare(const model::SecondOrderSystem& system, const model::State& initial) {
  ida_.reset();  // before the matrices it refers to
  system_ = &system;
  const Index n = system.size();
  force_.resize(n);
  const SparseMatrix I = model::diagonal_matrix(Vector::Ones(n));
  const std::vector<Index> sizes{n, n};
  const SparseMatrix dyp = assemble_blocks(sizes, {{0, 0, &I}, {1, 1, &system.M}});
  dF_dy_ = assemble_blocks(sizes, {{0, 1, &I, -1.0}, {1, 0, &system.K}, {1, 1, &system.C}}, &dyp);
  dF_dyp_ = assemble_blocks(sizes, {{0, 0, &I}, {1, 1, &system.M}}, &dF_dy_);
  ida_ = std::make_unique<sundials::IdaSolver>(
      sundials::IdaSolver::Settings{.name = name_, .rtol = control_.rtol, .atol = control_.atol, .max_order = max_order_},
      [this](double t, const auto& y, const auto& yp, auto r) { residual(t, y, yp, r); }, dF_dy_, dF_dyp_);
  // Consistent initial values: y' = [v; M^-1 (f - C v - K u)].
  auto y = ida_->y(), yp = ida_->yp();
  y.head(n) = initial.u;
  y.tail(n) = initial.v;
  solvers::Cholesky mass;
  mass.compute(system.M);
  yp.head(n) = initial.v;
  yp.tail(n) = mass.solve(system.load.at(initial.t) - system.C * initial.v - system.K * initial.u);
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
                          .summary = summary};
  };
  return {row("ida-bdf5", 5, "IDA, variable-order BDF 1-5 on the residual form, KLU"),
          row("ida-bdf2", 2, "IDA with BDF capped at order 2 (A-stable)")};
}

}  // namespace roifem::integrators
