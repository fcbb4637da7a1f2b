// SPDX-License-Identifier: GPL-3.0-or-later
#include "model/fem_model.hpp"

#include <algorithm>
#include <initializer_list>
#include <map>
#include <string>
#include <string_view>

#include "common/errors.hpp"
#include "common/format.hpp"
#include "fem/assembly.hpp"
#include "fem/loads.hpp"
#include "model/hyperelastic_force.hpp"
#include "model/prescribed_motion.hpp"

namespace roifem::model {

namespace {

fem::Constraints fixed_constraints(const mesh::TetMesh& mesh, const std::vector<std::string>& fixed_sets) {
  fem::Constraints constraints(mesh.num_nodes());
  for (const auto& name : fixed_sets) constraints.fix_set(mesh, name);
  return constraints;
}

/// A set's force, restricted to the free dofs; InputError when the fixed nodes take all of it, a
/// warning with the share they take otherwise (a support's reaction, not a load on the tissue).
Vector set_load(const mesh::TetMesh& mesh, const fem::DofMap& dofs, const SetLoad& load, std::vector<std::string>& warnings) {
  const Vector full = fem::set_force(mesh, load.set, load.force);
  Vector kept = dofs.restrict_to_free(full);
  const double total = full.norm(), lost = (full - dofs.expand_homogeneous(kept)).norm();
  if (total > 0 && lost == total)
    throw InputError(mesh.source + ": the load on set '" + load.set +
                     "' lies wholly on fixed nodes: it would move nothing; load a set off the supports");
  if (lost > 1e-12 * total)
    warnings.push_back(
        format("the load on set '%s' acts partly on fixed nodes: %.3g%% of it (%.3g N) "
               "goes into the supports and moves nothing",
               load.set.c_str(), 100 * lost / total, lost));
  return kept;
}

std::vector<int> tool_nodes(const mesh::TetMesh& mesh, const SetTool& tool) {
  if (!tool.set.empty()) return mesh.set(tool.set).nodes;
  std::vector<int> nodes;
  for (const int n : mesh::boundary_nodes(mesh))
    if ((mesh.node(n) - tool.center).norm() <= tool.radius) nodes.push_back(n);
  return nodes;
}

/// Mean length of the edges of the elements that touch `nodes` (m).
double edge_length_around(const mesh::TetMesh& mesh, const std::vector<int>& nodes) {
  std::vector<bool> held(static_cast<std::size_t>(mesh.num_nodes()));
  for (const int n : nodes) held[static_cast<std::size_t>(n)] = true;
  double sum = 0;
  long count = 0;
  for (const auto& t : mesh.tets) {
    if (std::none_of(t.begin(), t.begin() + 4, [&](int n) { return held[static_cast<std::size_t>(n)]; })) continue;
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b, ++count) sum += (mesh.node(t[a]) - mesh.node(t[b])).norm();
  }
  return count > 0 ? sum / static_cast<double>(count) : 0.0;
}

/// A tool should hold a patch of the surface, not a node or two: below three nodes, its force is
/// that of the nodes the mesh happens to put there (on the 806-node brain a 4 mm and an 8 mm
/// spatula hold one node each and feel 142 mN; at 20k nodes, 93 mN).
constexpr std::size_t fewest_tool_nodes = 3;

void warn_of_a_tool_below_the_mesh(const mesh::TetMesh& mesh, const SetTool& t, const Tool& tool,
                                   std::vector<std::string>& warnings) {
  if (tool.nodes.size() >= fewest_tool_nodes) return;
  warnings.push_back(format(
      "%s holds %zu node%s, and the elements there have %.3g mm edges: its force is that of the nodes the mesh puts there, "
      "and changes with the mesh; give it a footprint of %zu nodes or more (%s)",
      t.describe().c_str(), tool.nodes.size(), tool.nodes.size() == 1 ? "" : "s", edge_length_around(mesh, tool.nodes) / mm,
      fewest_tool_nodes, t.set.empty() ? "a radius of about an element's edge, or a finer mesh there" : "a larger set"));
}

/// Each tool's nodes, checked: some, none fixed, none another tool's; a warning for one that holds
/// too few nodes to be more than the mesh's choice.
std::vector<Tool> attach_tools(const mesh::TetMesh& mesh, const fem::Constraints& fixed, const std::vector<SetTool>& tools,
                               std::vector<std::string>& warnings) {
  std::vector<Tool> attached;
  std::map<int, std::size_t> holder;
  for (std::size_t a = 0; a < tools.size(); ++a) {
    const SetTool& t = tools[a];
    Tool tool{.name = t.name, .nodes = tool_nodes(mesh, t), .path = t.path};
    // Where the scenario says it (file:line of its [[tool]] table), else the mesh.
    const std::string at = t.where.empty() ? mesh.source : t.where;
    const std::string of_mesh = t.where.empty() ? "" : " of " + mesh.source;
    const auto refusal = [&](std::initializer_list<std::string_view> parts) {
      std::string message = at;
      message.append(": ").append(t.describe());
      for (const std::string_view part : parts) message.append(part);
      return InputError(message);
    };
    if (tool.nodes.empty())
      throw refusal(
          {" holds no node", of_mesh, t.set.empty() ? " (no boundary node within its radius: widen it or move its centre)" : ""});
    for (const int n : tool.nodes) {
      const std::string node = std::to_string(n);
      if (fixed.is_constrained(3 * n) || fixed.is_constrained(3 * n + 1) || fixed.is_constrained(3 * n + 2))
        throw refusal({" holds node ", node, of_mesh, ", which [boundary] fixes: a tool moves free nodes only"});
      if (const auto [it, fresh] = holder.emplace(n, a); !fresh)
        throw refusal({" and ", tools[it->second].describe(), " both hold node ", node, of_mesh, ": tools must not overlap"});
    }
    warn_of_a_tool_below_the_mesh(mesh, t, tool, warnings);
    attached.push_back(std::move(tool));
  }
  return attached;
}

/// ModelError when the tools hold every free node: nothing is left to integrate.
void require_a_free_node(const mesh::TetMesh& mesh, const fem::DofMap& unfixed, const std::vector<Tool>& attached) {
  std::size_t held = 0;
  std::string names;
  for (const Tool& tool : attached) {
    held += tool.nodes.size();
    names += (names.empty() ? "'" : ", '") + tool.name + "'";
  }
  if (3 * static_cast<Index>(held) < unfixed.num_free()) return;
  throw ModelError(mesh.source + ": the tools (" + names + ") hold every free node (" + std::to_string(held) +
                   "): nothing is left to integrate; let them hold fewer nodes, or fix fewer");
}

SecondOrderSystem assemble(const mesh::TetMesh& mesh, const fem::MaterialMap& materials, fem::Element element,
                           const fem::DofMap& dofs, bool with_stiffness = true) {
  SecondOrderSystem system;
  if (with_stiffness) system.K = fem::stiffness(mesh, dofs, materials, element);
  const Vector m = fem::lumped_mass(mesh, dofs, materials);
  system.M = diagonal_matrix(m);
  system.C = diagonal_matrix(materials.alpha() * m);
  system.damping = Damping::mass_proportional(materials.alpha());
  return system;
}

LoadHistory loads_on(const mesh::TetMesh& mesh, const fem::MaterialMap& materials, const fem::DofMap& dofs,
                     const std::vector<SetLoad>& loads, std::vector<std::string>& warnings) {
  LoadHistory history(dofs.num_free());
  for (const auto& load : loads)
    history.add(load.gravity ? dofs.restrict_to_free(fem::gravity_force(mesh, materials, *load.gravity))
                             : set_load(mesh, dofs, load, warnings),
                load.ramp);
  return history;
}

/// A model of `mesh` with its materials (validated) and element, nothing assembled yet.
FemModel unassembled_model(const mesh::TetMesh& mesh, const fem::MaterialMap& materials, fem::Element element) {
  for (const fem::Material& m : materials.materials()) m.validate();
  FemModel model;
  model.mesh = &mesh;
  model.material = materials.base();
  model.materials = materials;
  model.element = element;
  model.warnings = mesh.warnings;  // what reading the mesh dropped, said where the model's warnings are
  return model;
}

void require_a_support(const mesh::TetMesh& mesh, const fem::DofMap& dofs) {
  if (dofs.num_constrained() == 0)
    throw ModelError(mesh.source + ": no node is fixed, so the brain can move as a rigid body (fix a set such as 'base')");
}

}  // namespace

