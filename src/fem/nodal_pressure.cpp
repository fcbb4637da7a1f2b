// SPDX-License-Identifier: GPL-3.0-or-later
#include "fem/nodal_pressure.hpp"

#include <cmath>
#include <string>
#include <vector>

#include "common/errors.hpp"
#include "common/number_text.hpp"
#include "fem/assembly.hpp"
#include "fem/tet4.hpp"

namespace roifem::fem {

SparseMatrix nodal_pressure_stiffness(const mesh::TetMesh& mesh, const DofMap& dofs, const Material& material,
                                      double stabilization) {
  return nodal_pressure_stiffness(mesh, dofs, MaterialMap(material), stabilization);
}

SparseMatrix nodal_pressure_stiffness(const mesh::TetMesh& mesh, const DofMap& dofs, const MaterialMap& materials,
                                      double stabilization) {
  if (mesh.is_quadratic())
    throw Error("internal: the nodal-pressure tetrahedron takes a linear mesh, not " + mesh.source + "'s quadratic one");
  if (!(stabilization >= 0 && stabilization <= 1))
    throw InputError("nodal-pressure tetrahedron: stabilization " + number_text(stabilization) + " must lie in [0, 1]");
  auto kappa_of = [](const Material& m) { return m.lambda + 2.0 / 3.0 * m.mu; };
  // Deviatoric part: the tetrahedron with lambda = -2 mu / 3 (D - kappa 1 1^T), material by material.
  const StiffnessAssembler assembler(mesh, dofs);
  SparseMatrix K = assembler.stiffness(materials.mapped([](Material m) {
    m.lambda = -2.0 / 3.0 * m.mu;
    return m;
  }));
  const bool uniform = materials.uniform();
  const double kappa = kappa_of(materials.base());

  // c (N x n_free): row a = sum over a's elements of (V_e / 4) b_e; the element-wise part's rows
  // (one per element, sqrt(V_e) b_e) in E.
  const Index N = mesh.num_nodes(), n = dofs.num_free();
  std::vector<Eigen::Triplet<double>> c_entries, e_entries;
  Vector nodal_volume = Vector::Zero(N), nodal_kappa_volume = Vector::Zero(N);
  Vector element_kappa(mesh.num_tets());
  for (Index e = 0; e < mesh.num_tets(); ++e) {
    const auto& tet = mesh.tets[static_cast<std::size_t>(e)];
    const Tet4Geometry g = tet4_geometry(mesh.node(tet[0]), mesh.node(tet[1]), mesh.node(tet[2]), mesh.node(tet[3]));
    const double volume = std::abs(g.volume);
    element_kappa[e] = kappa_of(materials.of(e));
    for (int a = 0; a < 4; ++a) {
      nodal_volume[tet[a]] += volume / 4;
      nodal_kappa_volume[tet[a]] += element_kappa[e] * volume / 4;
    }
    for (int b = 0; b < 4; ++b)
      for (int c = 0; c < 3; ++c) {
        const int dof = dofs.free_dof(tet[b], c);
        if (dof < 0) continue;
        const double divergence = g.grad(b, c);  // d N_b / d x_c: b_e's entry at (node b, component c)
        for (int a = 0; a < 4; ++a) c_entries.emplace_back(tet[a], dof, volume / 4 * divergence);
        // Uniform: kappa scales the product below, as before regions existed (the same bits).
        e_entries.emplace_back(e, dof, std::sqrt(uniform ? volume : element_kappa[e] * volume) * divergence);
      }
  }
  SparseMatrix C(N, n), E(mesh.num_tets(), n);
  C.setFromTriplets(c_entries.begin(), c_entries.end());
  E.setFromTriplets(e_entries.begin(), e_entries.end());
  // kappa_a / V_a with kappa_a = sum (V_e / 4) kappa_e / V_a: the nodal pressure kappa_a theta_a.
  const Vector weight = uniform ? Vector((1 - stabilization) * kappa * nodal_volume.cwiseInverse())
                                : Vector((1 - stabilization) * nodal_kappa_volume.cwiseQuotient(nodal_volume.cwiseAbs2()));
  const SparseMatrix nodal = SparseMatrix(C.transpose() * weight.asDiagonal() * C);
  const SparseMatrix element = SparseMatrix(E.transpose() * E) * (stabilization * (uniform ? kappa : 1.0));
  K += nodal;
  if (stabilization > 0) K += element;
  K.makeCompressed();
  return K;
}

}  // namespace roifem::fem
