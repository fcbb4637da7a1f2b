// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// The element formulations a model is assembled with (the scenario's top-level `element` key):
///   tet4            the linear 4-node tetrahedron (fem/tet4.hpp): the paper's; locks as nu nears 1/2
///   nodal-pressure  the average-nodal-pressure tetrahedron (fem/nodal_pressure.hpp): the same
///                   nodes, no locking; K couples nodes two elements apart
///   tet10           the straight-sided 10-node tetrahedron (fem/tet10.hpp) on the mesh with a node
///                   at every edge's midpoint (element_mesh): quadratic, HRZ-lumped mass
/// All give a constant, symmetric positive definite K, so condensation, every reduction and every
/// integrator take either unchanged.
#include <string>
#include <string_view>

#include "common/types.hpp"
#include "fem/dof_map.hpp"
#include "fem/material.hpp"
#include "fem/material_map.hpp"
#include "mesh/tet_mesh.hpp"

namespace roifem::fem {

enum class Element { tet4, nodal_pressure, tet10 };

std::string_view element_name(Element element);
/// "tet4", "nodal-pressure" or "tet10"; InputError naming them (with a suggestion) otherwise.
Element parse_element(std::string_view name);

/// The mesh `element` is assembled on, from a linear mesh: tet10 adds the edges' midpoints
/// (mesh::with_midside_nodes), the others take it as it is.
mesh::TetMesh element_mesh(mesh::TetMesh linear, Element element);

/// K_ff of `mesh` over `dofs` with `element`. Error when the mesh is not element_mesh's for it.
SparseMatrix stiffness(const mesh::TetMesh& mesh, const DofMap& dofs, const MaterialMap& materials, Element element);
SparseMatrix stiffness(const mesh::TetMesh& mesh, const DofMap& dofs, const Material& material, Element element);

}  // namespace roifem::fem
