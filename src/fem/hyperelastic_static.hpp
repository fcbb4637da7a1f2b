// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// The static hyperelastic problem at load fraction s (0 < s <= 1):
///   f_int(u) = s f_ext   over the free dofs, with the prescribed values at s u_p,
/// followed from rest through the fractions asked for (ascending), each reached from the last in
/// equal increments of at most `max_increment`, each solved by Newton (solvers/newton.hpp). An
/// increment whose Newton iteration fails (no convergence, an inverted element on the way) is
/// halved, up to `max_cutbacks` times, as CalculiX's *STATIC does; then the solve stops with a
/// SolverError naming the fraction reached.
#include <vector>

#include "common/types.hpp"
#include "fem/dof_map.hpp"
#include "fem/hyperelastic_assembly.hpp"
#include "solvers/newton.hpp"

namespace roifem::fem {

struct StaticLoadOptions {
  double max_increment = 0.25;  ///< of the full load
  int max_cutbacks = 8;
  solvers::NewtonOptions newton;
};

struct StaticLoadSolution {
  double fraction = 0;
  Vector u_free;                              ///< m, over the free dofs
  std::vector<solvers::NewtonReport> newton;  ///< one per increment taken since the previous fraction
};

/// f_ext over the free dofs (N). Throws InputError for fractions not positive and ascending.
std::vector<StaticLoadSolution> solve_hyperelastic_static(const HyperelasticAssembler& assembler, const DofMap& dofs,
                                                          const Vector& f_ext, const std::vector<double>& fractions,
                                                          const StaticLoadOptions& options = {});

}  // namespace roifem::fem