std::string SetTool::describe() const {
  return "tool '" + name + "' (" +
         (set.empty() ? format("boundary nodes within %g mm of (%g, %g, %g) mm", radius / mm, center.x() / mm, center.y() / mm,
                               center.z() / mm)
                      : "set '" + set + "'") +
         ")";
}

Vector FemModel::displacement(const Eigen::Ref<const Vector>& u_free, double t) const { return displacement(u_free, tools, t); }

Vector FemModel::displacement(const Eigen::Ref<const Vector>& u_free, const ToolSet& on_paths, double t) const {
  Vector u = dofs->expand(u_free);
  for (const Tool& tool : on_paths.tools()) {
    const Vec3 g = tool.path.at(t);
    for (const int n : tool.nodes) u.segment<3>(3 * n) = g;
  }
  return u;
}

FemModel build_fem_model(const mesh::TetMesh& mesh, const fem::Material& material, const std::vector<std::string>& fixed_sets,
                         const std::vector<SetLoad>& loads, const std::vector<SetTool>& tools, fem::Element element) {
  material.validate();
  return build_fem_model(mesh, fem::MaterialMap(material), fixed_sets, loads, tools, element);
}

FemModel build_fem_model_without_stiffness(const mesh::TetMesh& mesh, const fem::MaterialMap& materials,
                                           const std::vector<std::string>& fixed_sets, const std::vector<SetLoad>& loads,
                                           fem::Element element) {
  if (materials.nonlinear())
    throw InputError(mesh.source +
                     ": the distributed engine takes the linear material only; run a neo-hookean model with "
                     "roifem run, or give [material] model = \"linear\"");
  FemModel model = unassembled_model(mesh, materials, element);
  model.dofs = std::make_unique<fem::DofMap>(fixed_constraints(mesh, fixed_sets));
  require_a_support(mesh, *model.dofs);
  model.system = assemble(mesh, materials, element, *model.dofs, false);
  model.system.load = loads_on(mesh, materials, *model.dofs, loads, model.warnings);
  return model;
}

