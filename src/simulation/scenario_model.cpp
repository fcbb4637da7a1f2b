// SPDX-License-Identifier: GPL-3.0-or-later
#include "simulation/scenario_model.hpp"

#include <algorithm>
#include <utility>

#include "common/errors.hpp"
#include "cutting/split_copies.hpp"
#include "integrators/factory.hpp"
#include "mesh/gmsh_reader.hpp"
#include "mesh/mesh_checks.hpp"
#include "model/hyperelastic_force.hpp"
#include "model/prescribed_motion.hpp"
#include "model/uncondensed_form.hpp"

namespace roifem::simulation {

namespace {

/// The reduced model's DAE form: the full model with the tools' dofs as unknowns, reduced onto the
/// ROI and the tools' nodes (the same static part, so the same dynamics and, for Craig-Bampton, the
/// same modes), with the tools' dofs and the eliminated model's unknowns placed in it.
std::shared_ptr<const model::ConstrainedForm> condensed_constrained_form(const ScenarioModel& m,
                                                                         const condensation::Reduction& r) {
  const model::ConstrainedForm& full_form = *m.full.system.constrained;
  const fem::DofMap& all_dofs = *m.full.dofs_with_tools;
  std::vector<int> nodes = m.roi_nodes;
  for (const auto& tool : m.full.tools.tools()) nodes.insert(nodes.end(), tool.nodes.begin(), tool.nodes.end());
  std::sort(nodes.begin(), nodes.end());
  const roi::Partition partition = roi::partition_dofs(full_form.all.K, all_dofs, nodes);
  // A neo-Hookean model: the linear one condensed, the hybrid's law over the same ROI (the tools'
  // nodes among its unknowns) given after, as reduce_full_model does.
  model::SecondOrderSystem linear_all = full_form.all;
  const auto law = std::exchange(linear_all.internal_force, nullptr);
  condensation::ReducedModel reduced(linear_all, partition, all_dofs, r);
  std::vector<Index> position(static_cast<std::size_t>(all_dofs.num_free()), -1);
  for (std::size_t i = 0; i < partition.d.size(); ++i) position[static_cast<std::size_t>(partition.d[i])] = static_cast<Index>(i);
  auto form = std::make_shared<model::ConstrainedForm>();
  form->all = reduced.system();
  if (law)
    form->all.internal_force = model::hybrid_roi_force(m.mesh, all_dofs, m.full.materials, m.full.element, reduced.partition(),
                                                       reduced.system().K, {}, &reduced.system().K_split);
  form->tools = full_form.tools;
  for (auto& tool : form->tools)
    for (Index& dof : tool.dofs) dof = position[static_cast<std::size_t>(dof)];
  for (const Index e : m.condensation->partition().d) {
    const Index full = m.full.dofs->full_dof(e);
    form->kept.push_back(position[static_cast<std::size_t>(all_dofs.free_dof(full / 3, static_cast<int>(full % 3)))]);
  }
  // The same static part, so the same coordinates beyond the ROI (Craig-Bampton's modes), last in both.
  const Index modes = m.condensation->num_modes();
  if (reduced.num_modes() != modes) throw Error("internal: the tools' DAE form has other modal coordinates");
  for (Index j = 0; j < modes; ++j) form->kept.push_back(static_cast<Index>(partition.d.size()) + j);
  return form;
}

}  // namespace

model::ToolSet tools_in_reduced(const model::FemModel& full, const roi::Partition& partition, Index reduced_size) {
  std::vector<Index> position(static_cast<std::size_t>(full.system.size()), -1);
  for (std::size_t i = 0; i < partition.d.size(); ++i) position[static_cast<std::size_t>(partition.d[i])] = static_cast<Index>(i);
  const SparseMatrix& coupling = full.tools.coupling();
  for (Index j = 0; j < coupling.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(coupling, j); it; ++it)
      if (position[static_cast<std::size_t>(j)] < 0) {
        const auto& tool = full.tools.tools()[static_cast<std::size_t>(it.row() / 3)];
        throw ModelError(full.mesh->source + ": tool '" + tool.name + "' shares an element with node " +
                         std::to_string(full.dofs->full_dof(j) / 3) +
                         ", which is in the static part: the ROI must hold the tool's nodes and their neighbours");
      }
  return full.tools.renumbered(reduced_size, position);
}

std::unique_ptr<condensation::ReducedModel> reduce_full_model(model::FemModel& full, const roi::Partition& partition,
                                                              const condensation::Reduction& reduction,
                                                              const std::string& where) {
  // A neo-Hookean model's ROI is the hybrid: the linear model condensed as always, the law set
  // aside meanwhile (condensation takes a linear model) and given back after.
  std::shared_ptr<const model::InternalForce> law = std::exchange(full.system.internal_force, nullptr);
  if (law && !reduction.is_static_condensation()) {
    full.system.internal_force = law;
    throw InputError(where + ": [roi] reduction = \"" + reduction.label() +
                     "\" with a neo-hookean material: a reduction by modes linearizes the ROI's motion; the nonlinear "
                     "ROI takes static condensation (reduction = \"static\"), or give [material] model = \"linear\"");
  }
  std::unique_ptr<condensation::ReducedModel> reduced;
  try {
    reduced = std::make_unique<condensation::ReducedModel>(full.system, partition, *full.dofs, reduction);
  } catch (const ModelError& e) {  // a singular static part: name the mesh whose nodes it names
    full.system.internal_force = law;
    throw ModelError(full.mesh->source + ": " + e.what());
  }
  full.system.internal_force = law;
  if (law)
    reduced->attach_internal_force(model::hybrid_roi_force(*full.mesh, *full.dofs, full.materials, full.element,
                                                           reduced->partition(), reduced->system().K, full.tools.tools(),
                                                           &reduced->system().K_split));
  return reduced;
}

std::unique_ptr<ScenarioModel> build_scenario_model(const scenario::Scenario& sc) {
  auto m = std::make_unique<ScenarioModel>();
  m->mesh = mesh::read_mesh(sc.mesh);
  mesh::check_mesh(m->mesh);
  m->mesh = fem::element_mesh(std::move(m->mesh), sc.element);
  mesh::TetMesh unsplit;  // the mesh's own nodes, where the ROI is chosen
  if (std::any_of(sc.cuts.begin(), sc.cuts.end(), [](const auto& c) { return c.mode == cutting::CutMode::split; })) {
    m->split_plan =
        std::make_shared<const cutting::SplitPlan>(cutting::plan_splits(sc.cuts, m->mesh, sc.dt * static_cast<double>(sc.steps)));
    if (sc.roi) unsplit = m->mesh;
    m->mesh = cutting::with_copies(std::move(m->mesh), *m->split_plan);
  }
  m->full = model::build_fem_model(m->mesh, fem::MaterialMap(m->mesh, sc.material, sc.material_regions), sc.fixed_sets, sc.loads,
                                   sc.tools, sc.element);
  if (m->split_plan) cutting::hold_copies(m->full, *m->split_plan);
  const fem::DofMap& dofs = *m->full.dofs;
  if (sc.roi) {
    m->roi_nodes = roi::select_roi_nodes(m->split_plan ? unsplit : m->mesh, dofs, *sc.roi);
    if (m->split_plan)
      for (Index k = 0; k < m->split_plan->num_copies(); ++k)
        m->roi_nodes.push_back(static_cast<int>(m->split_plan->num_nodes + k));  // held, joined to nothing yet
    m->condensation =
        reduce_full_model(m->full, roi::partition_dofs(m->full.system.K, dofs, m->roi_nodes), sc.reduction, sc.file.string());
  }
  if (!m->full.tools.empty())
    m->tools = m->condensation ? tools_in_reduced(m->full, m->condensation->partition(), m->condensation->system().size())
                                     .with_law(m->condensation->system().internal_force)
                               : m->full.tools;
  // (Not for a basis learnt from the loads: the tool-kept model has other loads, so another basis.)
  if (m->condensation && !m->full.tools.empty() && !sc.reduction.kind->learns_from_loads)
    m->condensation->attach_constrained_form(condensed_constrained_form(*m, sc.reduction));
  if (m->condensation && sc.reduction.is_static_condensation()) {
    const roi::Partition& p = m->condensation->partition();
    std::shared_ptr<const model::InternalForce> law;
    if (m->full.system.is_nonlinear())
      law = model::hybrid_law_uncondensed(m->mesh, dofs, m->full.materials, m->full.element, p, m->full.system.K,
                                          m->full.tools.tools());
    m->condensation->attach_uncondensed_form(std::make_shared<const model::UncondensedForm>(
        model::UncondensedForm{.full = &m->full.system, .roi = p.d, .static_part = p.s, .law = std::move(law)}));
  }
  return m;
}

std::unique_ptr<integrators::Integrator> scenario_integrator(const scenario::Scenario& sc) {
  // Without rtol the step is fixed and the tolerances are StepControl's defaults: an implicit
  // method's Newton test on a nonlinear model still weighs by them (atol 0 made ARKODE refuse).
  integrators::StepControl control{.dt = sc.dt, .adaptive = sc.rtol.has_value()};
  if (sc.rtol) {
    control.rtol = *sc.rtol;
    control.atol = sc.absolute_tolerance();
  }
  try {
    return integrators::make_integrator(sc.integrator, control);
  } catch (const InputError& e) {  // an unknown name, tolerances for a fixed step: where the scenario says it
    throw InputError((sc.integrator_where.empty() ? sc.file.string() : sc.integrator_where) + ": " + e.what());
  }
}

roi::NodeDofs ScenarioModel::node_positions() const {
  const fem::DofMap& dofs = *full.dofs;
  const std::vector<int> nodes = roi_nodes.empty() ? roi::free_nodes(mesh, dofs) : roi_nodes;
  return condensation ? roi::node_dofs_in_reduced(nodes, condensation->partition(), dofs) : roi::node_dofs_in_full(nodes, dofs);
}

std::vector<Index> ScenarioModel::roi_components() const {
  std::vector<Index> components;
  if (condensation)
    for (const auto& p : node_positions()) components.insert(components.end(), p.begin(), p.end());
  return components;
}

}  // namespace roifem::simulation
