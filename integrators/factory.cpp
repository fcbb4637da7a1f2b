#include "integrators/factory.hpp"

#include "common/errors.hpp"
#include "integrators/trapezoid.hpp"

namespace roifem::integrators {

std::vector<std::string> integrator_names() { return {"trapezoid"}; }

std::unique_ptr<Integrator> make_integrator(const std::string& name, double dt) {
  if (name == "trapezoid") return std::make_unique<Trapezoid>(dt);
  std::string valid;
  for (const auto& n : integrator_names()) valid += (valid.empty() ? "" : ", ") + n;
  throw InputError("integrator '" + name + "' is unknown (valid: " + valid + ")");
}

}  // namespace roifem::integrators
