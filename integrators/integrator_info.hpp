// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// A row of the integrator table (integrator_table.hpp): a method's name and traits, and the maker
/// that builds it. Each family's files export their rows (trapezoid_rows(), arkode_rows(), ...);
/// a row names only what differs from the defaults below.
#include <memory>
#include <string>

#include "common/types.hpp"
#include "integrators/integrator.hpp"
#include "integrators/step_control.hpp"

namespace roifem::integrators {

/// petsc: PETSc's TS (src/distributed/petsc_ts.hpp), rows that roifem-mpi compare adds (CompareOptions::extra_rows).
enum class Family { trapezoid, arkode, ida, gsl, petsc };

/// What solves the method's linear systems.
enum class LinearSolver {
  none,        ///< explicit: no linear system (a lumped M is inverted by a product)
  cholmod,     ///< K_eff = K + 2/dt C + 4/dt^2 M by a sparse Cholesky factor (CHOLMOD)
  jacobi_cg,   ///< K_eff by Jacobi-preconditioned conjugate gradients (no factor)
  klu,         ///< a sparse Newton matrix by KLU (the first-order form's; energy-momentum's, unsymmetric)
  klu_mass,    ///< the same with M given to the library as a mass matrix (a second KLU)
  schur,       ///< the Newton matrix's Schur complement by one SPD Cholesky solve of size n
  schur_mass,  ///< the same with M as a mass matrix
  dense,       ///< GSL's dense LU of the 2n x 2n Jacobian
};

/// A Runge-Kutta method's Butcher tableau.
struct ButcherTableau {
  DenseMatrix A;
  Vector b;
};

struct IntegratorInfo;
using IntegratorMaker = std::unique_ptr<Integrator> (*)(const IntegratorInfo&, const StepControl&);

struct IntegratorInfo {
  std::string name;
  Family family = Family::trapezoid;
  int order = 0;  ///< theoretical order of accuracy (GSL's msadams / msbdf: their highest)
  bool is_explicit = false;
  bool fixed_step = false;  ///< takes a fixed dt on request; a method without one runs error-controlled
                            ///< at rtol 1e-8, atol 1e-12 when asked for a fixed step
  bool adaptive = false;    ///< has an error estimate and takes rtol / atol
  LinearSolver linear_solver = LinearSolver::none;
  int method_id = -1;  ///< the family's own choice: an ARKODE table ID, IDA's maximum BDF order, an index of GSL's steppers
  ButcherTableau (*tableau)() = nullptr;  ///< explicit Runge-Kutta methods: the tableau the stability search reads
  IntegratorMaker make = nullptr;
  std::string summary;             ///< one line for --help and the README
  bool needs_tools = false;        ///< a DAE formulation of a model with tools: runs only where there are some
  bool needs_uncondensed = false;  ///< integrates a static condensation's full system: runs only on one
  bool nonlinear = false;  ///< takes a nonlinear model (model/internal_force.hpp); Integrator::takes_nonlinear says the same
  /// a method for nonlinear models (energy-momentum): it runs on a linear one when named, but
  /// `compare` lists it only on nonlinear ones, where it differs from the rest
  bool needs_nonlinear = false;
  /// integrates by the law's discrete gradient (energy-momentum): not a force that forms none
  /// (model::InternalForce::has_discrete_gradient: the nodal-pressure element at finite strain)
  bool needs_discrete_gradient = false;
};

}  // namespace roifem::integrators
