// SPDX-License-Identifier: GPL-3.0-or-later
#include "simulation/cuts/element_cuts.hpp"

#include <algorithm>
#include <numeric>

#include "condensation/reduced_model.hpp"

namespace roifem::simulation {

CutSupports cut_supports(const ScenarioModel& m) {
  const mesh::TetMesh& mesh = m.mesh;
  const fem::DofMap& dofs = *m.full.dofs;
  const auto nodes = static_cast<std::size_t>(mesh.num_nodes());
  CutSupports at{.tool_at = std::vector<std::string>(nodes),
                 .in_static_part = std::vector<bool>(nodes, false),
                 .supported = std::vector<bool>(nodes, false),
                 .fixed_somewhere = std::vector<bool>(nodes, false)};
  for (const auto& tool : m.full.tools.tools())
    for (const int n : tool.nodes) at.tool_at[static_cast<std::size_t>(n)] = tool.name;
  std::vector<bool> in_roi(nodes, m.roi_nodes.empty());
  for (const int n : m.roi_nodes) in_roi[static_cast<std::size_t>(n)] = true;
  // A node fixed in every component has no unknown to be in the ROI or the static part: a cut may
  // reach it (the tetrahedron's free dofs are the ROI's), and it supports what it belongs to.
  for (int n = 0; n < mesh.num_nodes(); ++n) {
    const auto i = static_cast<std::size_t>(n);
    at.fixed_somewhere[i] = dofs.free_dof(n, 0) < 0 || dofs.free_dof(n, 1) < 0 || dofs.free_dof(n, 2) < 0;
    const bool free_somewhere = dofs.free_dof(n, 0) >= 0 || dofs.free_dof(n, 1) >= 0 || dofs.free_dof(n, 2) >= 0;
    at.in_static_part[i] = free_somewhere && !in_roi[i];
    at.supported[i] = at.fixed_somewhere[i] || at.in_static_part[i] || !at.tool_at[i].empty();
  }
  return at;
}

ElementCuts::ElementCuts(const scenario::Scenario& sc, const ScenarioModel& m)
    : remover_(m.mesh, *m.full.dofs, m.full.materials), supports_(cut_supports(m)) {
  const fem::DofMap& dofs = *m.full.dofs;
  system_dof_.assign(static_cast<std::size_t>(dofs.num_free()), -1);
  if (m.condensation) {
    const auto& d = m.condensation->partition().d;
    for (std::size_t i = 0; i < d.size(); ++i) system_dof_[static_cast<std::size_t>(d[i])] = static_cast<Index>(i);
  } else {
    std::iota(system_dof_.begin(), system_dof_.end(), Index{0});
  }
  for (std::size_t k = 0; k < sc.loads.size(); ++k)
    if (sc.loads[k].gravity) gravity_.emplace_back(k, *sc.loads[k].gravity);
}

std::optional<std::string> ElementCuts::refusal_to_remove(const mesh::TetMesh& mesh, Index e,
                                                          const std::vector<int>& hand) const {
  for (const int n : mesh.tets[static_cast<std::size_t>(e)]) {
    const auto i = static_cast<std::size_t>(n);
    if (supports_.in_static_part[i])
      return "which touches node " + std::to_string(n) +
             " of the static part: a cut stays inside the ROI, whose condensation it changes in place (a larger [roi], or "
             "cut nearer its target)";
    if (!supports_.tool_at[i].empty())
      return "which holds node " + std::to_string(n) + " of tool '" + supports_.tool_at[i] +
             "': a cut stays clear of the tools' nodes";
    if (std::binary_search(hand.begin(), hand.end(), n))
      return "which holds node " + std::to_string(n) +
             " of the hand: a cut stays clear of the hand (release, or cut farther from it)";
  }
  return std::nullopt;
}

std::optional<std::string> ElementCuts::refusal_to_split(const mesh::TetMesh& mesh, int node, Index moved) const {
  const auto i = static_cast<std::size_t>(node);
  if (!supports_.tool_at[i].empty())
    return "which tool '" + supports_.tool_at[i] + "' holds: a cut stays clear of the tools' nodes";
  if (supports_.fixed_somewhere[i])
    return std::string(
        "a fixed node: split mode keeps clear of the supports (move the blade off them, or use mode = \"remove\")");
  for (const int n : mesh.tets[static_cast<std::size_t>(moved)]) {
    const auto j = static_cast<std::size_t>(n);
    if (supports_.in_static_part[j])
      return "moving tetrahedron " + std::to_string(moved) + " which touches node " + std::to_string(n) +
             " of the static part: a cut stays inside the ROI, whose condensation it changes in place (a larger [roi], or "
             "move the blade)";
    if (!supports_.tool_at[j].empty())
      return "moving tetrahedron " + std::to_string(moved) + " which holds node " + std::to_string(n) + " of tool '" +
             supports_.tool_at[j] + "': a cut stays clear of the tools' nodes";
  }
  return std::nullopt;
}

std::optional<std::string> ElementCuts::refusal_to_empty(const mesh::TetMesh& mesh, std::size_t removing, bool condensed) const {
  const std::vector<bool>& there = remover_.still_there();
  std::size_t left = 0;
  for (std::size_t e = 0; e < there.size(); ++e)
    if (there[e] && std::none_of(mesh.tets[e].begin(), mesh.tets[e].end(),
                                 [&](int n) { return supports_.in_static_part[static_cast<std::size_t>(n)]; }))
      ++left;
  if (removing < left) return std::nullopt;
  return "would remove the last " + std::to_string(left) + " tetrahedra of the " + (condensed ? "ROI" : "mesh") +
         ": nothing would be left to move";
}

CutEvent ElementCuts::remove(std::vector<Index> elements, ScenarioModel& m, model::State& state) {
  CutEvent event;
  event.time = state.t;
  event.elements = std::move(elements);
  std::sort(event.elements.begin(), event.elements.end());
  const fem::DofMap& dofs = *m.full.dofs;
  const fem::ElementRemoval removal = remover_.remove(event.elements, 0.0);
  for (const Index e : event.elements) event.mass_removed += m.full.materials.of(e).rho * mesh::signed_volume(m.mesh, e);
  event.orphan_nodes = removal.orphan_nodes;

  const model::SecondOrderSystem& system = m.system();
  event.change = model::SystemChange::from_removal(removal, dofs, system_dof_, system.load.terms().size());
  model::SystemChange& change = event.change;
  const auto r = static_cast<Index>(removal.dofs.size());
  Vector u(r);
  for (Index a = 0; a < r; ++a) {
    const Index d = change.dofs[static_cast<std::size_t>(a)];
    u[a] = state.u[d];
    // The mass removed, held dofs' included (their stand-in carries nothing from now on).
    event.kinetic_energy -= 0.5 * removal.mass_change[a] * state.v[d] * state.v[d];
  }
  event.strain_energy = -0.5 * u.dot(change.stiffness * u);
  for (const auto& [k, g] : gravity_) {
    Vector dp(r);
    for (Index a = 0; a < r; ++a) {
      const Index full = dofs.full_dof(removal.dofs[static_cast<std::size_t>(a)]);
      dp[a] = removal.mass_change[a] * g[static_cast<int>(full % 3)];
    }
    change.loads[k] = std::move(dp);
  }
  // A load on a node left with no element has nothing to act on: it is dropped, and said.
  for (const Index d : change.held)
    for (std::size_t k = 0; k < system.load.terms().size(); ++k)
      if (change.loads[k].size() == 0 && system.load.terms()[k].pattern[d] != 0) {
        const Index full = dofs.full_dof(removal.dofs[static_cast<std::size_t>(
            std::lower_bound(change.dofs.begin(), change.dofs.end(), d) - change.dofs.begin())]);
        event.warnings.push_back("load " + std::to_string(k + 1) + " acted on node " + std::to_string(full / 3) +
                                 ", which the cut left with no tetrahedron: its share is dropped");
        break;
      }
  for (const Index d : change.held) state.v[d] = 0;
  m.change_system(change);

  // Pieces the cut freed from every support move rigidly: said, with their nodes.
  std::vector<int> touched;
  for (const Index e : event.elements)
    for (const int n : m.mesh.tets[static_cast<std::size_t>(e)]) touched.push_back(n);
  warn_loose_pieces(m.mesh, remover_.still_there(), touched, supports_.supported, event);
  return event;
}

}  // namespace roifem::simulation
