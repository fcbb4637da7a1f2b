// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// The trapezoidal rule (Newmark average acceleration, model/average_acceleration.hpp) on a
/// distributed model, with C = alpha M:
///   K_eff u_{k+1} = f_{k+1} + M w_k,   w_k = (c_u + 2 alpha/dt) u_k + (c_v + alpha) v_k + a_k,
///   K_eff = K + (c_u + 2 alpha/dt) M,   c_u = 4/dt^2,   c_v = 4/dt,
///   a_{k+1} = c_u (u_{k+1} - u_k) - c_v v_k - a_k,   v_{k+1} = v_k + dt/2 (a_k + a_{k+1}),
/// the serial integrators::Trapezoid's recurrence term for term; t_k = t_0 + k dt.
/// K_eff is solved by a PETSc KSP set up from the options database: by default MUMPS's parallel
/// Cholesky factorization (-ksp_type preonly -pc_type cholesky -pc_factor_mat_solver_type mumps),
/// factored once; or e.g. -ksp_type cg -pc_type gamg (or hypre with -pc_hypre_type boomeramg), with
/// the rigid-body modes as GAMG's near-null space, started from the predictor
/// u_k + dt v_k + dt^2/2 a_k and stopped at -ksp_rtol (default here 1e-10).
#include <string>

#include "distributed/distributed_model.hpp"

namespace roifem::distributed {

class DistributedTrapezoid {
 public:
  /// Starts at rest at t0 (a_0 = M^-1 f(t0)). `options_prefix` selects options ("" for -ksp_type ...).
  DistributedTrapezoid(const DistributedModel& model, double dt, double t0 = 0, const std::string& options_prefix = "");
  /// One step; SolverError naming the step and t when the KSP does not converge.
  void step();
  Vec u() const { return u_.get(); }
  Vec v() const { return v_.get(); }
  double t() const { return t_; }
  long steps() const { return k_; }
  /// The KSP's iterations in the last step (1 for a direct solve), and their sum over all steps.
  PetscInt last_iterations() const { return last_iterations_; }
  long total_iterations() const { return total_iterations_; }
  /// "preonly + cholesky (mumps)", "cg + gamg, rtol 1e-10": what solves K_eff.
  std::string solver() const;
  double setup_seconds() const { return setup_s_; }
  /// Energies v^T M v / 2 and u^T K u / 2 (J) of the current state.
  double kinetic_energy() const;
  double strain_energy() const;

 private:
  const DistributedModel& model_;
  double dt_, t0_, t_;
  long k_ = 0;
  OwnedMat K_eff_;
  OwnedNullSpace rigid_;
  OwnedKsp ksp_;
  OwnedVec u_, v_, a_, f_, w_, u_next_, a_next_;
  OwnedVec product_;  // the energies' M v or K u
  PetscInt last_iterations_ = 0;
  long total_iterations_ = 0;
  double setup_s_ = 0;
};

}  // namespace roifem::distributed
