// SPDX-License-Identifier: GPL-3.0-or-later
#include "integrators/factory.hpp"

#include "common/errors.hpp"

namespace roifem::integrators {

std::unique_ptr<Integrator> make_integrator(const std::string& name, const StepControl& control) {
  return make_integrator(integrator_info(name), control);
}

std::unique_ptr<Integrator> make_integrator(const IntegratorInfo& info, const StepControl& control) {
  const std::string& name = info.name;
  StepControl chosen = control;
  if (!chosen.adaptive && !info.fixed_step) {  // always error-controlled: a "fixed step" gets tight tolerances
    chosen.adaptive = true;
    chosen.rtol = 1e-8;
    chosen.atol = 1e-12;
  }
  if (chosen.adaptive && !info.adaptive)
    throw InputError("integrator '" + name + "' has a fixed step only (no error estimate, so no rtol/atol)");
  auto integrator = info.make(info, chosen);
  if (!chosen.adaptive && info.is_explicit && info.tableau && chosen.watch_stability)
    integrator->watch_stability(info, chosen.dt);
  return integrator;
}

}  // namespace roifem::integrators
