// SPDX-License-Identifier: GPL-3.0-or-later
#include "simulation/cuts/scenario_cuts.hpp"

#include <algorithm>
#include <limits>
#include <numeric>

#include "common/errors.hpp"
#include "common/number_text.hpp"
#include "condensation/reduced_model.hpp"
#include "fem/element_removal.hpp"
#include "integrators/integrator_table.hpp"
#include "model/internal_force.hpp"

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

}  // namespace

ScenarioCuts::ScenarioCuts(const scenario::Scenario& sc, const ScenarioModel& m) {
  if (sc.cuts.empty()) return;
  refuse_unsupported(sc, m);
  const mesh::TetMesh& mesh = m.mesh;
  time_slack_ = 1e-9 * sc.dt;
  cutter_.emplace(sc, m);
  const CutSupports& at = cutter_->supports();

  if (m.split_plan) {  // split mode: planned with the model, which holds the copies
    split_plan_ = m.split_plan.get();
    // What moves to a copy stays clear of the supports and the static part where it can.
    std::vector<bool> anchored(static_cast<std::size_t>(mesh.num_tets()), false);
    for (std::size_t e = 0; e < anchored.size(); ++e)
      anchored[e] =
          std::any_of(mesh.tets[e].begin(), mesh.tets[e].end(), [&](int n) { return at.supported[static_cast<std::size_t>(n)]; });
    refuse_splits(m, anchored);
    no_cuts_.assign(static_cast<std::size_t>(mesh.num_tets()), true);
    splits_.emplace(m, cutter_->system_dof(), cutter_->gravity(), time_slack_, std::move(anchored));
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

  // What the cuts may take: the element cuts' one rule, each refusal named with its blade and time.
  for (const auto& c : schedule_)
    if (const auto why = cutter_->refusal_to_remove(mesh, c.element)) {
      const cutting::Blade& blade = *by[static_cast<std::size_t>(c.element)];
      throw InputError(blade.where + ": " + blade.describe() + " reaches tetrahedron " + std::to_string(c.element) +
                       " at t = " + number_text(c.time) + " s, " + *why);
    }
  if (const auto why = cutter_->refusal_to_empty(mesh, schedule_.size(), !m.roi_nodes.empty()))
    throw InputError(sc.cuts.front().where + ": the cuts " + *why);
}

void ScenarioCuts::refuse_splits(const ScenarioModel& m, const std::vector<bool>& anchored) const {
  const cutting::SplitPlan& plan = *split_plan_;
  for (const auto& [move, face] : cutting::rehearse(plan, m.mesh.tets, anchored)) {
    const mesh::Tet& tet = m.mesh.tets[static_cast<std::size_t>(move.element)];
    const int node = tet[static_cast<std::size_t>(move.corner)];
    if (const auto why = cutter_->refusal_to_split(m.mesh, node, move.element)) {
      const cutting::SeparatedFace& f = plan.faces[face];
      const cutting::Blade& blade = *plan.blade_of[face];
      throw InputError(blade.where + ": " + blade.describe() + " separates tetrahedra " + std::to_string(f.a) + " and " +
                       std::to_string(f.b) + " at t = " + number_text(f.time) + " s, which splits node " + std::to_string(node) +
                       ", " + *why);
    }
  }
}

CutEvent ScenarioCuts::cut_due(double t, ScenarioModel& m, model::State& state) {
  if (!splits_) return remove_due(t, m, state);
  CutEvent event = splits_->split_due(t, m, state, cutter_->supports().supported);
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
  std::vector<Index> elements;
  while (due(t)) elements.push_back(schedule_[next_++].element);
  return cutter_->remove(std::move(elements), m, state);
}

}  // namespace roifem::simulation
