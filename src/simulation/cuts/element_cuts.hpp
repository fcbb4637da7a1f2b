// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Removing tetrahedra from a scenario's model as it runs (a cut in remove mode), whoever decides
/// which: a scenario's [[cut]] blades (scenario_cuts.hpp) or a hand on the page (serve/). It holds
/// the mesh as the cuts leave it (fem::ElementRemover), each free dof's unknown in the integrated
/// system, the gravity load terms and where the tissue is held, and forms each removal's change
/// (model/system_change.hpp), applying it to the model in place.
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "fem/element_removal.hpp"
#include "scenario/scenario.hpp"
#include "simulation/cuts/cut_event.hpp"
#include "simulation/scenario_model.hpp"

namespace roifem::simulation {

/// Where `model`'s tissue is held and what a cut may reach, per node of its mesh.
CutSupports cut_supports(const ScenarioModel& model);

class ElementCuts {
 public:
  /// `model` built from `scenario` (its gravity loads); both must outlive this.
  ElementCuts(const scenario::Scenario& scenario, const ScenarioModel& model);
  /// Removes `elements` (distinct, still there) from `model`'s integrated system at `state`: the
  /// change (gravity's share of each load term included, a load on a node left with no element
  /// dropped and said), the energy and mass it takes away, the velocity at the held dofs set to
  /// zero, and the pieces it frees from every support, named. The integrator must then take
  /// event.change. InputError (nothing removed) for an element out of range or already gone.
  CutEvent remove(std::vector<Index> elements, ScenarioModel& model, model::State& state);
  /// Per tetrahedron, whether it is still in the mesh.
  const std::vector<bool>& still_there() const { return remover_.still_there(); }

  /// The one rule for what a cut may take, whichever path asks (a scenario's blades in either mode,
  /// the page's scalpel): why it is refused, in words that follow "... reaches tetrahedron E[ at t],
  /// " (or "... splits node N, "), or nothing where it is admitted. The batch path throws it, naming
  /// the blade and the time; the live path says it. Removing tetrahedron `e` of `mesh` is refused
  /// at a node of the static part (a cut stays inside the ROI, whose condensation it changes in
  /// place), at a tool's node, or at a node of `hand` (the nodes a hand holds now, ascending).
  std::optional<std::string> refusal_to_remove(const mesh::TetMesh& mesh, Index e, const std::vector<int>& hand = {}) const;
  /// Splitting `node` and moving tetrahedron `moved` to its copy: refused at a tool's node or a
  /// fixed one, and where `moved` touches the static part or a tool's node.
  std::optional<std::string> refusal_to_split(const mesh::TetMesh& mesh, int node, Index moved) const;
  /// Removing `removing` of the tetrahedra still there (none touching the static part): refused
  /// where nothing of the ROI (`condensed`; else of the mesh) would be left to move.
  std::optional<std::string> refusal_to_empty(const mesh::TetMesh& mesh, std::size_t removing, bool condensed) const;
  const CutSupports& supports() const { return supports_; }
  /// Per free dof of the full model: its unknown in the integrated system (-1: the static part).
  const std::vector<Index>& system_dof() const { return system_dof_; }
  /// The load terms that are gravity, and g.
  const std::vector<std::pair<std::size_t, Vec3>>& gravity() const { return gravity_; }

 private:
  fem::ElementRemover remover_;
  CutSupports supports_;
  std::vector<Index> system_dof_;  ///< per free dof of the full model: its unknown in the system (-1: static part)
  std::vector<std::pair<std::size_t, Vec3>> gravity_;  ///< load terms that are gravity, and g
};

}  // namespace roifem::simulation