FemModel build_fem_model(const mesh::TetMesh& mesh, const fem::MaterialMap& materials, const std::vector<std::string>& fixed_sets,
                         const std::vector<SetLoad>& loads, const std::vector<SetTool>& tools, fem::Element element) {
  FemModel model = unassembled_model(mesh, materials, element);
  fem::Constraints constraints = fixed_constraints(mesh, fixed_sets);
  const fem::DofMap fixed_only(constraints);
  require_a_support(mesh, fixed_only);
  const std::vector<Tool> attached = attach_tools(mesh, constraints, tools, model.warnings);
  if (!attached.empty()) require_a_free_node(mesh, fixed_only, attached);
  if (attached.empty()) {
    model.dofs = std::make_unique<fem::DofMap>(constraints);
    model.system = assemble(mesh, materials, element, *model.dofs);
    model.system.load = loads_on(mesh, materials, *model.dofs, loads, model.warnings);
    model.system.internal_force = hyperelastic_force(mesh, *model.dofs, materials, element);
    return model;
  }
  // With tools: the model over every unfixed dof, then the tools' dofs eliminated.
  model.dofs_with_tools = std::make_unique<fem::DofMap>(fixed_only);
  SecondOrderSystem all = assemble(mesh, materials, element, *model.dofs_with_tools);
  // Over these dofs only the fixed nodes take a load's share (one on tools' nodes is theirs to carry).
  all.load = loads_on(mesh, materials, *model.dofs_with_tools, loads, model.warnings);
  // The tools' DAE forms (system.constrained) keep the tools' dofs as unknowns: the law reads them there.
  all.internal_force = hyperelastic_force(mesh, *model.dofs_with_tools, materials, element);
  std::vector<ToolDofs> tool_dofs;
  for (const Tool& tool : attached) {
    ToolDofs td{.tool = tool, .dofs = {}};
    for (const int n : tool.nodes) {
      for (int c = 0; c < 3; ++c) td.dofs.push_back(fixed_only.free_dof(n, c));
      constraints.fix_node(n);
    }
    tool_dofs.push_back(std::move(td));
  }
  ToolElimination eliminated = eliminate_tools(all, tool_dofs);
  model.dofs = std::make_unique<fem::DofMap>(constraints);
  model.system = std::move(eliminated.system);
  // A nonlinear law reads the tools' paths where they hold its elements' nodes (hyperelastic_force.hpp).
  model.system.internal_force = hyperelastic_force(mesh, *model.dofs, materials, element, attached);
  model.tools = eliminated.tools.with_law(model.system.internal_force);
  return model;
}

}  // namespace roifem::model
