// SPDX-License-Identifier: GPL-3.0-or-later
#include "distributed/distributed_trapezoid.hpp"

#include "common/errors.hpp"
#include "common/number_text.hpp"
#include "common/timer.hpp"
#include "model/time_grid.hpp"

namespace roifem::distributed {

DistributedTrapezoid::DistributedTrapezoid(const DistributedModel& model, double dt, double t0, const std::string& options_prefix)
    : model_(model), dt_(dt), t0_(t0), t_(t0) {
  model::check_time_step(dt, "roifem-mpi");
  const Stopwatch clock;
  const double c_u = 4.0 / (dt * dt), c_m = c_u + 2.0 * model.alpha / dt;
  check(MatDuplicate(model.K.get(), MAT_COPY_VALUES, K_eff_.out()), "MatDuplicate");
  w_ = model.new_vector();
  check(VecAXPY(w_.get(), c_m, model.mass.get()), "VecAXPY");
  check(MatDiagonalSet(K_eff_.get(), w_.get(), ADD_VALUES), "MatDiagonalSet");
  check(MatSetOption(K_eff_.get(), MAT_SPD, PETSC_TRUE), "MatSetOption(MAT_SPD)");
  check(MatNullSpaceCreateRigidBody(model.coordinates.get(), rigid_.out()), "MatNullSpaceCreateRigidBody");
  check(MatSetNearNullSpace(K_eff_.get(), rigid_.get()), "MatSetNearNullSpace");
  MPI_Comm comm = PETSC_COMM_WORLD;
  check(PetscObjectGetComm(reinterpret_cast<PetscObject>(model.K.get()), &comm), "PetscObjectGetComm");
  check(KSPCreate(comm, ksp_.out()), "KSPCreate");
  if (!options_prefix.empty()) check(KSPSetOptionsPrefix(ksp_.get(), options_prefix.c_str()), "KSPSetOptionsPrefix");
  check(KSPSetOperators(ksp_.get(), K_eff_.get(), K_eff_.get()), "KSPSetOperators");
  check(KSPSetType(ksp_.get(), KSPPREONLY), "KSPSetType");
  PC pc = nullptr;
  check(KSPGetPC(ksp_.get(), &pc), "KSPGetPC");
  check(PCSetType(pc, PCCHOLESKY), "PCSetType");
  check(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS), "PCFactorSetMatSolverType");
  check(KSPSetTolerances(ksp_.get(), 1e-10, 1e-50, PETSC_DEFAULT, 10000), "KSPSetTolerances");
  check(KSPSetFromOptions(ksp_.get()), "KSPSetFromOptions");
  KSPType type = nullptr;
  check(KSPGetType(ksp_.get(), &type), "KSPGetType");
  if (std::string(type) != KSPPREONLY) check(KSPSetInitialGuessNonzero(ksp_.get(), PETSC_TRUE), "KSPSetInitialGuessNonzero");
  check(KSPSetUp(ksp_.get()), "KSPSetUp (the factorization or the preconditioner of K_eff)");
  u_ = model.new_vector();
  v_ = model.new_vector();
  a_ = model.new_vector();
  f_ = model.new_vector();
  u_next_ = model.new_vector();
  a_next_ = model.new_vector();
  product_ = model.new_vector();
  // At rest: M a_0 = f(t0).
  model.load_at(t0, f_.get());
  check(VecPointwiseDivide(a_.get(), f_.get(), model.mass.get()), "VecPointwiseDivide");
  setup_s_ = clock.seconds();
}

