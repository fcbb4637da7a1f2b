// SPDX-License-Identifier: GPL-3.0-or-later
#include "integrators/haptic_trapezoid.hpp"

#include <algorithm>
#include <string>

#include "common/errors.hpp"
#include "common/timer.hpp"
#include "model/internal_force.hpp"

namespace roifem::integrators {

namespace {

DirectSolve factor_effective_stiffness(const model::SecondOrderSystem& system, const model::AverageAcceleration& rule) {
  try {
    return {system, rule, Refactor::never};  // a factorization would stall ticks: the loop corrects, always
  } catch (const solvers::NotPositiveDefinite& e) {
    throw SolverError(std::string("haptic trapezoid: K + 2/dt C + 4/dt^2 M is not positive definite: ") + e.what());
  }
}

}  // namespace

HapticTrapezoid::HapticTrapezoid(const model::SecondOrderSystem& system, double dt, HapticNewton newton)
    : system_(system), rule_(dt), K_eff_(factor_effective_stiffness(system, rule_)), newton_(newton) {
  const Index n = system.size();
  a_ = Vector::Zero(n);
  f_.resize(n);
  w_.resize(n);
  u_next_.resize(n);
  work_.resize(n);
  if (system.is_nonlinear()) {
    if (system.internal_force->has_motion())
      throw InputError("the haptic trapezoid holds its tool's nodes as unknowns; this law moves tools of its own (" +
                       system.internal_force->describe() + ")");
    if (newton_.iterations < 1)
      throw InputError("haptic trapezoid: a nonlinear model needs at least one Newton iteration per tick");
    for (Vector* v : {&rhs_, &step_, &excess_used_}) v->resize(n);
    zero_ = Vector::Zero(n);
    excess_ = Vector::Zero(n);
  }
}

void HapticTrapezoid::attach(const std::vector<std::array<Index, 3>>& node_dofs) {
  const Stopwatch clock;
  const Index n = system_.size();
  if (node_dofs.empty()) throw InputError("haptic tool: holds no node");
  if (K_eff_.correction() != nullptr) throw InputError("haptic tool: attach it before the model is cut");
  std::vector<Index> held;
  for (const auto& dofs : node_dofs)
    for (const Index d : dofs) {
      if (d < 0 || d >= n)
        throw InputError("haptic tool: dof " + std::to_string(d) + " is not an unknown of the system (" + std::to_string(n) +
                         " dofs)");
      held.push_back(d);
    }
  std::vector<Index> sorted = held;
  std::sort(sorted.begin(), sorted.end());
  if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) throw InputError("haptic tool: a node is held twice");

  const auto m3 = static_cast<Index>(held.size());
  DenseMatrix Z(n, m3);
  const Vector zero = Vector::Zero(n);
  Vector unit = Vector::Zero(n), column(n);
  for (Index j = 0; j < m3; ++j) {
    unit[held[static_cast<std::size_t>(j)]] = 1.0;
    K_eff_.solve(unit, zero, column);
    Z.col(j) = column;
    unit[held[static_cast<std::size_t>(j)]] = 0.0;
  }
  DenseMatrix W(m3, m3);
  for (Index i = 0; i < m3; ++i) W.row(i) = Z.row(held[static_cast<std::size_t>(i)]);
  W = 0.5 * (W + W.transpose()).eval();  // symmetric to rounding
  Eigen::LLT<DenseMatrix> W_factor(W);
  if (W_factor.info() != Eigen::Success) throw SolverError("haptic tool: its compliance W = H K_eff^-1 H^T is singular");

  // K symmetric: the held dofs' rows are their columns.
  std::vector<Eigen::Triplet<double>> entries;
  for (std::size_t i = 0; i < held.size(); ++i)
    for (SparseMatrix::InnerIterator it(system_.K, held[i]); it; ++it)
      entries.emplace_back(static_cast<Index>(i % 3), it.row(), it.value());
  rows_.resize(3, n);
  rows_.setFromTriplets(entries.begin(), entries.end());
  rows_.makeCompressed();
  is_held_.assign(static_cast<std::size_t>(n), false);
  for (const Index d : held) is_held_[static_cast<std::size_t>(d)] = true;
  held_ = std::move(held);
  Z0_ = std::move(Z);
  W_ = std::move(W);
  W_factor_ = std::move(W_factor);
  gap_.resize(m3);
  attach_s_ = clock.seconds();
}

void HapticTrapezoid::reset(const model::State& initial) {
  if (initial.u.size() != system_.size() || initial.v.size() != system_.size())
    throw Error("internal: haptic trapezoid: state size mismatch");
  t0_ = initial.t;
  k_ = 0;
  a_ = model::AverageAcceleration::consistent_acceleration(system_, initial);
  if (system_.is_nonlinear()) system_.internal_force->excess_force(initial.u, excess_);
}

