// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// The model a scenario describes: the mesh, the full FEM model, and with an [roi] the static
/// condensation onto it. system() is what integrators advance.
#include <memory>
#include <vector>

#include "condensation/reduced_model.hpp"
#include "cutting/split_plan.hpp"
#include "integrators/integrator.hpp"
#include "model/fem_model.hpp"
#include "roi/node_dofs.hpp"
#include "scenario/scenario.hpp"

namespace roifem::simulation {

struct ScenarioModel {
  mesh::TetMesh mesh;
  model::FemModel full;
  std::unique_ptr<condensation::ReducedModel> condensation;
  std::vector<int> roi_nodes;  ///< empty for the full model
  model::ToolSet tools;        ///< the scenario's tools, in system()'s numbering
  /// Cuts in split mode: their plan, whose copies are the mesh's last nodes (held until a split
  /// brings them in: simulation/cuts/scenario_splits.hpp); null otherwise.
  std::shared_ptr<const cutting::SplitPlan> split_plan;

  const model::SecondOrderSystem& system() const { return condensation ? condensation->system() : full.system; }
  /// Changes system() in place (a cut: simulation/cuts/scenario_cuts.hpp).
  void change_system(model::SystemChange& change) {
    if (condensation)
      condensation->change_system(change);
    else
      change.apply(full.system);
  }
  /// The integrated system's nodes (ROI nodes, or all free nodes) in its numbering
  /// (roi/node_dofs.hpp): errors are measured per node.
  roi::NodeDofs node_positions() const;
  /// The ROI nodes' components among the unknowns, 3 per node (-1: fixed), as results.h5 records
  /// them; empty for the full model.
  std::vector<Index> roi_components() const;
};

/// The full model's tools in a reduced model's numbering (its first unknowns are the ROI dofs d of
/// `partition`). ModelError, naming the mesh and the node, when a tool shares an element with a
/// node of the static part: its force and its motion must reach the tissue through the ROI alone.
model::ToolSet tools_in_reduced(const model::FemModel& full, const roi::Partition& partition, Index reduced_size);

/// The ROI model of `full` on `partition`: the reduction of the linear model (a neo-Hookean
/// model's K is its tangent at rest), and with a neo-Hookean material the hybrid ROI's law
/// (model/hyperelastic_force.hpp) over it, the tools' motion included. A reduction by modes
/// linearizes the ROI's motion: InputError naming it (`where`: the scenario file, for the message).
/// The full model's law is set aside while it condenses and given back (hence non-const).
std::unique_ptr<condensation::ReducedModel> reduce_full_model(model::FemModel& full, const roi::Partition& partition,
                                                              const condensation::Reduction& reduction, const std::string& where);

/// The integrator the scenario names, with its steps: fixed dt, or error-controlled at its rtol and
/// atol with dt as the output interval. InputError for an unknown name (before any work).
std::unique_ptr<integrators::Integrator> scenario_integrator(const scenario::Scenario& scenario);

/// Reads and checks the mesh, builds the model and condenses it. Cuts in split mode are planned
/// first: their copies join the mesh as nodes (the ROI, selected on the mesh's own nodes, holds
/// every copy) and are held. Held by unique_ptr: the model refers to its own mesh.
std::unique_ptr<ScenarioModel> build_scenario_model(const scenario::Scenario& scenario);

}  // namespace roifem::simulation
