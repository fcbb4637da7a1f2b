// SPDX-License-Identifier: GPL-3.0-or-later
#include "distributed/petsc_ts.hpp"

#include <petscts.h>

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "common/errors.hpp"
#include "common/number_text.hpp"
#include "common/timer.hpp"
#include "integrators/callback_guard.hpp"

namespace roifem::distributed {

namespace {

using RowMajor = Eigen::SparseMatrix<double, Eigen::RowMajor, PetscInt>;

/// A view of a sequential Vec's values for the lifetime of the object: read-only, or writable.
template <bool Writable>
class VecView {
 public:
  using Scalar = std::conditional_t<Writable, PetscScalar, const PetscScalar>;
  explicit VecView(Vec v) : v_(v) {
    PetscInt n = 0;
    check(VecGetLocalSize(v, &n), "VecGetLocalSize");
    if constexpr (Writable)
      check(VecGetArray(v, &data_), "VecGetArray");
    else
      check(VecGetArrayRead(v, &data_), "VecGetArrayRead");
    n_ = n;
  }
  VecView(const VecView&) = delete;
  VecView& operator=(const VecView&) = delete;
  ~VecView() {
    if constexpr (Writable)
      VecRestoreArray(v_, &data_);
    else
      VecRestoreArrayRead(v_, &data_);
  }
  Eigen::Map<std::conditional_t<Writable, Vector, const Vector>> map() const { return {data_, n_}; }

