#include "simulation/scenario_model.hpp"

#include "common/errors.hpp"
#include "mesh/gmsh_reader.hpp"
#include "mesh/mesh_checks.hpp"

namespace roifem::simulation {

std::unique_ptr<ScenarioModel> build_scenario_model(const scenario::Scenario& sc) {
  auto m = std::make_unique<ScenarioModel>();
  m->mesh = mesh::read_mesh(sc.mesh);
  mesh::check_mesh(m->mesh);
  m->full = model::build_fem_model(m->mesh, sc.material, sc.fixed_sets, sc.loads);
  const fem::DofMap& dofs = *m->full.dofs;
  if (sc.roi) {
    m->roi_nodes = roi::select_roi_nodes(m->mesh, dofs, *sc.roi);
    try {
      m->condensation = std::make_unique<condensation::ReducedModel>(
          m->full.system, roi::partition_dofs(m->full.system.K, dofs, m->roi_nodes), dofs, sc.reduction);
    } catch (const ModelError& e) {  // a singular static part: name the mesh whose nodes it names
      throw ModelError(m->mesh.source + ": " + e.what());
    }
  }
  return m;
}

roi::NodeDofs ScenarioModel::node_positions() const {
  const fem::DofMap& dofs = *full.dofs;
  const std::vector<int> nodes = roi_nodes.empty() ? roi::free_nodes(mesh, dofs) : roi_nodes;
  return condensation ? roi::node_dofs_in_reduced(nodes, condensation->partition(), dofs) : roi::node_dofs_in_full(nodes, dofs);
}

}  // namespace roifem::simulation
