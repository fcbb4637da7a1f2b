// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// SUNDIALS ARKODE (ARKStep) on the first-order form y = [u; v]:
///   u' = v,   M v' = f(t) - C v - K u.
/// Explicit (ERK) methods use y' = [v; M^-1 (f - C v - K u)], M^-1 a product for the lumped M and
/// a Cholesky solve for the full M of a Guyan, Craig-Bampton or POD model.
/// Implicit (DIRK/ESDIRK) methods solve with the Jacobian J = [[0, I], [-M^-1 K, -M^-1 C]]
/// held as a SUNSparseMatrix (sparse for a reduced model too: its M is block diagonal, and M^-1 K is
/// dense only in the block's rows), factored by KLU with AMD ordering (KLU's default COLAMD is
/// slower on 3D meshes), the problem declared linear so that at a fixed step one factorization
/// serves every step. With `mass_matrix`, M is handed to ARKODE as its
/// mass matrix instead (J = [[0, I], [-K, -C]], a second KLU for [[I, 0], [0, M]]), for comparison.
/// The trapezoidal rule is available as a user Butcher table: c = [0, 1], A = [[0, 0], [1/2, 1/2]],
/// b = [1/2, 1/2] (an ESDIRK; equals the hand-written Newmark average-acceleration rule).
/// With `schur`, the Newton systems are solved by sundials::SchurSolver (one SPD Cholesky solve of
/// size n per stage) instead of KLU on the 2n system.
/// A nonlinear system (model/internal_force.hpp), with KLU: f_int(u) replaces K u, K_t(u) replaces K
/// in J, and ARKODE's modified Newton decides when to rebuild J and refactor (KLU refactors on
/// the first analysis); at a fixed step, rtol and atol weigh Newton's convergence test.
#include <exception>
#include <memory>
#include <string>
#include <vector>

#include "integrators/first_order_form.hpp"
#include "integrators/integrator.hpp"
#include "integrators/integrator_info.hpp"
#include "integrators/step_control.hpp"
#include "integrators/sundials/handles.hpp"
#include "integrators/sundials/klu_solver.hpp"
#include "integrators/sundials/schur_solver.hpp"

namespace roifem::integrators {

struct ArkodeMethod {
  std::string name;  ///< e.g. "arkode-sdirk2-mass"
  bool implicit = false;
  int table = -1;          ///< ARKODE_ERKTableID or ARKODE_DIRKTableID; -1 with `trapezoid`
  bool trapezoid = false;  ///< the user table above
  bool mass_matrix = false;
  bool schur = false;  ///< the Schur-complement Cholesky solver instead of KLU (see schur_solver.hpp)
  int order = 0;       ///< of the method (for the docs and tests)
  sundials::KluOrdering klu_ordering = sundials::KluOrdering::amd;
};

/// The ARKODE method of a row of the integrator table (integrator_table.hpp).
ArkodeMethod arkode_method(const IntegratorInfo& info);
/// The same by name (to vary one setting, e.g. the KLU ordering).
ArkodeMethod arkode_method(const std::string& name);
/// The factory's maker for the table's ARKODE rows.
std::unique_ptr<Integrator> make_arkode(const IntegratorInfo& info, const StepControl& control);
/// The table's rows of this family: the explicit ERK methods and each implicit one in its four
/// linear-algebra variants.
std::vector<IntegratorInfo> arkode_rows();

class Arkode final : public Integrator {
 public:
  Arkode(ArkodeMethod method, StepControl control);
  std::string_view name() const override { return method_.name; }
  Stats stats() const override;
  /// The explicit methods (f_int(u) alone, FirstOrderForm::evaluate) and the implicit ones on KLU
  /// (the Jacobian from the tangent K_t(u)); the Schur solver factors K itself and does not.
  bool takes_nonlinear() const override { return !method_.schur; }

 private:
  void prepare(const model::SecondOrderSystem& system, const model::State& initial) override;
  void advance(double t_out, model::State& state) override;
  static int rhs(double t, N_Vector y, N_Vector ydot, void* self);
  static int jacobian(double t, N_Vector y, N_Vector fy, SUNMatrix J, void* self, N_Vector, N_Vector, N_Vector);
  static int unit_weights(N_Vector y, N_Vector ewt, void* self);
  static int mass(double t, SUNMatrix M, void* self, N_Vector, N_Vector, N_Vector);
  void check(int flag, const char* call) const;
  void create_memory(const model::State& initial);
  void set_steps();
  void set_butcher_table();
  void attach_linear_solvers();
  /// The Newton matrix's Jacobian for the stiffness K (the system's, or a tangent) in this
  /// method's variant, with every entry of `pattern_of` present.
  SparseMatrix newton_jacobian(const SparseMatrix& K, const SparseMatrix* pattern_of = nullptr) const;

  ArkodeMethod method_;
  StepControl control_;
  sundials::Context context_;  // first member: destroyed last
  sundials::Vector y_;
  sundials::Matrix J_, M_;
  std::unique_ptr<sundials::KluSolver> solver_, mass_solver_;
  std::unique_ptr<sundials::SchurSolver> schur_;
  sundials::ArkodeMemory memory_;
  const model::SecondOrderSystem* system_ = nullptr;
  std::unique_ptr<FirstOrderForm> form_;
  double t0_ = 0;  // of the last reset, for messages
  SparseMatrix jacobian_, mass_matrix_;
  SparseMatrix jacobian_pattern_;  ///< a nonlinear problem's first Jacobian: every later one in its pattern
  std::exception_ptr pending_;     // an exception from a callback, rethrown after the C call
  std::string inadmissible_;       // the last Newton iterate the model refused (guarded_recoverable_callback)
  sundials::LastError last_error_;
};

}  // namespace roifem::integrators