 private:
  Vec v_;
  Scalar* data_ = nullptr;
  Index n_ = 0;
};
using ReadView = VecView<false>;
using WriteView = VecView<true>;

OwnedVec sequential_vector(const Eigen::Ref<const Vector>& values) {
  OwnedVec v;
  check(VecCreateSeq(PETSC_COMM_SELF, static_cast<PetscInt>(values.size()), v.out()), "VecCreateSeq");
  WriteView(v.get()).map() = values;
  return v;
}

/// A SeqAIJ matrix with A's pattern and values (A compressed, columns sorted in each row).
OwnedMat sequential_matrix(const RowMajor& A) {
  OwnedMat m;
  check(MatCreate(PETSC_COMM_SELF, m.out()), "MatCreate");
  check(MatSetSizes(m.get(), A.rows(), A.cols(), A.rows(), A.cols()), "MatSetSizes");
  check(MatSetType(m.get(), MATSEQAIJ), "MatSetType");
  check(MatSeqAIJSetPreallocationCSR(m.get(), A.outerIndexPtr(), A.innerIndexPtr(), A.valuePtr()),
        "MatSeqAIJSetPreallocationCSR");
  return m;
}

/// New values for a matrix of the same pattern.
void copy_values(const RowMajor& A, Mat m) {
  PetscInt nonzeros = 0;
  MatInfo info;
  check(MatGetInfo(m, MAT_LOCAL, &info), "MatGetInfo");
  nonzeros = static_cast<PetscInt>(info.nz_used);
  if (nonzeros != A.nonZeros()) throw Error("internal: petsc-ts: the Jacobian's pattern changed");
  PetscScalar* values = nullptr;
  check(MatSeqAIJGetArray(m, &values), "MatSeqAIJGetArray");
  std::copy(A.valuePtr(), A.valuePtr() + A.nonZeros(), values);
  check(MatSeqAIJRestoreArray(m, &values), "MatSeqAIJRestoreArray");
  // The assembly marks the matrix changed, so the preconditioner refactors it (restoring the array
  // does not: TSALPHA2's starting steps, at other shifts, would keep their factor).
  check(MatAssemblyBegin(m, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  check(MatAssemblyEnd(m, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
}

/// [s I, -I; K, s M + C] (the first-order form's Jacobian at shift s).
RowMajor first_order_matrix(const model::SecondOrderSystem& sys, double s) {
  const Index n = sys.size();
  std::vector<Eigen::Triplet<double, PetscInt>> entries;
  entries.reserve(static_cast<std::size_t>(2 * n + sys.K.nonZeros() + sys.M.nonZeros() + sys.C.nonZeros()));
  for (Index i = 0; i < n; ++i) {
    entries.emplace_back(static_cast<PetscInt>(i), static_cast<PetscInt>(i), s);
    entries.emplace_back(static_cast<PetscInt>(i), static_cast<PetscInt>(n + i), -1.0);
  }
  const SparseMatrix lower = s * sys.M + sys.C;
  for (const SparseMatrix* block : {&sys.K, &lower})
    for (Index j = 0; j < block->outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(*block, j); it; ++it)
        entries.emplace_back(static_cast<PetscInt>(n + it.row()), static_cast<PetscInt>(block == &sys.K ? j : n + j), it.value());
  RowMajor J(2 * n, 2 * n);
  J.setFromTriplets(entries.begin(), entries.end());
  J.makeCompressed();
  return J;
}

RowMajor second_order_matrix(const model::SecondOrderSystem& sys, double shift_v, double shift_a) {
  RowMajor J = sys.K + shift_a * sys.M + shift_v * sys.C;
  J.makeCompressed();
  return J;
}

// The C trampolines: each runs its body through guarded_callback (no exception crosses PETSc).
PetscErrorCode alpha2_residual(TS, PetscReal t, Vec U, Vec V, Vec A, Vec F, void* self) {
  auto* ts = static_cast<PetscTs*>(self);
  return integrators::guarded_callback(ts->pending, PETSC_ERR_USER, [&] { ts->residual(t, U, V, A, F); });
}
PetscErrorCode alpha2_jacobian(TS, PetscReal, Vec, Vec, Vec, PetscReal shift_v, PetscReal shift_a, Mat J, Mat, void* self) {
  auto* ts = static_cast<PetscTs*>(self);
  return integrators::guarded_callback(ts->pending, PETSC_ERR_USER, [&] { ts->jacobian(shift_v, shift_a, J); });
}
PetscErrorCode theta_residual(TS, PetscReal t, Vec Y, Vec Ydot, Vec F, void* self) {
  auto* ts = static_cast<PetscTs*>(self);
  return integrators::guarded_callback(ts->pending, PETSC_ERR_USER, [&] { ts->first_order_residual(t, Y, Ydot, F); });
}
PetscErrorCode theta_jacobian(TS, PetscReal, Vec, Vec, PetscReal shift, Mat J, Mat, void* self) {
  auto* ts = static_cast<PetscTs*>(self);
  return integrators::guarded_callback(ts->pending, PETSC_ERR_USER, [&] { ts->first_order_jacobian(shift, J); });
}

}  // namespace

std::vector<integrators::IntegratorInfo> petsc_ts_rows() {
  using integrators::Family;
  using integrators::IntegratorInfo;
  using integrators::LinearSolver;
  auto make = [](const IntegratorInfo& info,
                 const integrators::StepControl& control) -> std::unique_ptr<integrators::Integrator> {
    return std::make_unique<PetscTs>(info.method_id == 0 ? PetscTs::Method::alpha2 : PetscTs::Method::theta, control.dt);
  };
  return {{.name = "petsc-alpha2",
           .family = Family::petsc,
           .order = 2,
           .fixed_step = true,
           .linear_solver = LinearSolver::cholmod,
           .method_id = 0,
           .make = make,
           .summary = "PETSc TSALPHA2: generalized-alpha (Chung-Hulbert) on the second-order form, rho_inf 0.5, CHOLMOD"},
          {.name = "petsc-theta",
           .family = Family::petsc,
           .order = 2,
           .fixed_step = true,
           .linear_solver = LinearSolver::klu,
           .method_id = 1,
           .make = make,
           .summary = "PETSc TSTHETA, theta 1/2 at the endpoints (Crank-Nicolson) on the first-order form, KLU"}};
}

PetscTs::PetscTs(Method method, double dt) : method_(method), grid_(0.0, dt, name()) {
  PetscBool initialized = PETSC_FALSE;
  PetscInitialized(&initialized);
  if (!initialized) throw Error("internal: " + std::string(name()) + " needs an open PetscSession");
}

void PetscTs::rethrow_pending() {
  if (pending) std::rethrow_exception(std::exchange(pending, nullptr));
}

void PetscTs::prepare(const model::SecondOrderSystem& system, const model::State& initial) {
  const Stopwatch clock;
  system_ = &system;
  grid_ = model::TimeGrid(initial.t, grid_.dt(), name());
  k_ = 0;
  jacobians_ = residuals_ = 0;
  shift_v_ = shift_a_ = -1;
  f_.resize(system.size());
  work_.resize(system.size());
  ts_.reset();
  check(TSCreate(PETSC_COMM_SELF, ts_.out()), "TSCreate");
  TS ts = ts_.get();
  const bool alpha2 = method_ == Method::alpha2;
  check(TSSetOptionsPrefix(ts, alpha2 ? "petsc_alpha2_" : "petsc_theta_"), "TSSetOptionsPrefix");
  if (alpha2) {
    check(TSSetType(ts, TSALPHA2), "TSSetType(alpha2)");
    check(TSAlpha2SetRadius(ts, 0.5), "TSAlpha2SetRadius");
    J_ = sequential_matrix(second_order_matrix(system, 1, 1));
    check(TSSetI2Function(ts, nullptr, alpha2_residual, this), "TSSetI2Function");
    check(TSSetI2Jacobian(ts, J_.get(), J_.get(), alpha2_jacobian, this), "TSSetI2Jacobian");
    u_ = sequential_vector(initial.u);
    v_ = sequential_vector(initial.v);
    check(TS2SetSolution(ts, u_.get(), v_.get()), "TS2SetSolution");
  } else {
    check(TSSetType(ts, TSTHETA), "TSSetType(theta)");
    check(TSThetaSetTheta(ts, 0.5), "TSThetaSetTheta");
    check(TSThetaSetEndpoint(ts, PETSC_TRUE), "TSThetaSetEndpoint");
    J_ = sequential_matrix(first_order_matrix(system, 1));
    check(TSSetIFunction(ts, nullptr, theta_residual, this), "TSSetIFunction");
    check(TSSetIJacobian(ts, J_.get(), J_.get(), theta_jacobian, this), "TSSetIJacobian");
    Vector y(2 * system.size());
    y << initial.u, initial.v;
    y_ = sequential_vector(y);
    check(TSSetSolution(ts, y_.get()), "TSSetSolution");
  }
  check(TSSetTime(ts, initial.t), "TSSetTime");
  check(TSSetTimeStep(ts, grid_.dt()), "TSSetTimeStep");
  // advance_to counts the steps itself (TSStep); PETSc still wants a bound (its default reads as none).
  check(TSSetMaxSteps(ts, PETSC_MAX_INT - 1), "TSSetMaxSteps");
  TSAdapt adapt = nullptr;
  check(TSGetAdapt(ts, &adapt), "TSGetAdapt");
  check(TSAdaptSetType(adapt, TSADAPTNONE), "TSAdaptSetType");
  SNES snes = nullptr;
  KSP ksp = nullptr;
  PC pc = nullptr;
  check(TSGetSNES(ts, &snes), "TSGetSNES");
  // The problem is linear, so one Newton step solves it; Newton with a plain step rather than
  // SNESKSPONLY, whose residual is never evaluated at the solution: TSALPHA2 takes the new
  // velocity and acceleration from that last evaluation (with KSPONLY, the guess's: wrong).
  check(SNESSetType(snes, SNESNEWTONLS), "SNESSetType");
  SNESLineSearch line_search = nullptr;
  check(SNESGetLineSearch(snes, &line_search), "SNESGetLineSearch");
  check(SNESLineSearchSetType(line_search, SNESLINESEARCHBASIC), "SNESLineSearchSetType");
  check(SNESGetKSP(snes, &ksp), "SNESGetKSP");
  check(KSPSetType(ksp, KSPPREONLY), "KSPSetType");
  check(KSPGetPC(ksp, &pc), "KSPGetPC");
  check(PCSetType(pc, alpha2 ? PCCHOLESKY : PCLU), "PCSetType");
  check(PCFactorSetMatSolverType(pc, alpha2 ? MATSOLVERCHOLMOD : MATSOLVERKLU), "PCFactorSetMatSolverType");
  check(TSSetFromOptions(ts), "TSSetFromOptions");
  check(TSSetUp(ts), "TSSetUp");
  rethrow_pending();
  setup_s_ = clock.seconds();
}

void PetscTs::advance(double t_out, model::State& state) {
  const long target = grid_.index_of(t_out, k_);
  while (k_ < target) {
    const PetscErrorCode code = TSStep(ts_.get());
    rethrow_pending();
    ++k_;
    if (code != 0)
      throw SolverError(std::string(name()) + ": step " + std::to_string(k_) + ", t = " + number_text(grid_.at(k_)) +
                        " s: PETSc's TSStep failed (error " + std::to_string(static_cast<int>(code)) + ")");
  }
  state.t = grid_.at(k_);
  const Index n = system_->size();
  if (method_ == Method::alpha2) {
    Vec U = nullptr, V = nullptr;
    check(TS2GetSolution(ts_.get(), &U, &V), "TS2GetSolution");
    state.u = ReadView(U).map();
    state.v = ReadView(V).map();
  } else {
    Vec Y = nullptr;
    check(TSGetSolution(ts_.get(), &Y), "TSGetSolution");
    const ReadView y(Y);
    state.u = y.map().head(n);
    state.v = y.map().tail(n);
  }
  if (!state.u.allFinite())
    throw SolverError(std::string(name()) + ": non-finite displacement at step " + std::to_string(k_) +
                      ", t = " + number_text(state.t) + " s");
}

integrators::Stats PetscTs::stats() const {
  integrators::Stats s;
  s.steps = k_;
  s.rhs_evals = residuals_;
  s.jac_evals = jacobians_;
  s.lin_setups = jacobians_;
  PetscInt solves = 0;
  if (ts_.get()) TSGetKSPIterations(ts_.get(), &solves);
  s.lin_solves = solves;
  s.factorization_s = setup_s_;
  return s;
}

void PetscTs::residual(double t, Vec U, Vec V, Vec A, Vec F) {
  ++residuals_;
  const ReadView u(U), v(V), a(A);
  WriteView out(F);
  auto r = out.map();
  system_->apply_mass(a.map(), r);
  system_->apply_stiffness(u.map(), work_);
  r += work_;
  if (system_->damping.is_mass_proportional()) {
    system_->apply_mass(v.map(), work_);
    r += system_->damping.alpha * work_;
  } else {
    r += system_->C * v.map();
  }
  system_->load.evaluate(t, f_);
  r -= f_;
}

void PetscTs::jacobian(double shift_v, double shift_a, Mat J) {
  if (shift_v == shift_v_ && shift_a == shift_a_) return;  // unchanged: PETSc keeps its factorization
  ++jacobians_;
  copy_values(second_order_matrix(*system_, shift_v, shift_a), J);
  shift_v_ = shift_v;
  shift_a_ = shift_a;
}

void PetscTs::first_order_residual(double t, Vec Y, Vec Ydot, Vec F) {
  ++residuals_;
  const Index n = system_->size();
  const ReadView y(Y), ydot(Ydot);
  WriteView out(F);
  auto r = out.map();
  r.head(n) = ydot.map().head(n) - y.map().tail(n);
  auto lower = r.tail(n);
  system_->apply_mass(ydot.map().tail(n), lower);
  system_->apply_stiffness(y.map().head(n), work_);
  lower += work_ + system_->C * y.map().tail(n);
  system_->load.evaluate(t, f_);
  lower -= f_;
}

void PetscTs::first_order_jacobian(double shift, Mat J) {
  if (shift == shift_a_) return;
  ++jacobians_;
  copy_values(first_order_matrix(*system_, shift), J);
  shift_a_ = shift;
}

}  // namespace roifem::distributed
