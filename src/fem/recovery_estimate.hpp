// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// A posteriori error estimate of a displacement field in the energy norm, by strain recovery
/// (Zienkiewicz & Zhu 1987): linear tetrahedra give a strain that is constant per element and
/// jumps between them; averaging it at the nodes (weighted by the elements' volumes) and
/// interpolating linearly gives a recovered strain eps* far closer to the exact one than eps_h,
/// so the difference estimates the error:
///   eta_e^2 = int_e 2 mu |dev(eps*) - dev(eps_h)|^2 + kappa (theta* - theta_h)^2 dV,
///   ||u||_E^2 = int 2 mu |dev eps|^2 + kappa theta^2 dV = u^T K u,
/// with theta the volumetric strain and kappa = lambda + 2 mu / 3. The integral of a linear field
/// against a constant is exact: int_e |sum_a d_a N_a|^2 = V_e / 20 (sum_a |d_a|^2 + |sum_a d_a|^2).
/// The nodal-pressure tetrahedron (fem/nodal_pressure.hpp) already carries the recovered
/// volumetric strain theta_a at its nodes, so its estimate is the deviatoric part alone; with a
/// nearly incompressible material that part is almost all of the energy.
/// The estimate is what drives mesh adaptation (mesh/adapted_size_field.hpp); its effectivity
/// (estimated over true error) is measured against Lame's solution in the tests.
#include "common/types.hpp"
#include "fem/element.hpp"
#include "fem/material_map.hpp"
#include "mesh/tet_mesh.hpp"

namespace roifem::fem {

struct RecoveryEstimate {
  Vector element_error2;   ///< #E: eta_e^2 (J, twice the error's strain energy in the element)
  double error = 0;        ///< sqrt(sum eta_e^2)
  double energy_norm = 0;  ///< ||u_h||_E
  /// The estimated relative error in the energy norm.
  double relative() const { return energy_norm > 0 ? error / energy_norm : 0; }
};

/// The estimate for u (3N, over every node) on `mesh` assembled with `element` and `materials`.
RecoveryEstimate recovery_estimate(const mesh::TetMesh& mesh, const MaterialMap& materials, Element element, const Vector& u);

}  // namespace roifem::fem
