// SPDX-License-Identifier: GPL-3.0-or-later
#include "simulation/scenario_cuts.hpp"

#include <algorithm>
#include <limits>
#include <numeric>

#include "common/errors.hpp"
#include "common/number_text.hpp"
#include "condensation/reduced_model.hpp"
#include "fem/element_removal.hpp"
#include "integrators/integrator_table.hpp"

namespace roifem::simulation {

namespace {

/// InputError for what cuts are not built on: said once, before the blades are traced.
void refuse_unsupported(const scenario::Scenario& sc, const ScenarioModel& m) {
  const std::string cut = sc.cuts.front().where + ": " + sc.cuts.front().describe();
  if (m.full.element != fem::Element::tet4)
    throw InputError(cut + ": cuts are built for 4-node tetrahedra (element = \"tet4\"), not element = \"" +
                     std::string(fem::element_name(m.full.element)) + "\"");
  if (m.system().is_nonlinear())
    throw InputError(cut + ": cuts are built for the linear material; this model's is " + m.system().internal_force->describe() +
                     " (give [material] model = \"linear\")");
  if (m.condensation && m.condensation->reduction().kind->counted)
    throw InputError(cut + ": [roi] reduction = \"" + m.condensation->reduction().label() +
                     "\" keeps modes of the uncut mesh's static part; cuts take reduction = \"static\" or \"guyan\"");
  const auto& info = integrators::integrator_info(sc.integrator);
  if (info.needs_tools || info.needs_uncondensed)
    throw InputError(cut + ": integrator '" + sc.integrator +
                     "' integrates a DAE form that keeps the uncut system; a cut takes the eliminated form (trapezoid, "
                     "arkode-*, ida-bdf*, gsl-*)");
}

/// Where the tissue is held, and what a cut may reach.
CutSupports supports_of(const ScenarioModel& m) {
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

}  // namespace

ScenarioCuts::ScenarioCuts(const scenario::Scenario& sc, const ScenarioModel& m) {
  if (sc.cuts.empty()) return;
  refuse_unsupported(sc, m);
  const mesh::TetMesh& mesh = m.mesh;
  const fem::DofMap& dofs = *m.full.dofs;
  time_slack_ = 1e-9 * sc.dt;
  const CutSupports at = supports_of(m);
  supported_ = at.supported;
  system_dof_.assign(static_cast<std::size_t>(dofs.num_free()), -1);
  if (m.condensation) {
    const auto& d = m.condensation->partition().d;
    for (std::size_t i = 0; i < d.size(); ++i) system_dof_[static_cast<std::size_t>(d[i])] = static_cast<Index>(i);
  } else {
    std::iota(system_dof_.begin(), system_dof_.end(), Index{0});
  }
  for (std::size_t k = 0; k < sc.loads.size(); ++k)
    if (sc.loads[k].gravity) gravity_.emplace_back(k, *sc.loads[k].gravity);

  if (m.split_plan) {  // split mode: planned with the model, which holds the copies
    split_plan_ = m.split_plan.get();
    // What moves to a copy stays clear of the supports and the static part where it can.
    std::vector<bool> anchored(static_cast<std::size_t>(mesh.num_tets()), false);
    for (std::size_t e = 0; e < anchored.size(); ++e)
      anchored[e] =
          std::any_of(mesh.tets[e].begin(), mesh.tets[e].end(), [&](int n) { return at.supported[static_cast<std::size_t>(n)]; });
    refuse_splits(m, at, anchored);
    no_cuts_.assign(static_cast<std::size_t>(mesh.num_tets()), true);
    splits_.emplace(m, system_dof_, gravity_, time_slack_, std::move(anchored));
    return;
  }
  const double t_end = sc.dt * static_cast<double>(sc.steps);
  const auto elements = static_cast<std::size_t>(mesh.num_tets());

  // Each tetrahedron once, at the earliest time a blade reaches it within the run.
  std::vector<double> when(elements, std::numeric_limits<double>::infinity());
  std::vector<const cutting::Blade*> by(elements, nullptr);
  for (const cutting::Blade& blade : sc.cuts) {
    const std::vector<cutting::Crossing> crossings = cutting::swept_elements(blade, mesh);
    if (crossings.empty())
      throw InputError(blade.where + ": " + blade.describe() + " never meets the mesh " + mesh.source +
                       ": its edge, swept along its path, crosses no tetrahedron");
    if (crossings.front().time > t_end + time_slack_)
      throw InputError(blade.where + ": " + blade.describe() + " first reaches the mesh (tetrahedron " +
                       std::to_string(crossings.front().element) + ") at t = " + number_text(crossings.front().time) +
                       " s, after the run ends at t = " + number_text(t_end) + " s");
    for (const auto& c : crossings)
      if (c.time <= t_end + time_slack_ && c.time < when[static_cast<std::size_t>(c.element)]) {
        when[static_cast<std::size_t>(c.element)] = c.time;
        by[static_cast<std::size_t>(c.element)] = &blade;
      }
  }
  for (std::size_t e = 0; e < elements; ++e)
    if (by[e]) schedule_.push_back({static_cast<Index>(e), when[e]});
  std::stable_sort(schedule_.begin(), schedule_.end(), [](const auto& a, const auto& b) { return a.time < b.time; });

  for (const auto& c : schedule_) {
    const cutting::Blade& blade = *by[static_cast<std::size_t>(c.element)];
    for (const int n : mesh.tets[static_cast<std::size_t>(c.element)]) {
      const std::string where = blade.where + ": " + blade.describe() + " reaches tetrahedron " + std::to_string(c.element) +
                                " at t = " + number_text(c.time) + " s, ";
      if (!at.tool_at[static_cast<std::size_t>(n)].empty())
        throw InputError(where + "which holds node " + std::to_string(n) + " of tool '" +
                         at.tool_at[static_cast<std::size_t>(n)] + "': a cut stays clear of the tools' nodes");
      if (at.in_static_part[static_cast<std::size_t>(n)])
        throw InputError(where + "which touches node " + std::to_string(n) +
                         " of the static part: a cut stays inside the ROI, whose condensation it changes in place (a larger "
                         "[roi], or move the blade)");
    }
  }
  Index inside = 0;
  for (const auto& tet : mesh.tets)
    inside += std::none_of(tet.begin(), tet.end(), [&](int n) { return at.in_static_part[static_cast<std::size_t>(n)]; }) ? 1 : 0;
  if (static_cast<Index>(schedule_.size()) == inside)
    throw InputError(sc.cuts.front().where + ": the cuts remove all " + std::to_string(inside) + " tetrahedra of the " +
                     (m.roi_nodes.empty() ? "mesh" : "ROI") + ": nothing would be left to move");
  remover_.emplace(mesh, dofs, m.full.materials);
}

void ScenarioCuts::refuse_splits(const ScenarioModel& m, const CutSupports& at, const std::vector<bool>& anchored) const {
  const cutting::SplitPlan& plan = *split_plan_;
  for (const auto& [move, face] : cutting::rehearse(plan, m.mesh.tets, anchored)) {
    const cutting::SeparatedFace& f = plan.faces[face];
    const cutting::Blade& blade = *plan.blade_of[face];
    const mesh::Tet& tet = m.mesh.tets[static_cast<std::size_t>(move.element)];
    const auto node = static_cast<std::size_t>(tet[static_cast<std::size_t>(move.corner)]);
    const std::string where = blade.where + ": " + blade.describe() + " separates tetrahedra " + std::to_string(f.a) + " and " +
                              std::to_string(f.b) + " at t = " + number_text(f.time) + " s, which splits node " +
                              std::to_string(node);
    if (!at.tool_at[node].empty())
      throw InputError(where + ", which tool '" + at.tool_at[node] + "' holds: a cut stays clear of the tools' nodes");
    if (at.fixed_somewhere[node])
      throw InputError(where +
                       ", a fixed node: split mode keeps clear of the supports (move the blade off them, or use "
                       "mode = \"remove\")");
    for (const int n : tet) {
      if (at.in_static_part[static_cast<std::size_t>(n)])
        throw InputError(where + ", moving tetrahedron " + std::to_string(move.element) + " which touches node " +
                         std::to_string(n) +
                         " of the static part: a cut stays inside the ROI, whose condensation it changes in place (a larger "
                         "[roi], or move the blade)");
      if (!at.tool_at[static_cast<std::size_t>(n)].empty())
        throw InputError(where + ", moving tetrahedron " + std::to_string(move.element) + " which holds node " +
                         std::to_string(n) + " of tool '" + at.tool_at[static_cast<std::size_t>(n)] +
                         "': a cut stays clear of the tools' nodes");
    }
  }
}

CutEvent ScenarioCuts::cut_due(double t, ScenarioModel& m, model::State& state) {
  if (!splits_) return remove_due(t, m, state);
  CutEvent event = splits_->split_due(t, m, state, supported_);
  for (const cutting::Rewire& move : event.moved) moves_.emplace_back(event.time, move);
  nodes_split_ += event.splits.size();
  return event;
}

std::vector<mesh::Tet> ScenarioCuts::tets_at(double t, const mesh::TetMesh& mesh) const {
  std::vector<mesh::Tet> tets = mesh.tets;
  // The state at t_k is the step's end, before a split at t_k (the next step's start).
  for (auto m = moves_.rbegin(); m != moves_.rend() && m->first >= t - time_slack_; ++m)
    tets[static_cast<std::size_t>(m->second.element)][static_cast<std::size_t>(m->second.corner)] = m->second.from;
  return tets;
}

CutEvent ScenarioCuts::remove_due(double t, ScenarioModel& m, model::State& state) {
  CutEvent event;
  event.time = state.t;
  while (due(t)) event.elements.push_back(schedule_[next_++].element);
  std::sort(event.elements.begin(), event.elements.end());
  const fem::DofMap& dofs = *m.full.dofs;
  const fem::ElementRemoval removal = remover_->remove(event.elements, 0.0);
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
  warn_loose_pieces(m.mesh, remover_->still_there(), touched, supported_, event);
  return event;
}

}  // namespace roifem::simulation
