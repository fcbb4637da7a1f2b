// SPDX-License-Identifier: GPL-3.0-or-later
#include "model/prescribed_motion.hpp"

#include "common/errors.hpp"

namespace roifem::model {

namespace {

/// S: 3T x #p, summing each tool's attached dofs per component (G = S^T g spreads them back).
SparseMatrix summation(const std::vector<ToolDofs>& tools, Index num_tool_dofs) {
  SparseMatrix S(3 * static_cast<Index>(tools.size()), num_tool_dofs);
  std::vector<Eigen::Triplet<double>> ones;
  Index column = 0;
  for (std::size_t a = 0; a < tools.size(); ++a)
    for (std::size_t k = 0; k < tools[a].dofs.size(); ++k) ones.emplace_back(3 * static_cast<Index>(a) + k % 3, column++, 1.0);
  S.setFromTriplets(ones.begin(), ones.end());
  return S;
}

bool couples(const SparseMatrix& A, const std::vector<char>& is_tool) {
  for (Index j = 0; j < A.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(A, j); it; ++it)
      if (it.value() != 0 && is_tool[static_cast<std::size_t>(it.row())] != is_tool[static_cast<std::size_t>(it.col())])
        return true;
  return false;
}

}  // namespace

SparseMatrix selection_matrix(const std::vector<Index>& columns, Index n) {
  SparseMatrix P(static_cast<Index>(columns.size()), n);
  std::vector<Eigen::Triplet<double>> ones;
  for (std::size_t i = 0; i < columns.size(); ++i) ones.emplace_back(static_cast<Index>(i), columns[i], 1.0);
  P.setFromTriplets(ones.begin(), ones.end());
  return P;
}

ToolElimination eliminate_tools(const SecondOrderSystem& all, const std::vector<ToolDofs>& tools) {
  const Index n = all.size();
  std::vector<char> is_tool(static_cast<std::size_t>(n), 0);
  std::vector<Index> tool_dofs;
  for (const auto& t : tools) {
    if (t.dofs.empty() || t.dofs.size() % 3 != 0) throw Error("internal: tool '" + t.tool.name + "' without three dofs per node");
    for (const Index i : t.dofs) {
      if (is_tool[static_cast<std::size_t>(i)]) throw Error("internal: a dof held by two tools");
      is_tool[static_cast<std::size_t>(i)] = 1;
      tool_dofs.push_back(i);
    }
  }
  if (couples(all.M, is_tool) || couples(all.C, is_tool))
    throw ModelError("tools: M and C must not couple a tool's dofs to the others (lumped mass and damping)");
  ToolElimination out;
  for (Index i = 0; i < n; ++i)
    if (!is_tool[static_cast<std::size_t>(i)]) out.kept.push_back(i);
  const SparseMatrix P_f = selection_matrix(out.kept, n), P_p = selection_matrix(tool_dofs, n);
  const SparseMatrix S = summation(tools, static_cast<Index>(tool_dofs.size()));
  const SparseMatrix K_fp = P_f * all.K * SparseMatrix(P_p.transpose());
  const SparseMatrix K_pp = P_p * all.K * SparseMatrix(P_p.transpose());

  SecondOrderSystem& sys = out.system;
  sys.K = P_f * all.K * SparseMatrix(P_f.transpose());
  sys.M = P_f * all.M * SparseMatrix(P_f.transpose());
  sys.C = P_f * all.C * SparseMatrix(P_f.transpose());
  sys.damping = all.damping;
  const Index n_f = static_cast<Index>(out.kept.size()), rows = S.rows();
  sys.load = LoadHistory(n_f);
  LoadHistory at_tools(rows);
  for (const auto& term : all.load.terms()) {
    sys.load.add(P_f * term.pattern, term.ramp);
    at_tools.add(S * (P_p * term.pattern), term.ramp);
  }
  // -K_fp G(t): each term of a tool's path is one pattern (its direction spread) times its history.
  for (std::size_t a = 0; a < tools.size(); ++a)
    for (const auto& [direction, history] : tools[a].tool.path.terms()) {
      Vector g = Vector::Zero(rows);
      g.segment<3>(3 * static_cast<Index>(a)) = direction;
      sys.load.add(-(K_fp * (S.transpose() * g)), history);
    }
  sys.constrained = std::make_shared<const ConstrainedForm>(ConstrainedForm{.all = all, .tools = tools, .kept = out.kept});
  std::vector<Tool> described;
  described.reserve(tools.size());
  for (const auto& t : tools) described.push_back(t.tool);
  out.tools = ToolSet(std::move(described), SparseMatrix(S * K_fp.transpose()), DenseMatrix(S * K_pp * S.transpose()),
                      std::move(at_tools));
  return out;
}

}  // namespace roifem::model
