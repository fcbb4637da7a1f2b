#include "fem/element.hpp"

#include <array>
#include <utility>
#include <vector>

#include "common/did_you_mean.hpp"
#include "common/errors.hpp"
#include "fem/assembly.hpp"
#include "fem/nodal_pressure.hpp"

namespace roifem::fem {

namespace {

constexpr std::array<std::pair<Element, std::string_view>, 2> element_names{
    {{Element::tet4, "tet4"}, {Element::nodal_pressure, "nodal-pressure"}}};

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
  throw InputError("unknown element '" + std::string(name) + "'" + did_you_mean(name, names) + ": use tet4 or nodal-pressure");
}

SparseMatrix stiffness(const mesh::TetMesh& mesh, const DofMap& dofs, const MaterialMap& materials, Element element) {
  if (element == Element::nodal_pressure) return nodal_pressure_stiffness(mesh, dofs, materials, 0.0);
  return StiffnessAssembler(mesh, dofs).stiffness(materials);
}

SparseMatrix stiffness(const mesh::TetMesh& mesh, const DofMap& dofs, const Material& material, Element element) {
  return stiffness(mesh, dofs, MaterialMap(material), element);
}

}  // namespace roifem::fem
