// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// The full dynamic model of a mesh: free dofs after fixing named sets, lumped M, C = alpha M,
/// K assembled, forces on named sets with their ramps, and tools (tools.hpp) whose attached nodes
/// follow a prescribed path: their dofs are eliminated (prescribed_motion.hpp) and the DofMap
/// lists them as constrained.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "fem/dof_map.hpp"
#include "fem/element.hpp"
#include "fem/material.hpp"
#include "fem/material_map.hpp"
#include "mesh/tet_mesh.hpp"
#include "model/second_order_system.hpp"
#include "model/tools.hpp"

namespace roifem::model {

/// A ramped load: a total force (N) spread over a named set, or, with an empty set name,
/// gravity (m/s^2) acting on the lumped masses of the whole mesh.
struct SetLoad {
  std::string set;
  Vec3 force = Vec3::Zero();
  Ramp ramp;
  std::optional<Vec3> gravity;  ///< set: body force rho g instead of `force` on `set`
};

/// A rigid tool attached to the nodes of a named set, or to the boundary nodes within a ball.
struct SetTool {
  std::string name;
  std::string set;             ///< or, empty: the footprint
  Vec3 center = Vec3::Zero();  ///< m, footprint: boundary nodes within `radius` of it
  double radius = 0;           ///< m
  ToolPath path;
  std::string where;             ///< "file:line" of its [[tool]] table in the scenario, for messages (empty: none)
  std::string describe() const;  ///< "tool 'left' (set 'opening_left')"
};

struct FemModel {
  const mesh::TetMesh* mesh = nullptr;
  fem::Material material;      ///< the base material (everywhere, unless regions say otherwise)
  fem::MaterialMap materials;  ///< each tetrahedron's material (uniform: `material` everywhere)
  fem::Element element = fem::Element::tet4;
  std::unique_ptr<fem::DofMap> dofs;  ///< tools' nodes are constrained here (their motion: tools)
  SecondOrderSystem system;
  ToolSet tools;  ///< in the free numbering
  /// With tools: the dof map before their nodes were constrained, the numbering of
  /// system.constrained->all (the DAE forms').
  std::unique_ptr<fem::DofMap> dofs_with_tools;
  std::vector<std::string> warnings;  ///< e.g. a load partly on fixed nodes, and how much it loses
  /// The displacement of every node (3N, m): u over the free dofs, the tools' paths at time t.
  Vector displacement(const Eigen::Ref<const Vector>& u_free, double t) const;
  /// The same with the tools on other paths (the same tools, e.g. ToolSet::with_ramp).
  Vector displacement(const Eigen::Ref<const Vector>& u_free, const ToolSet& on_paths, double t) const;
};

/// Builds the full model. Throws InputError for a missing set, a load wholly on fixed nodes, and a
/// tool on no node, on a fixed node or on another tool's node; ModelError when nothing is fixed.
FemModel build_fem_model(const mesh::TetMesh& mesh, const fem::Material& material, const std::vector<std::string>& fixed_sets,
                         const std::vector<SetLoad>& loads, const std::vector<SetTool>& tools = {},
                         fem::Element element = fem::Element::tet4);
/// The same model without K (system.K left empty) and without tools: the dof map, M, C and the
/// loads, for an engine that assembles K itself (src/distributed: each rank its own elements).
FemModel build_fem_model_without_stiffness(const mesh::TetMesh& mesh, const fem::MaterialMap& materials,
                                           const std::vector<std::string>& fixed_sets, const std::vector<SetLoad>& loads,
                                           fem::Element element = fem::Element::tet4);
/// The same with materials by region (fem::MaterialMap).
FemModel build_fem_model(const mesh::TetMesh& mesh, const fem::MaterialMap& materials, const std::vector<std::string>& fixed_sets,
                         const std::vector<SetLoad>& loads, const std::vector<SetTool>& tools = {},
                         fem::Element element = fem::Element::tet4);

}  // namespace roifem::model
