#include "integrators/effective_stiffness.hpp"

namespace roifem::integrators {

namespace {

SparseMatrix effective_stiffness(const model::SecondOrderSystem& system, double dt) {
  return system.K + (2.0 / dt) * system.C + (4.0 / (dt * dt)) * system.M;
}

}  // namespace

DirectSolve::DirectSolve(const model::SecondOrderSystem& system, double dt) : system_(system), rhs_(system.size()) {
  K_eff_.compute(effective_stiffness(system, dt), system.dense_block_dofs());
}

void DirectSolve::solve(const Vector& f, const Vector& w, Vector& x) {
  system_.apply_mass(w, rhs_);
  rhs_ += f;
  K_eff_.solve(rhs_, x);
}

ConjugateGradients::ConjugateGradients(const model::SecondOrderSystem& system, double dt, solvers::CgSettings settings)
    : system_(system), cg_(settings), rhs_(system.size()) {
  cg_.compute(effective_stiffness(system, dt));
}

void ConjugateGradients::solve(const Vector& f, const Vector& w, Vector& x) {
  system_.apply_mass(w, rhs_);
  rhs_ += f;
  iterations_ += cg_.solve(rhs_, x);
}

}  // namespace roifem::integrators
