#include "integrators/ida_tool_dae.hpp"

#include <ida/ida.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

#include "common/did_you_mean.hpp"
#include "common/errors.hpp"
#include "common/number_text.hpp"
#include "integrators/block_matrix.hpp"
#include "integrators/callback_guard.hpp"
#include "integrators/sundials/ida_support.hpp"
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
    : all_(all), formulation_(formulation), control_(control), a_(baumgarte_rate), context_(sundials::make_context()) {
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
  const SparseMatrix I = model::diagonal_matrix(Vector::Ones(n()));
  const bool ggl = formulation_ == ToolFormulation::ggl, index1 = formulation_ == ToolFormulation::index1;
  std::vector<Index> sizes{n(), n(), p()};
  if (ggl) sizes.push_back(p());
  std::vector<Block> dyp{{0, 0, &I}, {1, 1, &all.M}};
  std::vector<Block> dy{{0, 1, &I, -1.0}, {1, 0, &all.K}, {1, 1, &all.C}, {1, 2, &Ht_, -1.0}};
  if (index1) {
    dyp.push_back({2, 1, &H_});
    dy.push_back({2, 0, &H_, a_ * a_});
    dy.push_back({2, 1, &H_, 2 * a_});
  } else {
    dy.push_back({2, 0, &H_});
  }
  if (ggl) {
    dy.push_back({0, 3, &Ht_, -1.0});
    dy.push_back({3, 1, &H_});
  }
  const SparseMatrix dyp_alone = assemble_blocks(sizes, dyp);
  dF_dy_ = assemble_blocks(sizes, dy, &dyp_alone);
  dF_dyp_ = assemble_blocks(sizes, dyp, &dF_dy_);
  if (dF_dy_.nonZeros() != dF_dyp_.nonZeros()) throw Error("internal: IDA tool DAE Jacobian patterns differ");
  f_.resize(n());
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

int IdaToolDae::residual(double t, N_Vector y, N_Vector yp, N_Vector r, void* self) {
  auto* me = static_cast<IdaToolDae*>(self);
  return guarded_callback(me->pending_, -1, [&] {
    const Index n = me->n(), p = me->p();
    const auto Y = sundials::view(y), YP = sundials::view(yp);
    auto R = sundials::view(r);
    me->all_.load.evaluate(t, me->f_);
    const auto u = Y.head(n), v = Y.segment(n, n), lambda = Y.segment(2 * n, p);
    R.head(n) = YP.head(n) - v;
    R.segment(n, n).noalias() = me->all_.M * YP.segment(n, n) + me->all_.C * v + me->all_.K * u - me->Ht_ * lambda;
    R.segment(n, n) -= me->f_;
    switch (me->formulation_) {
      case ToolFormulation::index3:
        R.segment(2 * n, p) = me->H_ * u - me->path(t, 0);
        break;
      case ToolFormulation::ggl:
        R.head(n) -= me->Ht_ * Y.segment(2 * n + p, p);
        R.segment(2 * n, p) = me->H_ * u - me->path(t, 0);
        R.segment(2 * n + p, p) = me->H_ * v - me->path(t, 1);
        break;
      case ToolFormulation::index1:
        R.segment(2 * n, p) = me->H_ * YP.segment(n, n) - me->path(t, 2) + 2 * me->a_ * (me->H_ * v - me->path(t, 1)) +
                              me->a_ * me->a_ * (me->H_ * u - me->path(t, 0));
        break;
    }
  });
}

int IdaToolDae::jacobian(double, double c_j, N_Vector, N_Vector, N_Vector, SUNMatrix J, void* self, N_Vector, N_Vector,
                         N_Vector) {
  auto* me = static_cast<IdaToolDae*>(self);
  return guarded_callback(me->pending_, -1, [&] { sundials::write_newton_matrix(me->dF_dy_, me->dF_dyp_, c_j, J); });
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
  const Vector rest = f_ - all_.C * v - all_.K * u;  // M a = rest + H^T lambda
  Vector a(n);
  mass_inverse_->apply(rest, a);  // M is block diagonal between the tools' dofs and the rest
  for (Index i = 0; i < p; ++i) a[tool_dofs_[static_cast<std::size_t>(i)]] = ddG[i];
  const Vector lambda = H_ * (all_.M * a - rest);
  auto y = sundials::view(y_.get()), yp = sundials::view(yp_.get());
  y.setZero();
  yp.setZero();
  y.head(n) = u;
  y.segment(n, n) = v;
  y.segment(2 * n, p) = lambda;
  yp.head(n) = v;
  yp.segment(n, n) = a;
}

void IdaToolDae::start(double t0) {
  auto check = [&](int flag, const char* call) {
    if (flag < 0)
      throw SolverError("IDA tool DAE (" + std::string(formulation_name(formulation_)) + "): " + call +
                        " failed: " + sundials::flag_name(IDAGetReturnFlagName(flag)) + last_error_.detail());
  };
  if (memory_) {
    restarted_ = stats();
    restarted_.factorization_s = 0;
    check(IDAReInit(memory_.get(), t0, y_.get(), yp_.get()), "IDAReInit");
    return;
  }
  memory_.reset(IDACreate(context_.get()));
  if (!memory_) throw SolverError("IDA tool DAE: IDACreate failed");
  check(IDAInit(memory_.get(), residual, t0, y_.get(), yp_.get()), "IDAInit");
  check(IDASetUserData(memory_.get(), this), "IDASetUserData");
  check(IDASetErrHandlerFn(memory_.get(), sundials::LastError::handler, &last_error_), "IDASetErrHandlerFn");
  check(IDASStolerances(memory_.get(), control_.rtol, control_.atol), "IDASStolerances");
  check(IDASetMaxNumSteps(memory_.get(), max_steps_per_output), "IDASetMaxNumSteps");
  check(IDASetId(memory_.get(), id_.get()), "IDASetId");
  check(IDASetSuppressAlg(memory_.get(), SUNTRUE), "IDASetSuppressAlg");
  J_ = sundials::make_sparse(dF_dy_, context_.get());
  solver_ = std::make_unique<sundials::KluSolver>(y_.get(), J_.get(), context_.get());
  check(IDASetLinearSolver(memory_.get(), solver_->get(), J_.get()), "IDASetLinearSolver");
  check(IDASetJacFn(memory_.get(), jacobian), "IDASetJacFn");
}

void IdaToolDae::reset(double t0) {
  const Index size = 2 * n() + (formulation_ == ToolFormulation::ggl ? 2 : 1) * p();
  memory_.reset();  // before the solver and vectors it refers to
  solver_.reset();
  J_.reset();
  pending_ = nullptr;
  restarted_ = {};
  t_ = t0;
  y_ = sundials::make_vector(size, context_.get());
  yp_ = sundials::make_vector(size, context_.get());
  id_ = sundials::make_vector(size, context_.get());
  auto id = sundials::view(id_.get());
  id.setZero();
  id.head(2 * n()).setOnes();  // u, v differential; the multipliers algebraic
  // Index 3: the tools' velocities are index-2 variables, kept out of the error test too.
  if (formulation_ == ToolFormulation::index3)
    for (const Index i : tool_dofs_) id[n() + i] = 0;
  make_consistent(t0, Vector::Zero(n()), Vector::Zero(n()));
  start(t0);
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
  if (!memory_) throw Error("internal: IDA tool DAE: advance_to before reset");
  while (t_ < t_out) {
    while (next_kink_ < kinks_.size() && kinks_[next_kink_] <= t_) ++next_kink_;
    const bool to_kink = next_kink_ < kinks_.size() && kinks_[next_kink_] <= t_out;
    const double target = to_kink ? kinks_[next_kink_] : t_out;
    IDASetStopTime(memory_.get(), target);
    const int flag = IDASolve(memory_.get(), target, &t_, y_.get(), yp_.get(), IDA_NORMAL);
    if (pending_) std::rethrow_exception(std::exchange(pending_, nullptr));
    if (flag < 0)
      throw SolverError("IDA tool DAE (" + std::string(formulation_name(formulation_)) + "): failed at t = " + number_text(t_) +
                        " s: " + sundials::flag_name(IDAGetReturnFlagName(flag)) + last_error_.detail());
    if (to_kink) {  // the path's velocity jumps: restart from consistent values past the kink
      t_ = target;
      make_consistent(t_, displacement(), velocity());
      start(t_);
    }
  }
}

Vector IdaToolDae::displacement() const { return sundials::view(y_.get()).head(n()); }
Vector IdaToolDae::velocity() const { return sundials::view(y_.get()).segment(n(), n()); }
Vector IdaToolDae::multipliers() const { return sundials::view(y_.get()).segment(2 * n(), p()); }

Vector IdaToolDae::tool_forces() const {
  const Vector own = H_ * (all_.M * (Ht_ * path(t_, 2)) + all_.C * (Ht_ * path(t_, 1)));  // the nodes' inertia
  return S_ * (multipliers() - own);
}

double IdaToolDae::position_drift() const { return (H_ * displacement() - path(t_, 0)).cwiseAbs().maxCoeff(); }
double IdaToolDae::velocity_drift() const { return (H_ * velocity() - path(t_, 1)).cwiseAbs().maxCoeff(); }

Stats IdaToolDae::stats() const {
  Stats s = sundials::ida_stats(memory_.get());
  s.steps += restarted_.steps;
  s.rhs_evals += restarted_.rhs_evals;
  s.jac_evals += restarted_.jac_evals;
  s.lin_setups += restarted_.lin_setups;
  s.lin_solves += restarted_.lin_solves;
  s.failed_steps += restarted_.failed_steps;
  if (solver_) s.factorization_s = solver_->setup_seconds();
  return s;
}

}  // namespace roifem::integrators
