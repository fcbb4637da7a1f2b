#pragma once
/// Integrators chosen by name. An unknown name is an InputError listing the valid ones.
#include <memory>
#include <string>
#include <vector>

#include "integrators/integrator.hpp"

namespace roifem::integrators {

std::vector<std::string> integrator_names();
std::unique_ptr<Integrator> make_integrator(const std::string& name, double dt);

}  // namespace roifem::integrators
