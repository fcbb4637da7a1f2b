#include "integrators/integrator_table.hpp"

#include <arkode/arkode_butcher.h>
#include <arkode/arkode_butcher_dirk.h>
#include <arkode/arkode_butcher_erk.h>

#include <cstdio>

#include "common/did_you_mean.hpp"
#include "common/errors.hpp"
#include "integrators/arkode.hpp"
#include "integrators/gsl_odeiv2.hpp"
#include "integrators/ida.hpp"
#include "integrators/roi_dae.hpp"
#include "integrators/tool_dae.hpp"
#include "integrators/trapezoid.hpp"

namespace roifem::integrators {

namespace {

ButcherTableau arkode_erk_tableau(ARKODE_ERKTableID id) {
  ARKodeButcherTable table = ARKodeButcherTable_LoadERK(id);
  ButcherTableau t{DenseMatrix(table->stages, table->stages), Vector(table->stages)};
  for (int i = 0; i < table->stages; ++i) {
    t.b[i] = table->b[i];
    for (int j = 0; j < table->stages; ++j) t.A(i, j) = table->A[i][j];
  }
  ARKodeButcherTable_Free(table);
  return t;
}

ButcherTableau classical_rk4() {
  ButcherTableau t{DenseMatrix::Zero(4, 4), Vector(4)};
  t.A(1, 0) = 0.5;
  t.A(2, 1) = 0.5;
  t.A(3, 2) = 1.0;
  t.b << 1.0 / 6, 1.0 / 3, 1.0 / 3, 1.0 / 6;
  return t;
}

/// An ARKODE implicit method in its four linear-algebra variants: KLU on J = [[0, I], [-M^-1 K,
/// -M^-1 C]], M as ARKODE's mass matrix (-mass), and the Schur-complement solver (-schur).
void add_arkode_implicit(std::vector<IntegratorInfo>& rows, const std::string& name, int order, int table,
                         const std::string& summary) {
  const struct {
    const char* suffix;
    LinearSolver solver;
    const char* how;
  } variants[] = {{"", LinearSolver::klu, "KLU"},
                  {"-mass", LinearSolver::klu_mass, "M as ARKODE's mass matrix, KLU"},
                  {"-schur", LinearSolver::schur, "Schur-complement Cholesky"},
                  {"-mass-schur", LinearSolver::schur_mass, "M as mass matrix, Schur-complement Cholesky"}};
  const bool has_error_estimate = table >= 0;  // the user trapezoid table has no embedding
  for (const auto& v : variants)
    rows.push_back({.name = name + v.suffix,
                    .family = Family::arkode,
                    .order = order,
                    .is_explicit = false,
                    .fixed_step = true,
                    .adaptive = has_error_estimate,
                    .linear_solver = v.solver,
                    .method_id = table,
                    .tableau = nullptr,
                    .make = make_arkode,
                    .summary = summary + " (" + v.how + ")"});
}

std::vector<IntegratorInfo> build_table() {
  using LS = LinearSolver;
  std::vector<IntegratorInfo> rows{
      {.name = "trapezoid",
       .family = Family::trapezoid,
       .order = 2,
       .is_explicit = false,
       .fixed_step = true,
       .adaptive = false,
       .linear_solver = LS::cholmod,
       .method_id = -1,
       .tableau = nullptr,
       .make = make_trapezoid,
       .summary = "the paper's trapezoidal rule (Newmark average acceleration), K_eff factored once"},
      {.name = "trapezoid-cg",
       .family = Family::trapezoid,
       .order = 2,
       .is_explicit = false,
       .fixed_step = true,
       .adaptive = false,
       .linear_solver = LS::jacobi_cg,
       .method_id = -1,
       .tableau = nullptr,
       .make = make_trapezoid,
       .summary = "the same rule with K_eff solved by Jacobi-preconditioned CG (no factor; for the largest brains)"},
  };
  auto erk = [&](const char* name, int order, ARKODE_ERKTableID id, ButcherTableau (*tableau)(), const char* summary) {
    rows.push_back({.name = name,
                    .family = Family::arkode,
                    .order = order,
                    .is_explicit = true,
                    .fixed_step = true,
                    .adaptive = true,
                    .linear_solver = LS::none,
                    .method_id = id,
                    .tableau = tableau,
                    .make = make_arkode,
                    .summary = summary});
  };
  erk(
      "arkode-erk2", 2, ARKODE_HEUN_EULER_2_1_2, [] { return arkode_erk_tableau(ARKODE_HEUN_EULER_2_1_2); },
      "ARKODE explicit Heun-Euler 2(1)");
  erk(
      "arkode-erk3", 3, ARKODE_BOGACKI_SHAMPINE_4_2_3, [] { return arkode_erk_tableau(ARKODE_BOGACKI_SHAMPINE_4_2_3); },
      "ARKODE explicit Bogacki-Shampine 3(2)");
  erk(
      "arkode-erk4", 4, ARKODE_ZONNEVELD_5_3_4, [] { return arkode_erk_tableau(ARKODE_ZONNEVELD_5_3_4); },
      "ARKODE explicit Zonneveld 4(3)");
  erk(
      "arkode-erk5", 5, ARKODE_DORMAND_PRINCE_7_4_5, [] { return arkode_erk_tableau(ARKODE_DORMAND_PRINCE_7_4_5); },
      "ARKODE explicit Dormand-Prince 5(4)");
  add_arkode_implicit(rows, "arkode-sdirk2", 2, ARKODE_SDIRK_2_1_2, "ARKODE implicit SDIRK-2-1-2");
  add_arkode_implicit(rows, "arkode-ark3", 3, ARKODE_ARK324L2SA_DIRK_4_2_3, "ARKODE implicit ARK324 (its DIRK table)");
  add_arkode_implicit(rows, "arkode-esdirk4", 4, ARKODE_ESDIRK436L2SA_6_3_4, "ARKODE implicit ESDIRK436L2SA");
  add_arkode_implicit(rows, "arkode-esdirk5", 5, ARKODE_ESDIRK547L2SA_7_4_5, "ARKODE implicit ESDIRK547L2SA");
  add_arkode_implicit(rows, "arkode-trapezoid", 2, -1, "ARKODE with the trapezoidal rule as a user Butcher table, fixed step");
  rows.push_back({.name = "ida-bdf5",
                  .family = Family::ida,
                  .order = 5,
                  .is_explicit = false,
                  .fixed_step = false,
                  .adaptive = true,
                  .linear_solver = LS::klu,
                  .method_id = 5,
                  .tableau = nullptr,
                  .make = make_ida,
                  .summary = "IDA, variable-order BDF 1-5 on the residual form, KLU"});
  rows.push_back({.name = "ida-bdf2",
                  .family = Family::ida,
                  .order = 2,
                  .is_explicit = false,
                  .fixed_step = false,
                  .adaptive = true,
                  .linear_solver = LS::klu,
                  .method_id = 2,
                  .tableau = nullptr,
                  .make = make_ida,
                  .summary = "IDA with BDF capped at order 2 (A-stable)"});
  rows.push_back({.name = "ida-roi-dae",
                  .family = Family::ida,
                  .order = 5,
                  .is_explicit = false,
                  .fixed_step = false,
                  .adaptive = true,
                  .linear_solver = LS::klu,
                  .method_id = 5,
                  .tableau = nullptr,
                  .make = make_roi_dae,
                  .summary = "IDA on the ROI model uncondensed: the static part kept as algebraic unknowns "
                             "(scenarios with an [roi] and static condensation; tools eliminated), KLU",
                  .needs_uncondensed = true});
  auto tool_dae = [&](const char* name, ToolFormulation formulation, const char* summary) {
    rows.push_back({.name = name,
                    .family = Family::ida,
                    .order = 5,
                    .is_explicit = false,
                    .fixed_step = false,
                    .adaptive = true,
                    .linear_solver = LS::klu,
                    .method_id = static_cast<int>(formulation),
                    .tableau = nullptr,
                    .make = make_tool_dae,
                    .summary = summary,
                    .needs_tools = true});
  };
  tool_dae("ida-index3", ToolFormulation::index3,
           "IDA on the tools' DAE, index 3 (position constraints; velocities and multipliers out of the error test), KLU");
  tool_dae("ida-ggl", ToolFormulation::ggl,
           "IDA on the tools' DAE, GGL-stabilized index 2 (position and velocity constraints), KLU");
  tool_dae("ida-index1", ToolFormulation::index1,
           "IDA on the tools' DAE, index 1 (acceleration constraint, Baumgarte-stabilized, a = 100/s), KLU");
  auto gsl = [&](const char* name, int order, bool is_explicit, bool fixed, LS solver, ButcherTableau (*tableau)(),
                 IntegratorMaker make, const char* summary) {
    rows.push_back({.name = name,
                    .family = Family::gsl,
                    .order = order,
                    .is_explicit = is_explicit,
                    .fixed_step = fixed,
                    .adaptive = true,
                    .linear_solver = solver,
                    .method_id = -1,
                    .tableau = tableau,
                    .make = make,
                    .summary = summary});
  };
  gsl(
      "gsl-bsimp", 6, false, false, LS::dense, nullptr,
      [](const IntegratorInfo& i, const StepControl& c) { return make_gsl(i, gsl_odeiv2_step_bsimp, c); },
      "GSL implicit Bulirsch-Stoer (Bader-Deuflhard), dense Jacobian");
  gsl(
      "gsl-msadams", 12, true, false, LS::none, nullptr,
      [](const IntegratorInfo& i, const StepControl& c) { return make_gsl(i, gsl_odeiv2_step_msadams, c); },
      "GSL variable-order Adams (orders 1-12, explicit)");
  gsl(
      "gsl-msbdf", 5, false, false, LS::dense, nullptr,
      [](const IntegratorInfo& i, const StepControl& c) { return make_gsl(i, gsl_odeiv2_step_msbdf, c); },
      "GSL variable-order BDF (orders 1-5), dense Jacobian");
  gsl(
      "gsl-rk4", 4, true, true, LS::none, classical_rk4,
      [](const IntegratorInfo& i, const StepControl& c) { return make_gsl(i, gsl_odeiv2_step_rk4, c); },
      "GSL classical Runge-Kutta 4");
  gsl(
      "gsl-rk4imp", 4, false, true, LS::dense, nullptr,
      [](const IntegratorInfo& i, const StepControl& c) { return make_gsl(i, gsl_odeiv2_step_rk4imp, c); },
      "GSL implicit Gauss-Legendre 4, dense Jacobian");
  gsl(
      "gsl-rk8pd", 8, true, false, LS::none, nullptr,
      [](const IntegratorInfo& i, const StepControl& c) { return make_gsl(i, gsl_odeiv2_step_rk8pd, c); },
      "GSL explicit Prince-Dormand 8(9)");
  return rows;
}

}  // namespace

std::span<const IntegratorInfo> integrator_table() {
  static const std::vector<IntegratorInfo> table = build_table();
  return table;
}

const IntegratorInfo& integrator_info(std::string_view name) {
  for (const auto& info : integrator_table())
    if (info.name == name) return info;
  throw InputError("integrator '" + std::string(name) + "' is unknown" + did_you_mean(name, integrator_names()) +
                   " (valid: " + integrator_name_list() + ")");
}

std::vector<std::string> integrator_names() {
  std::vector<std::string> names;
  for (const auto& info : integrator_table()) names.push_back(info.name);
  return names;
}

std::string integrator_name_list() {
  std::string list;
  for (const auto& info : integrator_table()) list += (list.empty() ? "" : ", ") + info.name;
  return list;
}

std::string integrator_table_text() {
  std::string text = "Integrators (scenario [time] integrator, --integrators):\n";
  for (const auto& info : integrator_table()) {
    std::string steps = info.fixed_step && info.adaptive ? "fixed or adaptive" : info.fixed_step ? "fixed step" : "adaptive";
    char line[160];
    std::snprintf(line, sizeof line, "  %-28s order %-2d %-8s %-17s %-20s ", info.name.c_str(), info.order,
                  info.is_explicit ? "explicit" : "implicit", steps.c_str(),
                  std::string(linear_solver_name(info.linear_solver)).c_str());
    text += line + info.summary + "\n";
  }
  return text;
}

std::string_view family_name(Family family) {
  switch (family) {
    case Family::trapezoid:
      return "trapezoid";
    case Family::arkode:
      return "ARKODE";
    case Family::ida:
      return "IDA";
    case Family::gsl:
      return "GSL odeiv2";
    case Family::petsc:
      return "PETSc TS";
  }
  return "?";
}

std::string_view linear_solver_name(LinearSolver solver) {
  switch (solver) {
    case LinearSolver::none:
      return "none";
    case LinearSolver::cholmod:
      return "CHOLMOD";
    case LinearSolver::jacobi_cg:
      return "Jacobi-CG";
    case LinearSolver::klu:
      return "KLU";
    case LinearSolver::klu_mass:
      return "KLU + mass KLU";
    case LinearSolver::schur:
      return "Schur-Cholesky";
    case LinearSolver::schur_mass:
      return "Schur-Cholesky, mass";
    case LinearSolver::dense:
      return "dense LU";
  }
  return "?";
}

}  // namespace roifem::integrators