void HapticTrapezoid::take_change(const model::SystemChange& change, const model::State& state) {
  if (held_.empty()) throw Error("internal: haptic trapezoid: take_change before attach");
  if (system_.is_nonlinear()) throw InputError("haptic tool: cutting a nonlinear model is not built");
  if (!system_.M_split.empty() || system_.M.nonZeros() > system_.size() || !system_.damping.is_mass_proportional())
    throw InputError("haptic tool: a cut needs a lumped (diagonal) mass and C = alpha M");
  for (const Index d : change.dofs)
    if (is_held_[static_cast<std::size_t>(d)])
      throw InputError("haptic tool: the cut reaches dof " + std::to_string(d) +
                       ", which the tool holds: a cut stays clear of the tool's nodes");
  const Stopwatch clock;
  DenseMatrix B = change.effective(rule_.mass_factor(system_.damping));
  K_eff_.update(change.dofs, B);
  compliance_with_changes("after the cut");
  follow_the_change(change, state);
  if (background_) background_->add({change.dofs, std::move(B)});
  change_s_ = clock.seconds();
}

void HapticTrapezoid::compliance_with_changes(const char* after) {
  // Z = K_eff^-1 H^T with the changes = Z_0 - Z_U T, T = the correction's coefficients for Z_0's
  // columns (r x 3m): W = H Z needs Z_U's held rows alone, O(r^2 m) with no n-sized product; a tick
  // applies the rest (constrained_solve).
  const solvers::LowRankUpdate& changes = *K_eff_.correction();
  T_ = changes.coefficients(Z0_);
  Z_U_held_ = changes.rows_of_Z(held_);
  for (std::size_t i = 0; i < held_.size(); ++i) W_.row(static_cast<Index>(i)) = Z0_.row(held_[i]);
  W_.noalias() -= Z_U_held_ * T_;
  W_ = 0.5 * (W_ + W_.transpose()).eval();
  W_factor_.compute(W_);
  if (W_factor_.info() != Eigen::Success) throw SolverError(std::string("haptic tool: its compliance became singular ") + after);
  coefficients_.resize(changes.rank());
}

void HapticTrapezoid::refactor_in_background() {
  if (held_.empty()) throw Error("internal: haptic trapezoid: refactor_in_background before attach");
  if (K_eff_.correction() != nullptr && K_eff_.correction()->rank() > 0)
    throw InputError("haptic tool: start the background refactorization before the model is cut");
  if (background_) return;
  DenseMatrix H_t = DenseMatrix::Zero(system_.size(), static_cast<Index>(held_.size()));
  for (std::size_t j = 0; j < held_.size(); ++j) H_t(held_[j], static_cast<Index>(j)) = 1;
  background_ = std::make_unique<solvers::BackgroundRefactorization>(rule_.effective_stiffness(system_),
                                                                     system_.dense_block_dofs(), std::move(H_t));
}

void HapticTrapezoid::expect_change(std::vector<Index> dofs) {
  if (background_) background_->expect(std::move(dofs));
}

void HapticTrapezoid::wait_for_background() {
  if (background_) swap_in(background_->take_current());
}

void HapticTrapezoid::swap_in(std::unique_ptr<solvers::RefreshedFactor> fresh) {
  if (!fresh) return;
  const Stopwatch clock;
  auto held = K_eff_.adopt(std::move(fresh->factor), std::move(fresh->correction));
  Z0_ = std::move(fresh->base_solution);
  // Changes taken after the worker last read the log (usually none): added here.
  for (const solvers::SymmetricChange& change : background_->changes_since(fresh->taken)) K_eff_.update(change.dofs, change.B);
  compliance_with_changes("with the background's factor");
  background_->retire(std::move(held.first), std::move(held.second));
  ++swaps_;
  swap_s_ = clock.seconds();
}

void HapticTrapezoid::follow_the_change(const model::SystemChange& change, const model::State& s) {
  // Before the change M a + C v + K u = f held at every free dof (the step's equilibrium), C = alpha
  // M. Only the change's dofs see another equation, so only their acceleration changes (the tool's
  // dofs, which a change never reaches, keep the tool's): at dof d, with i its place in the change,
  //   M' a' = f' - alpha M' v - K' u,   (K' u)_d = (K u)_d + (dK u)_i,
  //   (K u)_d = f_d - alpha M_d v_d - M_d a_d   from the old equation (0 at a dof the change starts),
  // an O(r^2) update instead of a product with the whole K (the dense block of a condensed model).
  const auto r = static_cast<Index>(change.dofs.size());
  Vector u(r);
  for (Index i = 0; i < r; ++i) u[i] = s.u[change.dofs[static_cast<std::size_t>(i)]];
  const Vector dK_u = change.stiffness * u;
  const double alpha = system_.damping.alpha;
  const auto& terms = system_.load.terms();  // already changed: the new patterns
  for (Index i = 0; i < r; ++i) {
    const Index d = change.dofs[static_cast<std::size_t>(i)];
    const double m_new = system_.M.coeff(d, d), m_old = m_new - change.mass[i];
    if (std::binary_search(change.held.begin(), change.held.end(), d)) {  // no element, no load: K's row is zero
      a_[d] = -alpha * s.v[d];
      continue;
    }
    double f_new = 0, f_old = 0;
    for (std::size_t k = 0; k < terms.size(); ++k) {
      const double scale = terms[k].ramp.value(s.t), p = terms[k].pattern[d];
      f_new += scale * p;
      f_old += scale * (change.loads[k].size() == r ? p - change.loads[k][i] : p);
    }
    const double K_u = std::binary_search(change.started.begin(), change.started.end(), d)
                           ? 0.0
                           : f_old - alpha * m_old * s.v[d] - m_old * a_[d];
    a_[d] = (f_new - alpha * m_new * s.v[d] - K_u - dK_u[i]) / m_new;
  }
}

