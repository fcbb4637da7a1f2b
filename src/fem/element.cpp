// SPDX-License-Identifier: GPL-3.0-or-later
#include "fem/element.hpp"

#include <array>
#include <utility>
#include <vector>

#include "common/did_you_mean.hpp"
#include "common/errors.hpp"
#include "fem/assembly.hpp"
#include "fem/nodal_pressure.hpp"
#include "mesh/quadratic_mesh.hpp"

namespace roifem::fem {

namespace {

constexpr std::array<std::pair<Element, std::string_view>, 3> element_names{
    {{Element::tet4, "tet4"}, {Element::nodal_pressure, "nodal-pressure"}, {Element::tet10, "tet10"}}};

}  // namespace

std::string_view element_name(Element element) {
  for (const auto& [value, name] : element_names)
    if (value == element) return name;
  throw Error("internal: an element without a name");
}

Element parse_element(std::string_view name) {
  std::vector<std::string> names;
  for (const auto& [value, known] : element_names) {
    if (known == name) return value;
    names.emplace_back(known);
  }
  throw InputError("unknown element '" + std::string(name) + "'" + did_you_mean(name, names) +
                   ": use tet4, nodal-pressure or tet10");
}

mesh::TetMesh element_mesh(mesh::TetMesh linear, Element element) {
  if (element != Element::tet10) return linear;  // moved, not copied
  return mesh::with_midside_nodes(linear);
}

SparseMatrix stiffness(const mesh::TetMesh& mesh, const DofMap& dofs, const MaterialMap& materials, Element element) {
  if (mesh.is_quadratic() != (element == Element::tet10))
    throw Error("internal: " + std::string(element_name(element)) + " assembled on a " +
                (mesh.is_quadratic() ? "quadratic" : "linear") + " mesh (fem::element_mesh makes the mesh an element needs)");
  if (element == Element::nodal_pressure) return nodal_pressure_stiffness(mesh, dofs, materials, 0.0);
  return StiffnessAssembler(mesh, dofs).stiffness(materials);
}

SparseMatrix stiffness(const mesh::TetMesh& mesh, const DofMap& dofs, const Material& material, Element element) {
  return stiffness(mesh, dofs, MaterialMap(material), element);
}

}  // namespace roifem::fem
