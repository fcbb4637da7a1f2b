// SPDX-License-Identifier: GPL-3.0-or-later
#include "integrators/integrator_table.hpp"

#include <cstdio>

#include "common/did_you_mean.hpp"
#include "common/errors.hpp"
#include "integrators/arkode.hpp"
#include "integrators/energy_momentum.hpp"
#include "integrators/gsl_odeiv2.hpp"
#include "integrators/ida.hpp"
#include "integrators/roi_dae.hpp"
#include "integrators/tool_dae.hpp"
#include "integrators/trapezoid.hpp"

namespace roifem::integrators {

namespace {

/// Every family's rows, in the order `compare` runs them and `--help` lists them. A new family is
/// one more line here.
std::vector<IntegratorInfo> build_table() {
  std::vector<IntegratorInfo> rows;
  for (auto* family_rows : {trapezoid_rows, energy_momentum_rows, arkode_rows, ida_rows, roi_dae_rows, tool_dae_rows, gsl_rows})
    for (IntegratorInfo& row : family_rows()) rows.push_back(std::move(row));
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
  std::string text =
      "Integrators (scenario [time] integrator, --integrators; 'nonlinear': takes a hyperelastic [material] model too "
      "(neo-hookean, ogden)):\n";
  for (const auto& info : integrator_table()) {
    std::string steps = info.fixed_step && info.adaptive ? "fixed or adaptive" : info.fixed_step ? "fixed step" : "adaptive";
    char line[160];
    std::snprintf(line, sizeof line, "  %-28s order %-2d %-8s %-17s %-20s ", info.name.c_str(), info.order,
                  info.is_explicit ? "explicit" : "implicit", steps.c_str(),
                  std::string(linear_solver_name(info.linear_solver)).c_str());
    text += line + info.summary + (info.nonlinear ? " [nonlinear]" : "") + "\n";
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
