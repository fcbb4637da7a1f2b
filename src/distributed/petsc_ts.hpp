// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// PETSc's time steppers as integrators of the seam (integrators/integrator.hpp), on one rank
/// (PETSC_COMM_SELF; a PetscSession must be open), fixed step:
///   petsc-alpha2  TSALPHA2: generalized-alpha for M u'' + C u' + K u = f(t) in its second-order
///                 form (Chung & Hulbert 1993), spectral radius at infinity rho_inf = 0.5: second
///                 order, numerical damping of the highest modes. Residual
///                 F(t, u, v, a) = M a + C v + K u - f(t); Jacobian shift_a M + shift_v C + K by
///                 CHOLMOD (PETSc's MATSOLVERCHOLMOD).
///   petsc-theta   TSTHETA with theta = 1/2 at the endpoints (Crank-Nicolson) on the first-order form
///                 y = [u; v]: F(t, y, y') = [u' - v; M v' + C v + K u - f(t)]; Jacobian
///                 [s I, -I; K, s M + C] by KLU. On a linear system this is the trapezoidal rule
///                 itself, so it reproduces integrators::Trapezoid (a test).
/// The Jacobians are rebuilt only when PETSc's shifts change (with a fixed step: once), so the
/// factorization is reused as the trapezoid's is. Callbacks never let an exception cross PETSc:
/// it is kept and rethrown after the PETSc call (integrators/callback_guard.hpp).
#include <petscts.h>

#include <exception>
#include <memory>
#include <vector>

#include "distributed/petsc_handle.hpp"
#include "integrators/integrator_info.hpp"
#include "model/time_grid.hpp"

namespace roifem::distributed {

/// The rows roifem-mpi compare adds to the table's (experiments::CompareOptions::extra_rows).
std::vector<integrators::IntegratorInfo> petsc_ts_rows();

class PetscTs final : public integrators::Integrator {
 public:
  enum class Method { alpha2, theta };
  PetscTs(Method method, double dt);
  std::string_view name() const override { return method_ == Method::alpha2 ? "petsc-alpha2" : "petsc-theta"; }
  integrators::Stats stats() const override;

  /// Callbacks' bodies (public for the C trampolines in petsc_ts.cpp).
  void residual(double t, Vec U, Vec V, Vec A, Vec F);
  void jacobian(double shift_v, double shift_a, Mat J);
  void first_order_residual(double t, Vec Y, Vec Ydot, Vec F);
  void first_order_jacobian(double shift, Mat J);
  std::exception_ptr pending;

 private:
  void prepare(const model::SecondOrderSystem& system, const model::State& initial) override;
  /// t_out on the grid t_0 + k dt.
  void advance(double t_out, model::State& state) override;
  void rethrow_pending();
  Method method_;
  model::TimeGrid grid_;  ///< t_k = t_0 + k dt from the last reset
  long k_ = 0;
  const model::SecondOrderSystem* system_ = nullptr;
  Owned<TS, TSDestroy> ts_;
  OwnedMat J_;
  OwnedVec u_, v_, y_;  // alpha2: u_, v_; theta: y_ = [u; v]
  Vector f_, work_;
  double shift_v_ = -1, shift_a_ = -1;  // the shifts J_ holds
  long jacobians_ = 0, residuals_ = 0;
  double setup_s_ = 0;
};

}  // namespace roifem::distributed
