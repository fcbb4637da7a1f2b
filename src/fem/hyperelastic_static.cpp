// SPDX-License-Identifier: GPL-3.0-or-later
#include "fem/hyperelastic_static.hpp"

#include <cmath>

#include "common/errors.hpp"
#include "common/format.hpp"

namespace roifem::fem {

namespace {

/// Newton at fraction s from u (overwritten when it converges).
solvers::NewtonReport solve_at(const HyperelasticAssembler& assembler, const DofMap& dofs, const Vector& f_ext, double s,
                               Vector& u, solvers::Cholesky& solver, const solvers::NewtonOptions& options) {
  const Vector u_prescribed = s * dofs.prescribed();
  auto full = [&](const Vector& x) { return Vector(u_prescribed + dofs.expand_homogeneous(x)); };
  solvers::NonlinearSystem system{.residual =
                                      [&](const Vector& x, Vector& r) {
                                        assembler.force(full(x), r);
                                        r -= s * f_ext;
                                      },
                                  .residual_and_jacobian =
                                      [&](const Vector& x, Vector& r, SparseMatrix& J) {
                                        assembler.force_and_tangent(full(x), r, J);
                                        r -= s * f_ext;
                                      }};
  // The force scale: the load, or (driven by prescribed values alone) the first residual.
  Vector r0(u.size());
  system.residual(u, r0);
  const double scale = std::max((s * f_ext).lpNorm<Eigen::Infinity>(), r0.lpNorm<Eigen::Infinity>());
  Vector x = u;
  solvers::NewtonReport report = solvers::newton_solve(system, x, scale, solver, options);
  u = x;
  return report;
}

}  // namespace

std::vector<StaticLoadSolution> solve_hyperelastic_static(const HyperelasticAssembler& assembler, const DofMap& dofs,
                                                          const Vector& f_ext, const std::vector<double>& fractions,
                                                          const StaticLoadOptions& o) {
  if (fractions.empty()) throw InputError("static solve: no load fractions asked for");
  for (std::size_t i = 0; i < fractions.size(); ++i)
    if (!(fractions[i] > 0) || (i > 0 && !(fractions[i] > fractions[i - 1])))
      throw InputError("static solve: load fractions must be positive and ascending");
  if (f_ext.size() != dofs.num_free()) throw InputError("static solve: the load does not match the free dofs");
  std::vector<StaticLoadSolution> solutions;
  solvers::Cholesky solver;
  Vector u = Vector::Zero(dofs.num_free());
  double reached = 0;
  for (const double target : fractions) {
    StaticLoadSolution solution{.fraction = target, .u_free = {}, .newton = {}};
    double increment = std::min(o.max_increment, target - reached);
    int cutbacks = 0;
    while (reached < target) {
      const double s = target - reached <= increment * (1 + 1e-12) ? target : reached + increment;
      Vector trial = u;
      try {
        solution.newton.push_back(solve_at(assembler, dofs, f_ext, s, trial, solver, o.newton));
      } catch (const Error& e) {  // no convergence, or an element inverted on the way
        if (++cutbacks > o.max_cutbacks)
          throw SolverError(
              format("static solve: stopped at %.6g of the load, the increment to %.6g failed after %d "
                     "cutbacks: %s",
                     reached, s, o.max_cutbacks, e.what()));
        increment /= 2;
        continue;
      }
      u = trial;
      reached = s;
    }
    solution.u_free = u;
    solutions.push_back(std::move(solution));
  }
  return solutions;
}

}  // namespace roifem::fem
