// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// The full model M u'' + C u' + K u = f(t) (model/fem_model.hpp) distributed over the ranks of a
/// communicator: K as a MatMPIAIJ of block size 3 (each rank assembles its own elements: those
/// whose first free node it owns; PETSc sends the rows it does not own to their owners), the lumped
/// M as a Vec, C = alpha M, and the load patterns with their ramps. Indexed by the partition's
/// node numbers (node_partition.hpp): dof 3 number[n] + c. The arithmetic per element is the
/// serial assembly's (fem/tet4.hpp, fem/tet10.hpp), so K differs from it by the order of sums only.
#include <memory>
#include <vector>

#include "distributed/node_partition.hpp"
#include "distributed/petsc_handle.hpp"
#include "model/fem_model.hpp"
#include "scenario/scenario.hpp"

namespace roifem::distributed {

struct DistributedLoad {
  OwnedVec pattern;  ///< N
  model::Ramp ramp;
};

struct DistributedModel {
  const model::FemModel* frame = nullptr;  ///< the serial model without K: mesh, dofs, materials
  NodePartition nodes;
  OwnedMat K;            ///< N/m
  OwnedVec mass;         ///< kg, M's diagonal
  OwnedVec coordinates;  ///< m, the free nodes' positions (block size 3): the rigid-body modes' source
  double alpha = 0;      ///< 1/s, C = alpha M
  std::vector<DistributedLoad> loads;
  PetscInt dofs() const { return 3 * nodes.count(); }
  /// f(t) into f.
  void load_at(double t, Vec f) const;
  /// A vector of this model's layout (zero).
  OwnedVec new_vector() const;
  /// A serial free-dof vector (the frame's numbering) as a distributed one, and back: `gather`
  /// returns the whole vector on every rank (to_all) or on rank 0 only (empty elsewhere).
  OwnedVec distribute(const Vector& serial) const;
  Vector gather(Vec x, bool to_all) const;
  /// The distributed index of a serial free dof.
  PetscInt index_of_free_dof(Index free) const;
};

/// What every rank builds of a scenario before distributing it: the mesh (read, checked, and made
/// the scenario element's) and the model without K. Held by unique_ptr: the model refers to its mesh.
struct ScenarioFrame {
  mesh::TetMesh mesh;
  model::FemModel model;
};
std::unique_ptr<ScenarioFrame> scenario_frame(const scenario::Scenario& scenario);

/// InputError for what the distributed model does not take, checked before any work: [[tool]]s (it
/// takes loads only; roifem run takes them), naming the scenario and `roifem run` as the alternative.
void check_distributable(const scenario::Scenario& scenario);

/// Distributes `frame` (build_fem_model_without_stiffness) over `comm` and assembles K.
/// InputError for the nodal-pressure element (its K couples nodes two elements apart; not built
/// here) and for non-zero prescribed displacements.
DistributedModel distribute_model(const model::FemModel& frame, MPI_Comm comm);

}  // namespace roifem::distributed
