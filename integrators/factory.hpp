// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Integrators chosen by name from the one table (integrator_table.hpp; `roifem run --help` and
/// the README list it). An unknown name is an InputError listing the valid ones.
/// A fixed-step request to a method without a fixed step (IDA, GSL's adaptive-only steppers) runs
/// it error-controlled at rtol 1e-8, atol 1e-12 with dt as the output interval; an adaptive
/// request to a method without an error estimate (the trapezoidal rules) is an InputError.
#include <memory>
#include <string>

#include "integrators/integrator.hpp"
#include "integrators/integrator_table.hpp"
#include "integrators/step_control.hpp"

namespace roifem::integrators {

std::unique_ptr<Integrator> make_integrator(const std::string& name, const StepControl& control);
/// The same from a row (the table's, or one beyond it: CompareOptions::extra_rows).
std::unique_ptr<Integrator> make_integrator(const IntegratorInfo& info, const StepControl& control);
inline std::unique_ptr<Integrator> make_integrator(const std::string& name, double dt) {
  return make_integrator(name, StepControl{.dt = dt});
}
/// The theoretical order of a named method (for convergence tests and plots).
inline int integrator_order(const std::string& name) { return integrator_info(name).order; }

}  // namespace roifem::integrators
