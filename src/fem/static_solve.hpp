// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// The static problem K u = f over the free dofs, with errors that name the model's fault.
#include "common/types.hpp"
#include "fem/dof_map.hpp"
#include "solvers/cholesky.hpp"

namespace roifem::fem {

/// Factorizes K (analysing its pattern once); a K that is not positive definite becomes a
/// ModelError naming the node and component where the factorization stopped, or the rigid-body
/// modes left free. `what` names the matrix in messages ("stiffness matrix", "static part K_ss").
void factorize_stiffness(solvers::Cholesky& solver, const SparseMatrix& K, const DofMap& dofs,
                         const std::string& what = "stiffness matrix");

/// Solves K u = f; throws ModelError when there is no Dirichlet condition at all (rigid-body
/// modes make K singular) or when K is not positive definite.
Vector solve_static(const SparseMatrix& K, const Vector& f, const DofMap& dofs);

}  // namespace roifem::fem
