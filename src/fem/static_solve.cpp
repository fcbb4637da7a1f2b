// SPDX-License-Identifier: GPL-3.0-or-later
#include "fem/static_solve.hpp"

#include "common/errors.hpp"
#include "common/number_text.hpp"

namespace roifem::fem {

void factorize_stiffness(solvers::Cholesky& solver, const SparseMatrix& K, const DofMap& dofs, const std::string& what) {
  if (dofs.num_constrained() == 0)
    throw ModelError(what +
                     " is singular: no node is fixed, so the body can move as a rigid body "
                     "(fix a named set, e.g. 'base')");
  try {
    solver.factorize(K);
  } catch (const solvers::NotPositiveDefinite& e) {
    if (e.column >= 0 && e.column < dofs.num_free()) {
      const Index full = dofs.full_dof(e.column);
      throw ModelError(what + " is not positive definite: the factorization stopped at node " + std::to_string(full / 3) +
                       ", component " + "xyz"[full % 3] + " (is that part of the mesh held by any fixed node?)");
    }
    throw ModelError(what + " is singular (reciprocal condition " + number_text(e.rcond) +
                     "): a part of the mesh is free to move as a rigid body; fix nodes on every piece");
  }
}

Vector solve_static(const SparseMatrix& K, const Vector& f, const DofMap& dofs) {
  solvers::Cholesky solver;
  factorize_stiffness(solver, K, dofs);
  return solver.solve(f);
}

}  // namespace roifem::fem
