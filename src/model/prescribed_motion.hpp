// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Tools by elimination: the tools' dofs leave the unknowns, and their prescribed motion
/// G(t) = S^T g(t) (each attached dof follows its tool's component) enters the rest as a load,
///   M_ff u_f'' + C_ff u_f' + K_ff u_f = f_f(t) - K_fp G(t),
/// which every integrator, condensation and reduction takes unchanged (M and C lumped, so they do
/// not couple the two). The ToolSet gives each tool's force from the solution (tools.hpp).
#include <vector>

#include "model/second_order_system.hpp"
#include "model/tools.hpp"

namespace roifem::model {

struct ToolDofs {
  Tool tool;
  std::vector<Index> dofs;  ///< x, y, z of each attached node in turn, in the system's numbering
};

/// A system with tools written the other way: the tools' dofs kept as unknowns, for a DAE.
struct ConstrainedForm {
  SecondOrderSystem all;        ///< M, C lumped
  std::vector<ToolDofs> tools;  ///< their dofs in all's numbering
  std::vector<Index> kept;      ///< the eliminated system's unknown i is all's unknown kept[i]
};

struct ToolElimination {
  SecondOrderSystem system;  ///< over the kept unknowns; system.constrained describes `all`
  ToolSet tools;             ///< in the kept numbering
  std::vector<Index> kept;   ///< the system's unknowns that stay, ascending
};

/// The 0/1 matrix with a one at (i, columns[i]): picks those entries of an n-vector.
SparseMatrix selection_matrix(const std::vector<Index>& columns, Index n);

/// Eliminates the tools' dofs from `all`. Throws Error when a dof is held by two tools or when M
/// or C couples a tool dof to another (they must be lumped).
ToolElimination eliminate_tools(const SecondOrderSystem& all, const std::vector<ToolDofs>& tools);

}  // namespace roifem::model
