#pragma once
/// Integrators chosen by name. An unknown name is an InputError listing the valid ones.
///   trapezoid                 the hand-written trapezoidal rule (Newmark average acceleration)
///   trapezoid-cg              the same with K_eff solved by Jacobi-preconditioned CG (no factor:
///                             for brains whose factor does not fit in memory; ~20x slower)
///   arkode-erk2 .. erk5       ARKODE explicit RK: Heun-Euler 2, Bogacki-Shampine 3, Zonneveld 4, Dormand-Prince 5
///   arkode-sdirk2, -ark3, -esdirk4, -esdirk5   ARKODE implicit: SDIRK-2-1-2, ARK324 (implicit table),
///                             ESDIRK436L2SA (order 4), ESDIRK547L2SA (order 5); KLU, linear
///   arkode-trapezoid          ARKODE with the trapezoidal rule as a user Butcher table
///   <implicit>-mass           the same with M given to ARKODE as a mass matrix
///   <implicit>[-mass]-schur   the same with the Schur-complement Cholesky solver instead of KLU
///   ida-bdf5, ida-bdf2        IDA, variable-order BDF up to 5 / capped at 2 (A-stable); always
///                             error-controlled (rtol, atol; a fixed-step request runs at 1e-8, 1e-12)
///   gsl-rk4, gsl-rk8pd, gsl-rk4imp, gsl-bsimp, gsl-msadams, gsl-msbdf   GSL odeiv2 (dense Jacobian,
///                             systems up to max_gsl_dofs)
#include <memory>
#include <string>
#include <vector>

#include "integrators/arkode.hpp"
#include "integrators/integrator.hpp"

namespace roifem::integrators {

std::vector<std::string> integrator_names();
/// Fixed step control.dt, or adaptive (rtol, atol) where the method has an error estimate.
std::unique_ptr<Integrator> make_integrator(const std::string& name, const StepControl& control);
inline std::unique_ptr<Integrator> make_integrator(const std::string& name, double dt) {
  return make_integrator(name, StepControl{.dt = dt});
}
/// The description of a named ARKODE method (to vary one setting, e.g. the KLU ordering).
ArkodeMethod arkode_method(const std::string& name);
/// The theoretical order of a named method (for convergence tests and plots).
int integrator_order(const std::string& name);

}  // namespace roifem::integrators
