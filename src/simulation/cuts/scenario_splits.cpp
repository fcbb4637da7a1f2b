// SPDX-License-Identifier: GPL-3.0-or-later
#include "simulation/cuts/scenario_splits.hpp"

#include <algorithm>
#include <map>

#include "common/errors.hpp"
#include "cutting/split_copies.hpp"
#include "fem/tet4.hpp"
#include "simulation/scenario_model.hpp"

namespace roifem::simulation {

ScenarioSplits::ScenarioSplits(const ScenarioModel& m, std::vector<Index> system_dof,
                               std::vector<std::pair<std::size_t, Vec3>> gravity, double time_slack, std::vector<bool> anchored)
    : plan_(m.split_plan.get()),
      splitter_(std::vector<mesh::Tet>(m.mesh.tets), plan_->neighbours, plan_->num_nodes, plan_->copies, std::move(anchored)),
      stand_in_(cutting::copy_stand_in_mass(m.mesh, m.full.materials, *plan_)),
      system_dof_(std::move(system_dof)),
      gravity_(std::move(gravity)),
      time_slack_(time_slack) {}

CutEvent ScenarioSplits::split_due(double t, ScenarioModel& m, model::State& state, const std::vector<bool>& supported) {
  CutEvent event;
  event.time = state.t;
  std::vector<std::pair<Index, Index>> faces;
  for (; due(t); ++next_) faces.emplace_back(plan_->faces[next_].a, plan_->faces[next_].b);
  event.faces_separated = faces.size();
  const std::size_t copies_before = splitter_.copies_made().size();
  event.moved = splitter_.separate(faces);
  if (event.moved.empty()) return event;
  for (std::size_t k = copies_before; k < splitter_.copies_made().size(); ++k) {
    const int copy = splitter_.copies_made()[k].first;
    // The node the copy comes from: the one its corners held before (the original, or an earlier copy).
    const auto from =
        std::find_if(event.moved.begin(), event.moved.end(), [copy](const cutting::Rewire& r) { return r.to == copy; });
    event.splits.emplace_back(from->from, copy);
  }

  // Each moved tetrahedron's corners before and after.
  std::map<Index, mesh::Tet> before, after;
  for (const cutting::Rewire& r : event.moved)
    after.try_emplace(r.element, splitter_.tets()[static_cast<std::size_t>(r.element)]);
  for (const auto& [e, tet] : after) before.emplace(e, tet);
  for (auto r = event.moved.rbegin(); r != event.moved.rend(); ++r)
    before[r->element][static_cast<std::size_t>(r->corner)] = r->from;

  const fem::DofMap& dofs = *m.full.dofs;
  const auto unknown = [&](int node, int i) {
    const int free = dofs.free_dof(node, i);
    return free < 0 ? Index{-1} : system_dof_[static_cast<std::size_t>(free)];
  };
  model::SystemChange& change = event.change;
  std::vector<std::pair<Index, int>> touched_dofs;  // (unknown, component)
  for (const auto* corners : {&before, &after})
    for (const auto& [e, tet] : *corners)
      for (const int n : tet)
        for (int i = 0; i < 3; ++i)
          if (const Index d = unknown(n, i); d >= 0) touched_dofs.emplace_back(d, i);
  std::sort(touched_dofs.begin(), touched_dofs.end());
  touched_dofs.erase(std::unique(touched_dofs.begin(), touched_dofs.end()), touched_dofs.end());
  for (const auto& [d, i] : touched_dofs) change.dofs.push_back(d);
  const auto r = static_cast<Index>(change.dofs.size());
  const auto local = [&](Index d) {
    return static_cast<Index>(std::lower_bound(change.dofs.begin(), change.dofs.end(), d) - change.dofs.begin());
  };
  change.stiffness = DenseMatrix::Zero(r, r);
  change.mass = Vector::Zero(r);
  Vector moved_mass = Vector::Zero(r);  // the tetrahedra's mass moving with their corners (what gravity follows)
  for (const auto& [e, old_tet] : before) {
    const mesh::Tet& new_tet = after.at(e);
    const fem::Tet4Geometry g =
        fem::tet4_geometry(m.mesh.node(old_tet[0]), m.mesh.node(old_tet[1]), m.mesh.node(old_tet[2]), m.mesh.node(old_tet[3]));
    const fem::Material& material = m.full.materials.of(e);
    const fem::ElementMatrix K = fem::tet4_stiffness(g, material);
    const double quarter = material.rho * std::abs(g.volume) / 4;
    for (const auto& [tet, sign] : {std::pair{&new_tet, 1.0}, std::pair{&old_tet, -1.0}}) {
      Index row[12];
      for (int k = 0; k < 12; ++k) {
        const Index d = unknown((*tet)[static_cast<std::size_t>(k / 3)], k % 3);
        row[k] = d < 0 ? -1 : local(d);
      }
      for (int a = 0; a < 12; ++a) {
        if (row[a] < 0) continue;
        for (int b = 0; b < 12; ++b)
          if (row[b] >= 0) change.stiffness(row[a], row[b]) += sign * K(a, b);
        if (old_tet[static_cast<std::size_t>(a / 3)] != new_tet[static_cast<std::size_t>(a / 3)])
          moved_mass[row[a]] += sign * quarter;
      }
    }
  }
  change.mass = moved_mass;
  for (const auto& [node, copy] : event.splits)
    for (int i = 0; i < 3; ++i)
      change.mass[local(unknown(copy, i))] -= stand_in_[static_cast<std::size_t>(copy - plan_->num_nodes)];
  change.loads.assign(m.system().load.terms().size(), Vector());
  for (const auto& [k, g] : gravity_) {
    Vector dp(r);
    for (Index a = 0; a < r; ++a) dp[a] = moved_mass[a] * g[touched_dofs[static_cast<std::size_t>(a)].second];
    change.loads[k] = std::move(dp);
  }

  // The copies start where their nodes are: the displacement stays continuous.
  for (const auto& [node, copy] : event.splits)
    for (int i = 0; i < 3; ++i) {
      state.u[unknown(copy, i)] = state.u[unknown(node, i)];
      state.v[unknown(copy, i)] = state.v[unknown(node, i)];
      change.started.push_back(unknown(copy, i));
    }
  std::sort(change.started.begin(), change.started.end());
  // What the split took (zero but for round-off: the same u_e per tetrahedron, the same v on the mass moved).
  Vector u(r), v(r);
  for (Index a = 0; a < r; ++a) {
    u[a] = state.u[change.dofs[static_cast<std::size_t>(a)]];
    v[a] = state.v[change.dofs[static_cast<std::size_t>(a)]];
  }
  event.strain_energy = -0.5 * u.dot(change.stiffness * u);
  event.kinetic_energy = -0.5 * v.dot(moved_mass.cwiseProduct(v));
  m.change_system(change);
  for (const auto& [e, tet] : after) m.mesh.tets[static_cast<std::size_t>(e)] = tet;

  std::vector<int> touched;
  for (const auto& [node, copy] : event.splits) touched.insert(touched.end(), {node, copy});
  warn_loose_pieces(m.mesh, std::vector<bool>(m.mesh.tets.size(), true), touched, supported, event);
  return event;
}

}  // namespace roifem::simulation
