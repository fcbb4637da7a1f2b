#pragma once
/// The semi-discrete equations of motion every integrator solves:
///   M u'' + C u' + K u = f(t)
/// M symmetric positive definite (lumped: diagonal), C = alpha M, K symmetric positive definite.
/// The full model and a condensed ROI model are both of this form.
#include "common/types.hpp"
#include "model/load_history.hpp"

namespace roifem::model {

struct SecondOrderSystem {
  SparseMatrix M, C, K;
  LoadHistory load;
  Index size() const { return K.rows(); }
};

/// Displacement and velocity at time t.
struct State {
  double t = 0;
  Vector u, v;
};

/// A diagonal as a sparse matrix.
SparseMatrix diagonal_matrix(const Vector& d);

/// Energies of a state: kinetic v^T M v / 2 and strain u^T K u / 2 (J).
double kinetic_energy(const SecondOrderSystem& sys, const State& s);
double strain_energy(const SecondOrderSystem& sys, const State& s);

}  // namespace roifem::model
