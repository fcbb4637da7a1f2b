// SPDX-License-Identifier: GPL-3.0-or-later
#include "cutting/split_copies.hpp"

#include "common/errors.hpp"
#include "model/system_change.hpp"

namespace roifem::cutting {

std::vector<double> copy_stand_in_mass(const mesh::TetMesh& mesh, const fem::MaterialMap& materials, const SplitPlan& plan) {
  std::vector<double> lumped(static_cast<std::size_t>(plan.num_nodes), 0.0);
  for (Index e = 0; e < mesh.num_tets(); ++e)
    for (const int n : mesh.tets[static_cast<std::size_t>(e)])
      if (n < plan.num_nodes) lumped[static_cast<std::size_t>(n)] += materials.of(e).rho * mesh::signed_volume(mesh, e) / 4;
  std::vector<double> stand_in;
  for (const int original : plan.copy_of) stand_in.push_back(lumped[static_cast<std::size_t>(original)]);
  return stand_in;
}

void hold_copies(model::FemModel& full, const SplitPlan& plan) {
  const std::vector<double> stand_in = copy_stand_in_mass(*full.mesh, full.materials, plan);
  model::SystemChange hold;
  std::vector<double> mass;
  for (Index k = 0; k < plan.num_copies(); ++k)
    for (int i = 0; i < 3; ++i) {
      const int d = full.dofs->free_dof(plan.num_nodes + k, i);
      if (d < 0) throw Error("internal: a split's copy is fixed");
      hold.dofs.push_back(d);
      mass.push_back(stand_in[static_cast<std::size_t>(k)]);
    }
  hold.held = hold.dofs;  // ascending: copies come last, a node's dofs in order
  hold.stiffness = DenseMatrix::Zero(static_cast<Index>(mass.size()), static_cast<Index>(mass.size()));
  hold.mass = Eigen::Map<const Vector>(mass.data(), static_cast<Index>(mass.size()));
  hold.loads.assign(full.system.load.terms().size(), Vector());
  hold.apply(full.system);
}

}  // namespace roifem::cutting
