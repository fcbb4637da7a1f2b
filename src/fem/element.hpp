#pragma once
/// The element formulations a model is assembled with (the scenario's top-level `element` key):
///   tet4            the linear 4-node tetrahedron (fem/tet4.hpp): the paper's; locks as nu nears 1/2
///   nodal-pressure  the average-nodal-pressure tetrahedron (fem/nodal_pressure.hpp): the same
///                   nodes, no locking; K couples nodes two elements apart
/// Both give a constant, symmetric positive definite K, so condensation, every reduction and every
/// integrator take either unchanged.
#include <string>
#include <string_view>

#include "common/types.hpp"
#include "fem/dof_map.hpp"
#include "fem/material.hpp"
#include "fem/material_map.hpp"
#include "mesh/tet_mesh.hpp"

namespace roifem::fem {

enum class Element { tet4, nodal_pressure };

std::string_view element_name(Element element);
/// "tet4" or "nodal-pressure"; InputError naming both (with a suggestion) otherwise.
Element parse_element(std::string_view name);

/// K_ff of `mesh` over `dofs` with `element`.
SparseMatrix stiffness(const mesh::TetMesh& mesh, const DofMap& dofs, const MaterialMap& materials, Element element);
SparseMatrix stiffness(const mesh::TetMesh& mesh, const DofMap& dofs, const Material& material, Element element);

}  // namespace roifem::fem
