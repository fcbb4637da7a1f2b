#pragma once
/// The full dynamic model of a mesh: free dofs after fixing named sets, lumped M, C = alpha M,
/// K assembled, and forces on named sets with their ramps.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "fem/dof_map.hpp"
#include "fem/material.hpp"
#include "mesh/tet_mesh.hpp"
#include "model/second_order_system.hpp"

namespace roifem::model {

/// A ramped load: a total force (N) spread over a named set, or, with an empty set name,
/// gravity (m/s^2) acting on the lumped masses of the whole mesh.
struct SetLoad {
  std::string set;
  Vec3 force = Vec3::Zero();
  Ramp ramp;
  std::optional<Vec3> gravity;  ///< set: body force rho g instead of `force` on `set`
};

struct FemModel {
  const mesh::TetMesh* mesh = nullptr;
  fem::Material material;
  std::unique_ptr<fem::DofMap> dofs;
  SecondOrderSystem system;
};

/// Builds the full model. Throws InputError for a missing set and ModelError when nothing is fixed.
FemModel build_fem_model(const mesh::TetMesh& mesh, const fem::Material& material, const std::vector<std::string>& fixed_sets,
                         const std::vector<SetLoad>& loads);

}  // namespace roifem::model
