// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// SUNLinSol_KLU behind a thin timing shell: the sparse direct solver every SUNDIALS integrator
/// here uses for its Newton matrix, with a deliberate fill-reducing ordering and the seconds its
/// setups (symbolic analysis, then numeric factorizations) take, for the reports.
/// Orderings: AMD suits the structurally symmetric Newton matrices of a mesh (I - gamma J,
/// c_j M + c K); KLU's default COLAMD orders for an unsymmetric LU and fills in more on 3D meshes
/// (see benchmarks/integrator_benchmark.cpp, setup cases, for the measured difference).
#include "integrators/sundials/handles.hpp"

namespace roifem::integrators::sundials {

enum class KluOrdering { amd = 0, colamd = 1, natural = 2 };

class KluSolver {
 public:
  KluSolver(N_Vector y, SUNMatrix A, SUNContext context, KluOrdering ordering = KluOrdering::amd);
  KluSolver(const KluSolver&) = delete;
  KluSolver& operator=(const KluSolver&) = delete;
  ~KluSolver();
  /// The solver to hand to ARKODE or IDA.
  SUNLinearSolver get() const { return shell_; }
  /// Seconds in all setups, and in the first (analysis plus the first factorization).
  double setup_seconds() const { return setup_s_; }
  double first_setup_seconds() const { return first_setup_s_; }

 private:
  static SUNLinearSolver_Type type(SUNLinearSolver);
  static int initialize(SUNLinearSolver S);
  static int setup(SUNLinearSolver S, SUNMatrix A);
  static int solve(SUNLinearSolver S, SUNMatrix A, N_Vector x, N_Vector b, double tol);
  static sunindextype last_flag(SUNLinearSolver S);
  static int free_shell(SUNLinearSolver) { return 0; }  // the owner frees it

  LinearSolver klu_;
  SUNLinearSolver shell_ = nullptr;
  double setup_s_ = 0, first_setup_s_ = 0;
  long setups_ = 0;
};

}  // namespace roifem::integrators::sundials
