// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// The average-nodal-pressure tetrahedron (Bonet & Burton 1998), linear elastic: the element's
/// stiffness splits into a deviatoric part and a volumetric one, kappa V b b^T (kappa = lambda +
/// 2 mu / 3, b the element's divergence operator: tr(eps) = b . u_e). Linear tetrahedra lock as nu
/// nears 1/2 because every element must keep its own volume; the nodal-pressure form asks that of
/// the patch of elements around each node instead: with nodal volumes V_a = sum over the node's
/// elements of V_e / 4 and nodal volumetric strains theta_a = sum (V_e / 4) tr(eps_e) / V_a, the
/// volumetric energy is kappa / 2 sum_a V_a theta_a^2, so
///   K = K_dev + (1 - s) K_nodal + s K_element,
///   K_nodal = sum_a kappa / V_a c_a c_a^T,   c_a = sum over the node's elements of (V_e / 4) b_e,
/// with a fraction s of the element-wise volumetric stiffness kept to damp the nodal form's
/// spurious (hourglass-like) pressure modes (s = 0: pure average nodal pressure). K stays
/// constant, symmetric and positive definite (with enough supports), with the pattern of the nodes
/// two elements apart.
#include "common/types.hpp"
#include "fem/dof_map.hpp"
#include "fem/material.hpp"
#include "fem/material_map.hpp"
#include "mesh/tet_mesh.hpp"

namespace roifem::fem {

/// K_ff of the nodal-pressure tetrahedron with stabilization fraction s in [0, 1] (s = 1: the
/// linear tetrahedron). Throws InputError for s outside [0, 1].
/// With materials by region, each node's kappa is the volume-weighted mean of its elements' kappa
/// (the nodal strain averages over the same elements).
SparseMatrix nodal_pressure_stiffness(const mesh::TetMesh& mesh, const DofMap& dofs, const MaterialMap& materials,
                                      double stabilization);
SparseMatrix nodal_pressure_stiffness(const mesh::TetMesh& mesh, const DofMap& dofs, const Material& material,
                                      double stabilization);

}  // namespace roifem::fem