void DistributedTrapezoid::step() {
  const double dt = dt_, c_u = 4.0 / (dt * dt), c_v = 4.0 / dt, alpha = model_.alpha;
  ++k_;
  t_ = t0_ + static_cast<double>(k_) * dt;
  // w = (c_u + 2 alpha/dt) u + (c_v + alpha) v + a;  rhs f = f(t) + M w.
  check(VecAXPBYPCZ(w_.get(), c_u + 2.0 * alpha / dt, c_v + alpha, 0.0, u_.get(), v_.get()), "VecAXPBYPCZ");
  check(VecAXPY(w_.get(), 1.0, a_.get()), "VecAXPY");
  model_.load_at(t_, f_.get());
  check(VecPointwiseMult(w_.get(), w_.get(), model_.mass.get()), "VecPointwiseMult");
  check(VecAXPY(f_.get(), 1.0, w_.get()), "VecAXPY");
  // The predictor u + dt v + dt^2/2 a starts an iterative solve (a direct one ignores it).
  check(VecWAXPY(u_next_.get(), dt, v_.get(), u_.get()), "VecWAXPY");
  check(VecAXPY(u_next_.get(), 0.5 * dt * dt, a_.get()), "VecAXPY");
  check(KSPSolve(ksp_.get(), f_.get(), u_next_.get()), "KSPSolve");
  KSPConvergedReason reason = KSP_CONVERGED_ITERATING;
  check(KSPGetConvergedReason(ksp_.get(), &reason), "KSPGetConvergedReason");
  check(KSPGetIterationNumber(ksp_.get(), &last_iterations_), "KSPGetIterationNumber");
  if (reason < 0)
    throw SolverError("roifem-mpi: step " + std::to_string(k_) + ", t = " + number_text(t_) + " s: " + solver() +
                      " did not converge (" + KSPConvergedReasons[reason] + " after " + std::to_string(last_iterations_) +
                      " iterations)");
  total_iterations_ += std::max<PetscInt>(last_iterations_, 1);
  // a_next = c_u (u_next - u) - c_v v - a;  v += dt/2 (a + a_next);  u = u_next.
  check(VecWAXPY(a_next_.get(), -1.0, u_.get(), u_next_.get()), "VecWAXPY");
  check(VecAXPBYPCZ(a_next_.get(), -c_v, -1.0, c_u, v_.get(), a_.get()), "VecAXPBYPCZ");
  check(VecAXPBYPCZ(v_.get(), 0.5 * dt, 0.5 * dt, 1.0, a_.get(), a_next_.get()), "VecAXPBYPCZ");
  std::swap(a_, a_next_);
  check(VecCopy(u_next_.get(), u_.get()), "VecCopy");
  PetscReal norm = 0;
  check(VecNorm(u_.get(), NORM_INFINITY, &norm), "VecNorm");
  if (PetscIsInfOrNanReal(norm))
    throw SolverError("roifem-mpi: non-finite displacement at step " + std::to_string(k_) + ", t = " + number_text(t_) + " s");
}

std::string DistributedTrapezoid::solver() const {
  KSPType ksp_type = nullptr;
  PCType pc_type = nullptr;
  PC pc = nullptr;
  KSPGetType(ksp_.get(), &ksp_type);
  KSPGetPC(ksp_.get(), &pc);
  PCGetType(pc, &pc_type);
  std::string text = std::string(ksp_type ? ksp_type : "?") + " + " + (pc_type ? pc_type : "?");
  MatSolverType package = nullptr;
  if (PCFactorGetMatSolverType(pc, &package) == 0 && package) text += " (" + std::string(package) + ")";
  if (std::string(ksp_type ? ksp_type : "") != KSPPREONLY) {
    PetscReal rtol = 0;
    KSPGetTolerances(ksp_.get(), &rtol, nullptr, nullptr, nullptr);
    text += ", rtol " + number_text(rtol);
  }
  return text;
}

double DistributedTrapezoid::kinetic_energy() const {
  check(VecPointwiseMult(product_.get(), model_.mass.get(), v_.get()), "VecPointwiseMult");
  PetscScalar e = 0;
  check(VecDot(product_.get(), v_.get(), &e), "VecDot");
  return 0.5 * e;
}

double DistributedTrapezoid::strain_energy() const {
  check(MatMult(model_.K.get(), u_.get(), product_.get()), "MatMult");
  PetscScalar e = 0;
  check(VecDot(product_.get(), u_.get(), &e), "VecDot");
  return 0.5 * e;
}

}  // namespace roifem::distributed
