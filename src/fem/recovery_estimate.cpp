// SPDX-License-Identifier: GPL-3.0-or-later
#include "fem/recovery_estimate.hpp"

#include <cassert>
#include <cmath>
#include <vector>

#include "common/errors.hpp"
#include "fem/tet4.hpp"

namespace roifem::fem {

namespace {

struct ElementStrain {
  Mat3 deviator;  ///< dev(sym grad u)
  double volumetric = 0;
  double volume = 0;
};

std::vector<ElementStrain> element_strains(const mesh::TetMesh& mesh, const Vector& u) {
  std::vector<ElementStrain> strains(static_cast<std::size_t>(mesh.num_tets()));
  for (Index e = 0; e < mesh.num_tets(); ++e) {
    const auto& tet = mesh.tets[static_cast<std::size_t>(e)];
    const Tet4Geometry g = tet4_geometry(mesh.node(tet[0]), mesh.node(tet[1]), mesh.node(tet[2]), mesh.node(tet[3]));
    Mat3 grad_u = Mat3::Zero();  // (i, j) = d u_i / d x_j
    for (int a = 0; a < 4; ++a) grad_u += u.segment<3>(3 * tet[a]) * g.grad.row(a);
    const Mat3 strain = 0.5 * (grad_u + grad_u.transpose());
    auto& s = strains[static_cast<std::size_t>(e)];
    s.volumetric = strain.trace();
    s.deviator = strain - s.volumetric / 3 * Mat3::Identity();
    s.volume = std::abs(g.volume);
  }
  return strains;
}

}  // namespace

RecoveryEstimate recovery_estimate(const mesh::TetMesh& mesh, const MaterialMap& materials, Element element, const Vector& u) {
  assert(u.size() == 3 * mesh.num_nodes());
  if (element == Element::tet10)
    throw InputError(mesh.source + ": the recovery estimate is for the linear elements (tet4, nodal-pressure), not tet10");
  const std::vector<ElementStrain> strains = element_strains(mesh, u);

  // Recovery: volume-weighted nodal means of the element strains.
  const Index N = mesh.num_nodes();
  std::vector<Mat3> nodal_deviator(static_cast<std::size_t>(N), Mat3::Zero());
  Vector nodal_volumetric = Vector::Zero(N), nodal_volume = Vector::Zero(N);
  for (Index e = 0; e < mesh.num_tets(); ++e) {
    const auto& s = strains[static_cast<std::size_t>(e)];
    for (const int a : mesh.tets[static_cast<std::size_t>(e)]) {
      nodal_deviator[static_cast<std::size_t>(a)] += s.volume * s.deviator;
      nodal_volumetric[a] += s.volume * s.volumetric;
      nodal_volume[a] += s.volume;
    }
  }
  for (Index a = 0; a < N; ++a) {
    if (nodal_volume[a] == 0) continue;  // a node of no tetrahedron
    nodal_deviator[static_cast<std::size_t>(a)] /= nodal_volume[a];
    nodal_volumetric[a] /= nodal_volume[a];
  }

  RecoveryEstimate r;
  r.element_error2.resize(mesh.num_tets());
  double energy2 = 0;
  for (Index e = 0; e < mesh.num_tets(); ++e) {
    const auto& s = strains[static_cast<std::size_t>(e)];
    const auto& tet = mesh.tets[static_cast<std::size_t>(e)];
    const Material& m = materials.of(e);
    const double kappa = m.lambda + 2.0 / 3.0 * m.mu;
    // The element's own volumetric strain: constant for tet4, the nodal field for nodal pressures.
    Mat3 deviator_sum = Mat3::Zero();
    double deviator_squares = 0, volumetric_sum = 0, volumetric_squares = 0, nodal_theta2 = 0;
    for (const int a : tet) {
      const Mat3 d = nodal_deviator[static_cast<std::size_t>(a)] - s.deviator;
      deviator_sum += d;
      deviator_squares += d.squaredNorm();
      const double t = nodal_volumetric[a] - s.volumetric;
      volumetric_sum += t;
      volumetric_squares += t * t;
      nodal_theta2 += nodal_volumetric[a] * nodal_volumetric[a];
    }
    const double deviatoric = 2 * m.mu * s.volume / 20 * (deviator_squares + deviator_sum.squaredNorm());
    const double volumetric =
        element == Element::tet4 ? kappa * s.volume / 20 * (volumetric_squares + volumetric_sum * volumetric_sum) : 0.0;
    r.element_error2[e] = deviatoric + volumetric;
    const double theta2 = element == Element::tet4 ? s.volumetric * s.volumetric : nodal_theta2 / 4;  // nodal quadrature
    energy2 += s.volume * (2 * m.mu * s.deviator.squaredNorm() + kappa * theta2);
  }
  r.error = std::sqrt(r.element_error2.sum());
  r.energy_norm = std::sqrt(energy2);
  return r;
}

}  // namespace roifem::fem
