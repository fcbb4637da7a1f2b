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

std::vector<std::array<Index, 3>> ScenarioModel::node_positions() const {
  const fem::DofMap& dofs = *full.dofs;
  std::vector<Index> position(static_cast<std::size_t>(dofs.num_free()), -1);
  if (condensation) {
    const auto& d = condensation->partition().d;
    for (std::size_t k = 0; k < d.size(); ++k) position[static_cast<std::size_t>(d[k])] = static_cast<Index>(k);
  } else {
    for (Index i = 0; i < dofs.num_free(); ++i) position[static_cast<std::size_t>(i)] = i;
  }
  std::vector<int> nodes = roi_nodes;
  if (nodes.empty())
    for (int n = 0; n < mesh.num_nodes(); ++n)
      if (dofs.free_dof(n, 0) >= 0 || dofs.free_dof(n, 1) >= 0 || dofs.free_dof(n, 2) >= 0) nodes.push_back(n);
  std::vector<std::array<Index, 3>> out;
  for (int n : nodes) {
    std::array<Index, 3> p{};
    for (int c = 0; c < 3; ++c) {
      const int i = dofs.free_dof(n, c);
      p[static_cast<std::size_t>(c)] = i < 0 ? -1 : position[static_cast<std::size_t>(i)];
    }
    out.push_back(p);
  }
  return out;
}

}  // namespace roifem::simulation
