// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Does the answer make physical sense? A linear-elastic model is only meaningful for displacements
/// small against the body and its elements, and a 100 N force on a soft brain silently gives
/// metres. PeakDisplacement observes a run (the largest nodal displacement of the integrated
/// system, and the state where it occurred); check_deformation() expands that state to the whole
/// mesh and reports the peak, the size it is measured against, and the tetrahedra the linear
/// solution turns inside out (det(I + grad u) <= 0: deformed signed volume <= 0).
#include <string>
#include <vector>

#include "model/second_order_system.hpp"
#include "simulation/scenario_model.hpp"

namespace roifem::simulation {

/// The peak covers every node the run moves: the integrated system's and the tools' (on their paths).
class PeakDisplacement {
 public:
  explicit PeakDisplacement(const ScenarioModel& model) : nodes_(model.node_positions()), tools_(&model.full.tools) {}
  /// A run-loop observer (run_loop.hpp).
  void observe(long step, const model::State& state);
  double peak_m() const { return peak_; }
  long step() const { return step_; }
  /// The integrated system's state at the peak (empty before any motion).
  const model::State& state() const { return state_; }

 private:
  roi::NodeDofs nodes_;
  const model::ToolSet* tools_;
  double peak_ = 0;
  long step_ = 0;
  model::State state_;
};

struct DeformationReport {
  double peak_m = 0;  ///< largest nodal displacement over the whole mesh, at the peak state
  int peak_node = -1;
  double smallest_extent_m = 0;  ///< the mesh's bounding box, smallest side
  double mean_edge_m = 0;        ///< mean tetrahedron edge length
  Index inverted = 0;            ///< tetrahedra turned inside out by the displacement
  Index first_inverted = -1;
  std::vector<std::string> warnings;  ///< empty when the answer is plausible
};

/// Warns when the peak exceeds a tenth of the mesh's smallest extent or three mean edge lengths,
/// or when tetrahedra invert.
/// `still_there`: per tetrahedron, whether it is in the mesh at the end (cuts); empty: all are.
/// `tets_at_peak`: the tetrahedra's corners at the peak (splits move them); null: the mesh's.
DeformationReport check_deformation(ScenarioModel& model, const PeakDisplacement& peak, const std::vector<bool>& still_there = {},
                                    const std::vector<mesh::Tet>* tets_at_peak = nullptr);

}  // namespace roifem::simulation
