#include "integrators/factory.hpp"

#include <arkode/arkode_butcher_dirk.h>
#include <arkode/arkode_butcher_erk.h>

#include <map>

#include "common/errors.hpp"
#include "integrators/gsl_odeiv2.hpp"
#include "integrators/ida.hpp"
#include "integrators/trapezoid.hpp"

namespace roifem::integrators {

namespace {

const std::map<std::string, ArkodeMethod>& arkode_methods() {
  static const std::map<std::string, ArkodeMethod> methods = [] {
    std::map<std::string, ArkodeMethod> m;
    auto add = [&](const std::string& name, bool implicit, int table, int order, bool trapezoid = false) {
      m[name] = {name, implicit, table, trapezoid, false, false, order};
      if (!implicit) return;
      m[name + "-mass"] = {name + "-mass", implicit, table, trapezoid, true, false, order};
      m[name + "-schur"] = {name + "-schur", implicit, table, trapezoid, false, true, order};
      m[name + "-mass-schur"] = {name + "-mass-schur", implicit, table, trapezoid, true, true, order};
    };
    add("arkode-erk2", false, ARKODE_HEUN_EULER_2_1_2, 2);
    add("arkode-erk3", false, ARKODE_BOGACKI_SHAMPINE_4_2_3, 3);
    add("arkode-erk4", false, ARKODE_ZONNEVELD_5_3_4, 4);
    add("arkode-erk5", false, ARKODE_DORMAND_PRINCE_7_4_5, 5);
    add("arkode-sdirk2", true, ARKODE_SDIRK_2_1_2, 2);
    add("arkode-ark3", true, ARKODE_ARK324L2SA_DIRK_4_2_3, 3);
    add("arkode-esdirk4", true, ARKODE_ESDIRK436L2SA_6_3_4, 4);
    add("arkode-esdirk5", true, ARKODE_ESDIRK547L2SA_7_4_5, 5);
    add("arkode-trapezoid", true, -1, 2, true);
    return m;
  }();
  return methods;
}

struct GslMethod {
  const gsl_odeiv2_step_type* type;
  int order;
};

const std::map<std::string, GslMethod>& gsl_methods() {
  static const std::map<std::string, GslMethod> methods = {
      {"gsl-rk4", {gsl_odeiv2_step_rk4, 4}},       {"gsl-rk8pd", {gsl_odeiv2_step_rk8pd, 8}},
      {"gsl-rk4imp", {gsl_odeiv2_step_rk4imp, 4}}, {"gsl-bsimp", {gsl_odeiv2_step_bsimp, 6}},
      {"gsl-msadams", {gsl_odeiv2_step_msadams, 12}}, {"gsl-msbdf", {gsl_odeiv2_step_msbdf, 5}}};
  return methods;
}

}  // namespace

ArkodeMethod arkode_method(const std::string& name) {
  const auto it = arkode_methods().find(name);
  if (it == arkode_methods().end()) throw InputError("unknown ARKODE method '" + name + "'");
  return it->second;
}

std::vector<std::string> integrator_names() {
  std::vector<std::string> names{"trapezoid", "trapezoid-cg", "ida-bdf5", "ida-bdf2"};
  for (const auto& [name, method] : arkode_methods()) names.push_back(name);
  for (const auto& [name, method] : gsl_methods()) names.push_back(name);
  return names;
}

std::unique_ptr<Integrator> make_integrator(const std::string& name, const StepControl& control) {
  if (name == "trapezoid") {
    if (control.adaptive) throw InputError("integrator 'trapezoid' has a fixed step only (no rtol/atol)");
    return std::make_unique<Trapezoid>(control.dt);
  }
  if (name == "trapezoid-cg") {
    if (control.adaptive) throw InputError("integrator 'trapezoid-cg' has a fixed step only (no rtol/atol)");
    return std::make_unique<Trapezoid>(control.dt, solvers::CgSettings{});
  }
  if (name == "ida-bdf5" || name == "ida-bdf2") {
    StepControl adaptive = control;
    if (!control.adaptive) {  // IDA is always error-controlled: a "fixed step" request gets tight tolerances
      adaptive.rtol = 1e-8;
      adaptive.atol = 1e-12;
    }
    return std::make_unique<Ida>(name, name == "ida-bdf5" ? 5 : 2, adaptive);
  }
  if (auto it = gsl_methods().find(name); it != gsl_methods().end())
    return std::make_unique<GslOdeiv2>(name, it->second.type, control);
  if (auto it = arkode_methods().find(name); it != arkode_methods().end()) {
    if (control.adaptive && it->second.trapezoid)
      throw InputError("integrator '" + name + "' has no embedded error estimate: fixed step only");
    return std::make_unique<Arkode>(it->second, control);
  }
  std::string valid;
  for (const auto& n : integrator_names()) valid += (valid.empty() ? "" : ", ") + n;
  throw InputError("integrator '" + name + "' is unknown (valid: " + valid + ")");
}

int integrator_order(const std::string& name) {
  if (name == "trapezoid" || name == "trapezoid-cg" || name == "ida-bdf2") return 2;
  if (name == "ida-bdf5") return 5;
  if (auto it = arkode_methods().find(name); it != arkode_methods().end()) return it->second.order;
  if (auto it = gsl_methods().find(name); it != gsl_methods().end()) return it->second.order;
  throw InputError("integrator '" + name + "' is unknown");
}

}  // namespace roifem::integrators
