// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// What one step's cut did to a scenario's model (simulation/cuts/scenario_cuts.hpp), and what the
/// cuts of either mode share: where the tissue is held, and the pieces a cut sets loose.
#include <string>
#include <utility>
#include <vector>

#include "common/types.hpp"
#include "cutting/node_splitter.hpp"
#include "mesh/tet_mesh.hpp"
#include "model/system_change.hpp"

namespace roifem::simulation {

struct CutEvent {
  double time = 0;                          ///< s: the state's time when it took effect (the start of the step that reaches it)
  std::vector<Index> elements;              ///< remove mode: tetrahedra removed, ascending
  std::vector<int> orphan_nodes;            ///< remove mode: nodes left with no element, held at rest from now on
  std::size_t faces_separated = 0;          ///< split mode: faces opened by this step
  std::vector<std::pair<int, int>> splits;  ///< split mode: (node, copy): nodes split, a copy taking a piece of their tetrahedra
  std::vector<cutting::Rewire> moved;       ///< split mode: the corners that moved to a copy
  model::SystemChange change;               ///< in the integrated system's numbering (empty: nothing to take)
  double strain_energy = 0;                 ///< J: the strain energy the cut took away (removed tetrahedra's u_e^T K_e u_e / 2)
  double kinetic_energy = 0;                ///< J: the kinetic energy the cut took away (the removed mass's)
  double mass_removed = 0;                  ///< kg: rho V of the removed tetrahedra
  std::vector<std::string> warnings;        ///< pieces cut loose, loads on nodes left with no element
  double energy_removed() const { return strain_energy + kinetic_energy; }
};

/// Where a scenario's tissue is held and what a cut may reach, per node of its mesh.
struct CutSupports {
  std::vector<std::string> tool_at;   ///< the tool holding the node, or empty
  std::vector<bool> in_static_part;   ///< an unknown of the node is in the static part
  std::vector<bool> supported;        ///< fixed in some component, held by a tool or in the static part
  std::vector<bool> fixed_somewhere;  ///< fixed in some component
};

/// Adds to event.warnings each piece of `mesh` (its tetrahedra still there joined by shared nodes)
/// that holds a node of `touched` and no supported node: it moves as a free body.
void warn_loose_pieces(const mesh::TetMesh& mesh, const std::vector<bool>& still_there, const std::vector<int>& touched,
                       const std::vector<bool>& supported, CutEvent& event);

}  // namespace roifem::simulation
