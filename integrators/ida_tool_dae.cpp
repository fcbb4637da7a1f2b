// SPDX-License-Identifier: GPL-3.0-or-later
#include "integrators/ida_tool_dae.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

#include "common/did_you_mean.hpp"
#include "common/errors.hpp"
#include "common/number_text.hpp"
#include "integrators/block_matrix.hpp"
#include "model/internal_force.hpp"
#include "model/mass_inverse.hpp"

namespace roifem::integrators {

namespace {

/// Steps IDA may take between two outputs before it gives up (IDA_TOO_MUCH_WORK): the stable
/// forms take a few hundred on the tests' models, index 3 can grind on at ever smaller steps.
constexpr long max_steps_per_output = 20000;

constexpr std::array<std::pair<ToolFormulation, std::string_view>, 3> formulation_names{
    {{ToolFormulation::index3, "index3"}, {ToolFormulation::ggl, "ggl"}, {ToolFormulation::index1, "index1"}}};

}  // namespace

std::string_view formulation_name(ToolFormulation f) {
  for (const auto& [value, name] : formulation_names)
    if (value == f) return name;
  throw Error("internal: a tool formulation without a name");
}

ToolFormulation parse_formulation(std::string_view name) {
  std::vector<std::string> names;
  for (const auto& [value, known] : formulation_names) {
    if (known == name) return value;
    names.emplace_back(known);
  }
  throw InputError("unknown tool formulation '" + std::string(name) + "'" + did_you_mean(name, names) +
                   ": use index3, ggl or index1");
}

IdaToolDae::IdaToolDae(const model::SecondOrderSystem& all, const std::vector<model::ToolDofs>& tools,
                       ToolFormulation formulation, StepControl control, double baumgarte_rate)
    : all_(all), formulation_(formulation), control_(control), a_(baumgarte_rate) {
  std::vector<Eigen::Triplet<double>> sums;
  for (std::size_t a = 0; a < tools.size(); ++a) {
    tools_.push_back(tools[a].tool);
    for (std::size_t k = 0; k < tools[a].dofs.size(); ++k) {
      sums.emplace_back(3 * static_cast<Index>(a) + static_cast<Index>(k % 3), static_cast<Index>(tool_dofs_.size()), 1.0);
      tool_dofs_.push_back(tools[a].dofs[k]);
      tool_component_.push_back(static_cast<int>(k % 3));
      tool_of_dof_.push_back(static_cast<Index>(a));
    }
  }
  if (tool_dofs_.empty()) throw Error("internal: IDA tool DAE without tools");
  // The tools' nodes' own inertia moves with them: M and C must not couple their dofs to others
  // (lumped there; a Guyan or Craig-Bampton mass couples only the interface and modal coordinates).
  for (const Index dof : tool_dofs_)
    for (const SparseMatrix* A : {&all.M, &all.C})
      for (SparseMatrix::InnerIterator it(*A, dof); it; ++it)
        if (it.row() != dof && it.value() != 0.0)
          throw ModelError("IDA tool DAE: M or C couples a tool's dof to another (it must be lumped at the tools' nodes)");
  mass_inverse_ = std::make_unique<model::MassInverse>(all.M);
  H_ = model::selection_matrix(tool_dofs_, n());
  Ht_ = H_.transpose();
  S_ = SparseMatrix(3 * static_cast<Index>(tools.size()), p());
  S_.setFromTriplets(sums.begin(), sums.end());
  I_ = model::diagonal_matrix(Vector::Ones(n()));
  sizes_ = {n(), n(), p()};
  if (formulation_ == ToolFormulation::ggl) sizes_.push_back(p());
  const SparseMatrix dyp_alone = assemble_blocks(sizes_, dF_dyp_blocks());
  dF_dy_ = assemble_blocks(sizes_, dF_dy_blocks(all.K), &dyp_alone);
  dF_dyp_ = assemble_blocks(sizes_, dF_dyp_blocks(), &dF_dy_);
  if (dF_dy_.nonZeros() != dF_dyp_.nonZeros()) throw Error("internal: IDA tool DAE Jacobian patterns differ");
  f_.resize(n());
  if (all.is_nonlinear()) {
    if (all.internal_force->has_motion()) throw Error("internal: IDA tool DAE: the law moves tools of its own");
    u_.resize(n());
    f_int_.resize(n());
    K_t_ = all.K;
  }
}

std::vector<Block> IdaToolDae::dF_dy_blocks(const SparseMatrix& K) const {
  std::vector<Block> dy{{0, 1, &I_, -1.0}, {1, 0, &K}, {1, 1, &all_.C}, {1, 2, &Ht_, -1.0}};
  if (formulation_ == ToolFormulation::index1) {
    dy.push_back({2, 0, &H_, a_ * a_});
    dy.push_back({2, 1, &H_, 2 * a_});
  } else {
    dy.push_back({2, 0, &H_});
  }
  if (formulation_ == ToolFormulation::ggl) {
    dy.push_back({0, 3, &Ht_, -1.0});
    dy.push_back({3, 1, &H_});
  }
  return dy;
}

std::vector<Block> IdaToolDae::dF_dyp_blocks() const {
  std::vector<Block> dyp{{0, 0, &I_}, {1, 1, &all_.M}};
  if (formulation_ == ToolFormulation::index1) dyp.push_back({2, 1, &H_});
  return dyp;
}

void IdaToolDae::update_dF_dy(double t, const Eigen::Ref<const Vector>& y) {
  u_ = y.head(n());
  all_.internal_force->force_and_tangent(t, u_, f_int_, K_t_);
  dF_dy_ = assemble_blocks(sizes_, dF_dy_blocks(K_t_), &dF_dyp_);  // the union of both patterns, as before
}

void IdaToolDae::add_internal_force(double t, const Eigen::Ref<const Vector>& u, Eigen::Ref<Vector> r) {
  if (!all_.is_nonlinear()) {
    r.noalias() += all_.K * u;
    return;
  }
  u_ = u;
  all_.internal_force->force(t, u_, f_int_);
  r += f_int_;
}

Vector IdaToolDae::path(double t, int derivative) const {
  Vector G(p());
  for (Index i = 0; i < p(); ++i) {
    const model::ToolPath& path = tools_[static_cast<std::size_t>(tool_of_dof_[static_cast<std::size_t>(i)])].path;
    const Vec3 g = derivative == 0 ? path.at(t) : derivative == 1 ? path.velocity(t) : path.acceleration(t);
    G[i] = g[tool_component_[static_cast<std::size_t>(i)]];
  }
  return G;
}

void IdaToolDae::residual(double t, const Eigen::Ref<const Vector>& y, const Eigen::Ref<const Vector>& yp, Eigen::Ref<Vector> r) {
  const Index n = this->n(), p = this->p();
  all_.load.evaluate(t, f_);
  const auto u = y.head(n), v = y.segment(n, n), lambda = y.segment(2 * n, p);
  r.head(n) = yp.head(n) - v;
  r.segment(n, n).noalias() = all_.M * yp.segment(n, n) + all_.C * v - Ht_ * lambda;
  add_internal_force(t, u, r.segment(n, n));
  r.segment(n, n) -= f_;
  switch (formulation_) {
    case ToolFormulation::index3:
      r.segment(2 * n, p) = H_ * u - path(t, 0);
      break;
    case ToolFormulation::ggl:
      r.head(n) -= Ht_ * y.segment(2 * n + p, p);
      r.segment(2 * n, p) = H_ * u - path(t, 0);
      r.segment(2 * n + p, p) = H_ * v - path(t, 1);
      break;
    case ToolFormulation::index1:
      r.segment(2 * n, p) = H_ * yp.segment(n, n) - path(t, 2) + 2 * a_ * (H_ * v - path(t, 1)) + a_ * a_ * (H_ * u - path(t, 0));
      break;
  }
}

void IdaToolDae::make_consistent(double t, const Vector& u_in, const Vector& v_in) {
  const Index n = this->n(), p = this->p();
  Vector u = u_in, v = v_in;
  const Vector G = path(t, 0), dG = path(t, 1), ddG = path(t, 2);
  for (Index i = 0; i < p; ++i) {
    u[tool_dofs_[static_cast<std::size_t>(i)]] = G[i];
    v[tool_dofs_[static_cast<std::size_t>(i)]] = dG[i];
  }
  all_.load.evaluate(t, f_);
  Vector internal = Vector::Zero(n);
  add_internal_force(t, u, internal);
  const Vector rest = f_ - all_.C * v - internal;  // M a = rest + H^T lambda
  Vector a(n);
  mass_inverse_->apply(rest, a);  // M is block diagonal between the tools' dofs and the rest
  for (Index i = 0; i < p; ++i) a[tool_dofs_[static_cast<std::size_t>(i)]] = ddG[i];
  const Vector lambda = H_ * (all_.M * a - rest);
  auto y = ida_->y(), yp = ida_->yp();
  y.setZero();
  yp.setZero();
  y.head(n) = u;
  y.segment(n, n) = v;
  y.segment(2 * n, p) = lambda;
  yp.head(n) = v;
  yp.segment(n, n) = a;
}

void IdaToolDae::reset(double t0) {
  const Index size = 2 * n() + (formulation_ == ToolFormulation::ggl ? 2 : 1) * p();
  t_ = t0;
  Vector differential = Vector::Zero(size);
  differential.head(2 * n()).setOnes();  // u, v differential; the multipliers algebraic
  // Index 3: the tools' velocities are index-2 variables, kept out of the error test too.
  if (formulation_ == ToolFormulation::index3)
    for (const Index i : tool_dofs_) differential[n() + i] = 0;
  ida_.reset();
  ida_ = std::make_unique<sundials::IdaSolver>(
      sundials::IdaSolver::Settings{
          .name = "IDA tool DAE (" + std::string(formulation_name(formulation_)) + ")",
          .rtol = control_.rtol,
          .atol = control_.atol,
          .max_order = 5,
          .max_steps = max_steps_per_output,
          .differential = std::move(differential),
          .suppress_algebraic = true,
          .update_dF_dy = all_.is_nonlinear()
                              ? std::function([this](double t, const Eigen::Ref<const Vector>& y) { update_dF_dy(t, y); })
                              : nullptr},
      [this](double t, const auto& y, const auto& yp, auto r) { residual(t, y, yp, r); }, dF_dy_, dF_dyp_);
  make_consistent(t0, Vector::Zero(n()), Vector::Zero(n()));
  ida_->start(t0);
  kinks_ = kinks_after(t0);
  next_kink_ = 0;
}

std::vector<double> IdaToolDae::kinks_after(double t) const {
  std::vector<double> kinks;
  auto add = [&](const std::vector<double>& more) { kinks.insert(kinks.end(), more.begin(), more.end()); };
  for (const auto& tool : tools_) add(tool.path.kinks_after(t));
  for (const auto& term : all_.load.terms()) add(term.ramp.kinks_after(t));
  std::sort(kinks.begin(), kinks.end());
  kinks.erase(std::unique(kinks.begin(), kinks.end()), kinks.end());
  return kinks;
}

void IdaToolDae::advance_to(double t_out) {
  if (!ida_) throw Error("internal: IDA tool DAE: advance_to before reset");
  while (t_ < t_out) {
    while (next_kink_ < kinks_.size() && kinks_[next_kink_] <= t_) ++next_kink_;
    const bool to_kink = next_kink_ < kinks_.size() && kinks_[next_kink_] <= t_out;
    const double target = to_kink ? kinks_[next_kink_] : t_out;
    t_ = ida_->advance_to(target);
    if (to_kink) {  // the path's velocity jumps: restart from consistent values past the kink
      t_ = target;
      make_consistent(t_, displacement(), velocity());
      ida_->start(t_);
    }
  }
}

Vector IdaToolDae::displacement() const { return ida_->y().head(n()); }
Vector IdaToolDae::velocity() const { return ida_->y().segment(n(), n()); }
Vector IdaToolDae::multipliers() const { return ida_->y().segment(2 * n(), p()); }

Vector IdaToolDae::tool_forces() const {
  const Vector own = H_ * (all_.M * (Ht_ * path(t_, 2)) + all_.C * (Ht_ * path(t_, 1)));  // the nodes' inertia
  return S_ * (multipliers() - own);
}

double IdaToolDae::position_drift() const { return (H_ * displacement() - path(t_, 0)).cwiseAbs().maxCoeff(); }
double IdaToolDae::velocity_drift() const { return (H_ * velocity() - path(t_, 1)).cwiseAbs().maxCoeff(); }

Stats IdaToolDae::stats() const {
  if (!ida_) return {};
  Stats s = ida_->stats();
  if (all_.is_nonlinear()) s.nonlinear_iterations = s.lin_solves;  // one linear solve per Newton iteration
  return s;
}

}  // namespace roifem::integrators
