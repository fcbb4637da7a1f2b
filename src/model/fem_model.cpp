#include "model/fem_model.hpp"

#include "common/errors.hpp"
#include "fem/assembly.hpp"
#include "fem/loads.hpp"

namespace roifem::model {

FemModel build_fem_model(const mesh::TetMesh& mesh, const fem::Material& material, const std::vector<std::string>& fixed_sets,
                         const std::vector<SetLoad>& loads) {
  material.validate();
  FemModel model;
  model.mesh = &mesh;
  model.material = material;
  fem::Constraints constraints(mesh.num_nodes());
  for (const auto& name : fixed_sets) constraints.fix_set(mesh, name);
  model.dofs = std::make_unique<fem::DofMap>(constraints);
  if (model.dofs->num_constrained() == 0)
    throw ModelError(mesh.source + ": no node is fixed, so the brain can move as a rigid body (fix a set such as 'base')");
  const fem::DofMap& dofs = *model.dofs;
  const fem::StiffnessAssembler assembler(mesh, dofs);
  model.system.K = assembler.stiffness(material);
  const Vector m = fem::lumped_mass(mesh, dofs, material.rho);
  model.system.M = diagonal_matrix(m);
  model.system.C = diagonal_matrix(material.alpha * m);
  model.system.damping = Damping::mass_proportional(material.alpha);
  model.system.load = LoadHistory(dofs.num_free());
  for (const auto& load : loads)
    model.system.load.add(dofs.restrict_to_free(load.gravity ? fem::gravity_force(mesh, material.rho, *load.gravity)
                                                             : fem::set_force(mesh, load.set, load.force)),
                          load.ramp);
  return model;
}

}  // namespace roifem::model
