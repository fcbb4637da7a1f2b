// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// SUNDIALS IDA with KLU on a sparse Newton matrix: the one owner of what the three IDA integrators
/// share (ida.hpp, ida_roi_dae.hpp, ida_tool_dae.hpp), in the shape of MFEM's SundialsSolver. It
/// creates IDA's memory, sets the tolerances, step bounds and differential/algebraic ids, builds the
/// Jacobian on the pattern of dF/dy and dF/dy' (one pattern, their union) with KLU, turns a failed
/// call into a SolverError naming the call, restarts (IDAReInit, the counters summed over restarts)
/// and advances. Each integrator keeps only its residual, its Newton matrix's two parts and its
/// consistent initial values. Callbacks never let an exception cross IDA (callback_guard.hpp).
///   F(t, y, y') = 0,  Newton matrix  J = dF/dy + c_j dF/dy'.
#include <exception>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "integrators/integrator.hpp"
#include "integrators/sundials/handles.hpp"
#include "integrators/sundials/klu_solver.hpp"

namespace roifem::integrators::sundials {

class IdaSolver {
 public:
  /// r = F(t, y, y').
  using Residual = std::function<void(double t, const Eigen::Ref<const Eigen::VectorXd>& y,
                                      const Eigen::Ref<const Eigen::VectorXd>& yp, Eigen::Ref<Eigen::VectorXd> r)>;
  struct Settings {
    std::string name;  ///< names the method in messages ("ida-bdf5", "IDA tool DAE (ggl)")
    double rtol = 1e-6, atol = 1e-9;
    int max_order = 5;
    long max_steps = 1000000;  ///< per advance
    /// 1 for a differential entry, 0 for an algebraic one (IDASetId); none: every entry differential.
    std::optional<Eigen::VectorXd> differential;
    bool suppress_algebraic = false;  ///< leave the algebraic entries out of the error test (index 2 and 3)
    /// Called with t and y before each Newton matrix is formed, where dF/dy depends on them (a
    /// nonlinear system): it rewrites dF_dy's values, its pattern unchanged.
    std::function<void(double t, const Eigen::Ref<const Eigen::VectorXd>& y)> update_dF_dy;
  };
  /// dF_dy and dF_dyp on one pattern (assemble_blocks' pattern_of), kept by reference.
  IdaSolver(Settings settings, Residual residual, const SparseMatrix& dF_dy, const SparseMatrix& dF_dyp);
  IdaSolver(const IdaSolver&) = delete;
  IdaSolver& operator=(const IdaSolver&) = delete;
  ~IdaSolver();

  /// y and y' to start from (size n); start() takes them.
  Eigen::Map<Eigen::VectorXd> y() { return view(y_.get()); }
  Eigen::Map<Eigen::VectorXd> yp() { return view(yp_.get()); }
  Eigen::Map<const Eigen::VectorXd> y() const { return {N_VGetArrayPointer(y_.get()), N_VGetLength(y_.get())}; }
  Eigen::Map<const Eigen::VectorXd> yp() const { return {N_VGetArrayPointer(yp_.get()), N_VGetLength(yp_.get())}; }
  /// Starts at t0 from y() and yp(): IDAInit the first time, IDAReInit after (a restart: the
  /// counters so far are kept).
  void start(double t0);
  /// IDACalcIC: the algebraic entries and the differential ones' derivatives made consistent,
  /// IDA_YA_YDP_INIT, towards t_first.
  void make_consistent(double t_first);
  /// Advances to t_out (a stop time: never past it); returns the t reached. SolverError naming the
  /// method, t and the step when IDA fails; the callbacks' exceptions rethrown. A Newton iterate the
  /// model refuses (an element inverted) is recoverable: IDA retries the step smaller. A solution
  /// that presses on an inversion would have it retry without end (a step limit of a million runs
  /// for minutes), so the refusals are bounded: the max_refused_per_output-th within one call stops
  /// it with a SolverError naming the element, the step and the time.
  double advance_to(double t_out);
  static constexpr int max_refused_per_output = 25;
  /// IDA's counters summed over every start, and the linear solver's setup time.
  Stats stats() const;

 private:
  static int residual_callback(double t, N_Vector y, N_Vector yp, N_Vector r, void* self);
  static int jacobian_callback(double t, double c_j, N_Vector, N_Vector, N_Vector, SUNMatrix J, void* self, N_Vector, N_Vector,
                               N_Vector);
  void check(int flag, const char* call) const;
  Stats current() const;

  Settings settings_;
  Residual residual_;
  const SparseMatrix& dF_dy_;
  const SparseMatrix& dF_dyp_;
  Context context_;  // first: destroyed last
  Vector y_, yp_, id_;
  Matrix J_;
  std::unique_ptr<KluSolver> solver_;
  IdaMemory memory_;
  Stats before_;  ///< the counters of the starts before the last
  std::exception_ptr pending_;
  std::string inadmissible_;  ///< the last Newton iterate the model refused (guarded_recoverable_callback)
  int refused_ = 0;           ///< refused iterates in this advance_to
  LastError last_error_;
};

}  // namespace roifem::integrators::sundials
