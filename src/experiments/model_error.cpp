// SPDX-License-Identifier: GPL-3.0-or-later
#include "experiments/model_error.hpp"

#include <ostream>

#include "common/errors.hpp"
#include "common/format.hpp"
#include "experiments/calculix_static.hpp"
#include "experiments/convergence_study.hpp"
#include "fem/loads.hpp"
#include "fem/static_solve.hpp"

namespace roifem::experiments {

namespace {

double max_nodal_norm(const Vector& u) {
  double m = 0;
  for (Index n = 0; n < u.size() / 3; ++n) m = std::max(m, u.segment<3>(3 * n).norm());
  return m;
}

}  // namespace

ModelErrorStudy measure_model_error(const mesh::TetMesh& mesh, const fem::Material& material,
                                    const std::vector<std::string>& fixed_sets, const std::vector<model::SetLoad>& loads,
                                    const std::vector<double>& fractions, const std::filesystem::path& work_dir,
                                    std::ostream& log) {
  CalculixProblem problem{.mesh = &mesh, .material = material, .fixed_nodes = {}, .forces = Vector::Zero(3 * mesh.num_nodes())};
  std::vector<model::SetLoad> held;  // the loads at their full value, for roifem's static solve
  for (const auto& load : loads) {
    if (load.gravity) throw InputError("the model-error study takes set forces only, not gravity");
    problem.forces += fem::set_force(mesh, load.set, load.force);
    held.push_back({load.set, load.force, model::Ramp{0}, std::nullopt});
  }
  for (const auto& set : fixed_sets)
    problem.fixed_nodes.insert(problem.fixed_nodes.end(), mesh.set(set).nodes.begin(), mesh.set(set).nodes.end());
  const model::FemModel full = model::build_fem_model(mesh, material, fixed_sets, held);
  const Vector u_unit = full.dofs->expand(fem::solve_static(full.system.K, full.system.load.at(1.0), *full.dofs));

  ModelErrorStudy study;
  const auto linear = solve_with_calculix(problem, {1.0}, false, work_dir, log);
  study.linear_check = max_nodal_norm(linear.front().u - u_unit) / max_nodal_norm(u_unit);
  if (study.linear_check > 1e-6)
    throw SolverError(
        format("the CalculiX deck does not reproduce roifem's small-strain answer (relative difference %.3g): "
               "see %s",
               study.linear_check, (work_dir / "linear.inp").c_str()));
  const auto nonlinear = solve_with_calculix(problem, fractions, true, work_dir, log);
  for (const auto& s : nonlinear) {
    const Vector u_lin = s.fraction * u_unit;
    ModelErrorRow row{.fraction = s.fraction,
                      .opening_linear_mm = opening_widening(mesh, u_lin) / mm,
                      .opening_nonlinear_mm = opening_widening(mesh, s.u) / mm,
                      .max_displacement_nonlinear_mm = max_nodal_norm(s.u) / mm,
                      .max_difference_mm = max_nodal_norm(u_lin - s.u) / mm};
    if (!study.within_10_percent_up_to_mm && row.relative() > 0.1) {
      // Interpolate the crossing linearly in the fraction from the previous row (or from zero).
      const double f0 = study.rows.empty() ? 0 : study.rows.back().fraction;
      const double r0 = study.rows.empty() ? 0 : study.rows.back().relative();
      const double f = f0 + (0.1 - r0) / (row.relative() - r0) * (row.fraction - f0);
      study.within_10_percent_up_to_mm = f * opening_widening(mesh, u_unit) / mm;
    }
    if (std::abs(s.fraction - 1) < 1e-12) {
      study.u_linear = u_lin;
      study.u_nonlinear = s.u;
      study.full_load_reached = true;
    }
    study.rows.push_back(row);
  }
  return study;
}

void print_model_error(const ModelErrorStudy& study, std::ostream& log) {
  log << format(
      "\nThe linear model against the geometrically nonlinear one (CalculiX NLGEOM, same mesh and elements; the deck's\n"
      "small-strain answer equals roifem's to %.1e)\n",
      study.linear_check);
  log << format("%8s  %12s  %12s  %9s  %14s  %14s  %9s\n", "load", "opening lin", "opening NL", "diff", "max |u| NL",
                "max |u_l-u_NL|", "of max");
  for (const auto& r : study.rows)
    log << format("%7.0f%%  %9.3f mm  %9.3f mm  %8.2f%%  %11.3f mm  %11.3f mm  %8.2f%%\n", 100 * r.fraction, r.opening_linear_mm,
                  r.opening_nonlinear_mm, 100 * r.opening_relative(), r.max_displacement_nonlinear_mm, r.max_difference_mm,
                  100 * r.relative());
  if (study.within_10_percent_up_to_mm)
    log << format(
        "The linear model stays within 10%% of the nonlinear one (largest nodal difference against the largest "
        "displacement) up to an opening of %.2f mm.\n",
        *study.within_10_percent_up_to_mm);
  else if (!study.rows.empty())
    log << format("The linear model stays within 10%% at every load reached (up to %.0f%%).\n", 100 * study.rows.back().fraction);
}

}  // namespace roifem::experiments