Vec3 HapticTrapezoid::tick(const Vec3& g, model::State& s) {
  if (held_.empty()) throw Error("internal: haptic trapezoid: tick before attach");
  if (background_) swap_in(background_->take());
  ++k_;
  s.t = t0_ + static_cast<double>(k_) * rule_.dt();
  system_.load.evaluate(s.t, f_);
  Vec3 load_on_tool = Vec3::Zero();
  for (std::size_t i = 0; i < held_.size(); ++i) load_on_tool[static_cast<Index>(i % 3)] += f_[held_[i]];
  rule_.history(system_, s, a_, f_, w_);
  if (!system_.is_nonlinear()) {
    constrained_solve(f_, w_, g, u_next_);  // the plain step, then the tool's constraint
  } else {
    rhs_ = f_ - excess_;  // the first iteration: g at u_n
    constrained_solve(rhs_, w_, g, u_next_);
    excess_used_ = excess_;
    iterate_nonlinear();
  }
  rule_.advance(s, a_, u_next_, work_);
  Vec3 force = -load_on_tool;
  for (Index c = 0; c < 3; ++c)
    for (decltype(rows_)::InnerIterator it(rows_, c); it; ++it) force[c] += it.value() * s.u[it.col()];
  if (system_.is_nonlinear())
    for (std::size_t i = 0; i < held_.size(); ++i) force[static_cast<Index>(i % 3)] += excess_[held_[i]];
  return force;
}

void HapticTrapezoid::constrained_solve(const Vector& rhs, const Vector& w, const Vec3& g, Vector& u) {
  // With the changes taken by Woodbury's correction (y = K_0^-1 (rhs + M w) with the factored K_eff,
  // c its coefficients: u* = y - Z_U c) and Z = Z_0 - Z_U T (compliance_with_changes):
  //   lambda = W^-1 (H u* - g),   u = u* - Z lambda = y - Z_0 lambda - Z_U (c - T lambda),
  // one n x 3m and one n x r product, as the plain correction and the constraint cost apart.
  K_eff_.solve_base(rhs, w, u);
  const solvers::LowRankUpdate* changes = K_eff_.correction();
  const bool changed = changes != nullptr && changes->rank() > 0;
  for (std::size_t i = 0; i < held_.size(); ++i) gap_[static_cast<Index>(i)] = u[held_[i]] - g[static_cast<Index>(i % 3)];
  if (changed) {
    changes->coefficients(u, coefficients_);
    gap_.noalias() -= Z_U_held_ * coefficients_;
  }
  W_factor_.solveInPlace(gap_);  // lambda
  u.noalias() -= Z0_ * gap_;
  if (changed) {
    coefficients_.noalias() -= T_ * gap_;
    changes->subtract(coefficients_, u);
  }
}

void HapticTrapezoid::iterate_nonlinear() {
  // On the free dofs K_eff u = f + M w - excess_used_ after every solve, so that there
  // R(u) = excess(u) - excess_used_. Its largest free entry is measured against the excess's own:
  // the share of the law's correction to the linear model that the budget leaves unresolved (the
  // free dofs' internal force itself is no scale: near equilibrium K u and g cancel there).
  auto residual = [&] {  // excess_ at u_next_, and the relative residual
    system_.internal_force->excess_force(u_next_, excess_);
    double largest = 0, scale = 0;
    for (Index i = 0; i < excess_.size(); ++i)
      if (!is_held_[static_cast<std::size_t>(i)]) {
        largest = std::max(largest, std::abs(excess_[i] - excess_used_[i]));
        scale = std::max(scale, std::abs(excess_[i]));
      }
    return scale > 0 ? largest / scale : 0.0;
  };
  last_iterations_ = 1;
  last_residual_ = residual();
  while (last_iterations_ < newton_.iterations && !(newton_.tolerance > 0 && last_residual_ <= newton_.tolerance)) {
    rhs_ = excess_used_ - excess_;                        // -R
    constrained_solve(rhs_, zero_, Vec3::Zero(), step_);  // H d = 0: the held dofs stay where the tool put them
    u_next_ += step_;
    excess_used_ = excess_;
    ++last_iterations_;
    last_residual_ = residual();
  }
}

}  // namespace roifem::integrators
