#include "integrators/ida_roi_dae.hpp"

#include <ida/ida.h>

#include <utility>

#include "common/errors.hpp"
#include "common/number_text.hpp"
#include "integrators/block_matrix.hpp"
#include "integrators/callback_guard.hpp"
#include "integrators/sundials/ida_support.hpp"

namespace roifem::integrators {

IdaRoiDae::IdaRoiDae(const model::SecondOrderSystem& full, const roi::Partition& partition, StepControl control, int max_order)
    : full_(full), partition_(partition), control_(control), max_order_(max_order), context_(sundials::make_context()) {
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
  dF_dy_ = assemble_blocks(
      sizes, {{0, 1, &I, -1.0}, {1, 0, &K_dd_}, {1, 1, &C_dd_}, {1, 2, &K_ds_}, {2, 0, &K_sd_}, {2, 2, &K_ss_}}, &dyp);
  dF_dyp_ = assemble_blocks(sizes, {{0, 0, &I}, {1, 1, &M_dd_}}, &dF_dy_);
  if (dF_dy_.nonZeros() != dF_dyp_.nonZeros()) throw Error("internal: IDA DAE Jacobian patterns differ");
  f_d_.resize(nd);
  f_s_.resize(ns);
}

int IdaRoiDae::residual(double t, N_Vector y, N_Vector yp, N_Vector r, void* self) {
  auto* me = static_cast<IdaRoiDae*>(self);
  return guarded_callback(me->pending_, -1, [&] {
    const Index nd = me->K_dd_.rows(), ns = me->K_ss_.rows();
    const auto Y = sundials::view(y), YP = sundials::view(yp);
    auto R = sundials::view(r);
    me->load_d_.evaluate(t, me->f_d_);
    me->load_s_.evaluate(t, me->f_s_);
    const auto u_d = Y.head(nd), v_d = Y.segment(nd, nd), u_s = Y.tail(ns);
    R.head(nd) = YP.head(nd) - v_d;
    R.segment(nd, nd).noalias() = me->M_dd_ * YP.segment(nd, nd) + me->C_dd_ * v_d + me->K_dd_ * u_d + me->K_ds_ * u_s;
    R.segment(nd, nd) -= me->f_d_;
    R.tail(ns).noalias() = me->K_sd_ * u_d + me->K_ss_ * u_s;
    R.tail(ns) -= me->f_s_;
  });
}

int IdaRoiDae::jacobian(double, double c_j, N_Vector, N_Vector, N_Vector, SUNMatrix J, void* self, N_Vector, N_Vector, N_Vector) {
  auto* me = static_cast<IdaRoiDae*>(self);
  return guarded_callback(me->pending_, -1, [&] { sundials::write_newton_matrix(me->dF_dy_, me->dF_dyp_, c_j, J); });
}

void IdaRoiDae::reset(double t0) {
  const Index nd = K_dd_.rows(), ns = K_ss_.rows(), n = 2 * nd + ns;
  memory_.reset();  // before the solver and vectors it refers to
  solver_.reset();
  J_.reset();
  pending_ = nullptr;
  t_ = t0;
  y_ = sundials::make_vector(n, context_.get());
  yp_ = sundials::make_vector(n, context_.get());
  id_ = sundials::make_vector(n, context_.get());
  sundials::view(y_.get()).setZero();
  sundials::view(yp_.get()).setZero();
  auto id = sundials::view(id_.get());
  id.head(2 * nd).setOnes();  // differential: u_d, v_d
  id.tail(ns).setZero();      // algebraic: u_s
  auto check = [&](int flag, const char* call) {
    if (flag < 0)
      throw SolverError(std::string("IDA ROI DAE: ") + call + " failed: " + sundials::flag_name(IDAGetReturnFlagName(flag)));
  };
  memory_.reset(IDACreate(context_.get()));
  if (!memory_) throw SolverError("IDA ROI DAE: IDACreate failed");
  check(IDAInit(memory_.get(), residual, t0, y_.get(), yp_.get()), "IDAInit");
  check(IDASetUserData(memory_.get(), this), "IDASetUserData");
  check(IDASetErrHandlerFn(memory_.get(), sundials::LastError::handler, &last_error_), "IDASetErrHandlerFn");
  check(IDASStolerances(memory_.get(), control_.rtol, control_.atol), "IDASStolerances");
  check(IDASetMaxOrd(memory_.get(), max_order_), "IDASetMaxOrd");
  check(IDASetMaxNumSteps(memory_.get(), 1000000), "IDASetMaxNumSteps");
  check(IDASetId(memory_.get(), id_.get()), "IDASetId");
  J_ = sundials::make_sparse(dF_dy_, context_.get());
  solver_ = std::make_unique<sundials::KluSolver>(y_.get(), J_.get(), context_.get());
  check(IDASetLinearSolver(memory_.get(), solver_->get(), J_.get()), "IDASetLinearSolver");
  check(IDASetJacFn(memory_.get(), jacobian), "IDASetJacFn");
  check(IDACalcIC(memory_.get(), IDA_YA_YDP_INIT, t0 + control_.dt), "IDACalcIC");
  if (pending_) std::rethrow_exception(std::exchange(pending_, nullptr));
}

void IdaRoiDae::advance_to(double t_out, Vector& u_d, Vector& u_s) {
  if (!memory_) throw Error("internal: IDA ROI DAE: advance_to before reset");
  IDASetStopTime(memory_.get(), t_out);
  const int flag = IDASolve(memory_.get(), t_out, &t_, y_.get(), yp_.get(), IDA_NORMAL);
  if (pending_) std::rethrow_exception(std::exchange(pending_, nullptr));
  if (flag < 0)
    throw SolverError("IDA ROI DAE: failed at t = " + number_text(t_) + " s: " + sundials::flag_name(IDAGetReturnFlagName(flag)) +
                      last_error_.detail());
  const Index nd = K_dd_.rows(), ns = K_ss_.rows();
  const auto y = sundials::view(y_.get());
  u_d = y.head(nd);
  u_s = y.tail(ns);
}

Vector IdaRoiDae::velocity_d() const {
  const Index nd = K_dd_.rows();
  return sundials::view(y_.get()).segment(nd, nd);
}

Stats IdaRoiDae::stats() const {
  Stats s = sundials::ida_stats(memory_.get());
  if (solver_) s.factorization_s = solver_->setup_seconds();
  return s;
}

}  // namespace roifem::integrators
