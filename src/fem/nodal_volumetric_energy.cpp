// SPDX-License-Identifier: GPL-3.0-or-later
#include "fem/nodal_volumetric_energy.hpp"

#include <algorithm>
#include <cmath>

#include "common/errors.hpp"
#include "common/format.hpp"
#include "fem/neo_hookean.hpp"
#include "fem/tet4.hpp"
#include "solvers/sparse_positions.hpp"

namespace roifem::fem {

namespace {

std::size_t as_size(Index i) { return static_cast<std::size_t>(i); }

/// The cofactor matrix of A (det(A) A^-T for an invertible A), entry by entry.
Mat3 cofactor(const Mat3& A) {
  Mat3 C;
  C(0, 0) = A(1, 1) * A(2, 2) - A(1, 2) * A(2, 1);
  C(0, 1) = A(1, 2) * A(2, 0) - A(1, 0) * A(2, 2);
  C(0, 2) = A(1, 0) * A(2, 1) - A(1, 1) * A(2, 0);
  C(1, 0) = A(0, 2) * A(2, 1) - A(0, 1) * A(2, 2);
  C(1, 1) = A(0, 0) * A(2, 2) - A(0, 2) * A(2, 0);
  C(1, 2) = A(0, 1) * A(2, 0) - A(0, 0) * A(2, 1);
  C(2, 0) = A(0, 1) * A(1, 2) - A(0, 2) * A(1, 1);
  C(2, 1) = A(0, 2) * A(1, 0) - A(0, 0) * A(1, 2);
  C(2, 2) = A(0, 0) * A(1, 1) - A(0, 1) * A(1, 0);
  return C;
}

/// cof(I + H) - I = tr(H) I - H^T + cof(H), without cancellation.
Mat3 cofactor_of_F_minus_identity(const Mat3& H) { return H.trace() * Mat3::Identity() - H.transpose() + cofactor(H); }

/// J - 1 - tr(H) = (tr(H)^2 - tr(H^2)) / 2 + det(H): what J exceeds its linearization by.
double J_beyond_linear(const Mat3& H) {
  const double tr = H.trace();
  return 0.5 * (tr * tr - (H * H).trace()) + H.determinant();
}

/// The element vector V A g (node b, component i: V sum_J A_iJ g_bJ).
Eigen::Matrix<double, 12, 1> element_vector(const Eigen::Matrix<double, 4, 3>& g, const Mat3& A, double V) {
  Eigen::Matrix<double, 12, 1> f;
  for (int b = 0; b < 4; ++b) f.segment<3>(3 * b) = V * (A * g.row(b).transpose());
  return f;
}

}  // namespace

NodalVolumetricEnergy::NodalVolumetricEnergy(const mesh::TetMesh& mesh, const DofMap& dofs, std::vector<double> element_kappa)
    : mesh_(mesh), dofs_(dofs) {
  if (mesh.is_quadratic())
    throw Error("internal: the nodal-pressure tetrahedron takes a linear mesh, not " + mesh.source + "'s quadratic one");
  if (static_cast<Index>(element_kappa.size()) != mesh.num_tets())
    throw Error("internal: nodal volumetric energy: one bulk modulus per tetrahedron");
  const Index N = mesh.num_nodes(), T = mesh.num_tets();
  grad_.resize(as_size(T));
  volume_.resize(T);
  nodal_volume_ = Vector::Zero(N);
  nodal_kappa_ = Vector::Zero(N);
  std::vector<Eigen::Triplet<double>> g_entries;
  for (Index e = 0; e < T; ++e) {
    const auto& tet = mesh.tets[as_size(e)];
    const Tet4Geometry g = tet4_geometry(mesh.node(tet[0]), mesh.node(tet[1]), mesh.node(tet[2]), mesh.node(tet[3]));
    grad_[as_size(e)] = g.grad;
    volume_[e] = std::abs(g.volume);
    for (int a = 0; a < 4; ++a) {
      nodal_volume_[tet[as_size(a)]] += volume_[e] / 4;
      nodal_kappa_[tet[as_size(a)]] += element_kappa[as_size(e)] * volume_[e] / 4;
      for (int k = 0; k < 12; ++k)
        if (const int dof = dofs.free_dof(tet[as_size(k / 3)], k % 3); dof >= 0)
          g_entries.emplace_back(tet[as_size(a)], dof, 1.0);
    }
  }
  for (Index a = 0; a < N; ++a)
    if (nodal_volume_[a] > 0) nodal_kappa_[a] /= nodal_volume_[a];
  G_pattern_.resize(N, dofs.num_free());
  G_pattern_.setFromTriplets(g_entries.begin(), g_entries.end());
  G_pattern_.makeCompressed();
  pattern_ = SparseMatrix(G_pattern_.transpose() * G_pattern_);
  pattern_.makeCompressed();
  std::fill(pattern_.valuePtr(), pattern_.valuePtr() + pattern_.nonZeros(), 0.0);
  std::fill(G_pattern_.valuePtr(), G_pattern_.valuePtr() + G_pattern_.nonZeros(), 0.0);
  G_positions_.assign(as_size(48 * T), -1);
  const int* outer = G_pattern_.outerIndexPtr();
  const int* inner = G_pattern_.innerIndexPtr();
  for (Index e = 0; e < T; ++e) {
    const auto& tet = mesh.tets[as_size(e)];
    for (int k = 0; k < 12; ++k) {
      const int dof = dofs.free_dof(tet[as_size(k / 3)], k % 3);
      if (dof < 0) continue;
      for (int a = 0; a < 4; ++a)
        G_positions_[as_size(48 * e + 4 * k + a)] =
            static_cast<int>(std::lower_bound(inner + outer[dof], inner + outer[dof + 1], tet[as_size(a)]) - inner);
    }
  }
}

void NodalVolumetricEnergy::check_size(const Vector& u_full) const {
  if (u_full.size() != 3 * mesh_.num_nodes())
    throw InputError(format("nodal volumetric energy: %lld displacement values for %lld nodes",
                            static_cast<long long>(u_full.size()), static_cast<long long>(mesh_.num_nodes())));
}

NodalVolumetricEnergy::Strains NodalVolumetricEnergy::strains(const Vector& u_full) const {
  check_size(u_full);
  const Index N = mesh_.num_nodes(), T = mesh_.num_tets();
  Strains s;
  s.H.resize(as_size(T));
  s.J_minus_1.resize(T);
  s.nodal_J_minus_1 = Vector::Zero(N);
  for (Index e = 0; e < T; ++e) {
    const auto& tet = mesh_.tets[as_size(e)];
    Mat3 H = Mat3::Zero();
    for (int a = 0; a < 4; ++a) H += u_full.segment<3>(3 * tet[as_size(a)]) * grad_[as_size(e)].row(a);
    s.H[as_size(e)] = H;
    s.J_minus_1[e] = NeoHookean::J_minus_1(H);
    for (int a = 0; a < 4; ++a) s.nodal_J_minus_1[tet[as_size(a)]] += volume_[e] / 4 * s.J_minus_1[e];
  }
  for (Index a = 0; a < N; ++a)
    if (nodal_volume_[a] > 0) s.nodal_J_minus_1[a] /= nodal_volume_[a];
  s.nodal_pressure = nodal_kappa_.cwiseProduct(s.nodal_J_minus_1);
  return s;
}

double NodalVolumetricEnergy::element_pressure(const Strains& s, Index e) const {
  const auto& tet = mesh_.tets[as_size(e)];
  return 0.25 * (s.nodal_pressure[tet[0]] + s.nodal_pressure[tet[1]] + s.nodal_pressure[tet[2]] + s.nodal_pressure[tet[3]]);
}

void NodalVolumetricEnergy::scatter(Index e, const Eigen::Matrix<double, 12, 1>& f_e, Eigen::Ref<Vector> f) const {
  const auto& tet = mesh_.tets[as_size(e)];
  for (int k = 0; k < 12; ++k)
    if (const int row = dofs_.free_dof(tet[as_size(k / 3)], k % 3); row >= 0) f[row] += f_e[k];
}

double NodalVolumetricEnergy::energy(const Vector& u_full) const {
  const Strains s = strains(u_full);
  return 0.5 * (nodal_volume_.array() * s.nodal_pressure.array() * s.nodal_J_minus_1.array()).sum();
}

void NodalVolumetricEnergy::add_force(const Vector& u_full, Eigen::Ref<Vector> f) const {
  const Strains s = strains(u_full);
  for (Index e = 0; e < mesh_.num_tets(); ++e) {
    const Mat3 cof_F = Mat3::Identity() + cofactor_of_F_minus_identity(s.H[as_size(e)]);
    scatter(e, element_vector(grad_[as_size(e)], cof_F, volume_[e] * element_pressure(s, e)), f);
  }
}

void NodalVolumetricEnergy::add_excess_force(const Vector& u_full, Eigen::Ref<Vector> g) const {
  // p_e cof(F) - p_e^lin I = (p_e - p_e^lin) cof(F) + p_e^lin (cof(F) - I), with p^lin the linear
  // element's nodal pressure kappa_a theta_a (theta_a the nodes' mean tr(H)), and p - p^lin from
  // J_e - 1 - tr(H_e): each factor formed from H.
  const Strains s = strains(u_full);
  const Index N = mesh_.num_nodes(), T = mesh_.num_tets();
  Vector theta = Vector::Zero(N), beyond = Vector::Zero(N);
  for (Index e = 0; e < T; ++e)
    for (const int a : mesh_.tets[as_size(e)]) {
      theta[a] += volume_[e] / 4 * s.H[as_size(e)].trace();
      beyond[a] += volume_[e] / 4 * J_beyond_linear(s.H[as_size(e)]);
    }
  for (Index a = 0; a < N; ++a)
    if (nodal_volume_[a] > 0) {
      theta[a] *= nodal_kappa_[a] / nodal_volume_[a];
      beyond[a] *= nodal_kappa_[a] / nodal_volume_[a];
    }
  for (Index e = 0; e < T; ++e) {
    const auto& tet = mesh_.tets[as_size(e)];
    const double p_linear = 0.25 * (theta[tet[0]] + theta[tet[1]] + theta[tet[2]] + theta[tet[3]]);
    const double p_beyond = 0.25 * (beyond[tet[0]] + beyond[tet[1]] + beyond[tet[2]] + beyond[tet[3]]);
    const Mat3 cof_minus_I = cofactor_of_F_minus_identity(s.H[as_size(e)]);
    const Mat3 A = p_beyond * (Mat3::Identity() + cof_minus_I) + p_linear * cof_minus_I;
    scatter(e, element_vector(grad_[as_size(e)], A, volume_[e]), g);
  }
}

void NodalVolumetricEnergy::add_force_and_tangent(const Vector& u_full, Eigen::Ref<Vector> f, SparseMatrix& K) const {
  const Strains s = strains(u_full);
  SparseMatrix G = G_pattern_;
  double* G_values = G.valuePtr();
  double* K_values = K.valuePtr();
  const int* outer = K.outerIndexPtr();
  const int* inner = K.innerIndexPtr();
  for (Index e = 0; e < mesh_.num_tets(); ++e) {
    const auto& tet = mesh_.tets[as_size(e)];
    const auto& g = grad_[as_size(e)];
    const Mat3 F = Mat3::Identity() + s.H[as_size(e)];
    const Mat3 cof_F = Mat3::Identity() + cofactor_of_F_minus_identity(s.H[as_size(e)]);
    const double p = element_pressure(s, e), V = volume_[e];
    const Eigen::Matrix<double, 12, 1> dJ = element_vector(g, cof_F, 1.0);  // dJ_e/dx_e
    scatter(e, V * p * dJ, f);
    // dJ_a/dx = sum over a's elements of (V_e / 4) dJ_e/dx / V_a.
    for (int k = 0; k < 12; ++k)
      for (int a = 0; a < 4; ++a)
        if (const int at = G_positions_[as_size(48 * e + 4 * k + a)]; at >= 0)
          G_values[at] += V / 4 * dJ[k] / nodal_volume_[tet[as_size(a)]];
    // V p d^2J/dx_bi dx_ck = V p sum_m eps_ikm (F (g_b x g_c))_m.
    for (int c = 0; c < 4; ++c)
      for (int k = 0; k < 3; ++k) {
        const int column = dofs_.free_dof(tet[as_size(c)], k);
        if (column < 0) continue;
        const int* begin = inner + outer[column];
        const int* end = inner + outer[column + 1];
        for (int b = 0; b < 4; ++b) {
          if (b == c) continue;  // g_b x g_b = 0
          const Vec3 w = V * p * (F * Vec3(g.row(b)).cross(Vec3(g.row(c))));
          for (int i = 0; i < 3; ++i) {
            if (i == k) continue;
            const int row = dofs_.free_dof(tet[as_size(b)], i);
            if (row < 0) continue;
            const int m = 3 - i - k;
            const double sign = (i + 1) % 3 == k ? 1.0 : -1.0;  // eps_ikm
            K_values[std::lower_bound(begin, end, row) - inner] += sign * w[m];
          }
        }
      }
  }
  const SparseMatrix GtDG = SparseMatrix(G.transpose() * (nodal_volume_.cwiseProduct(nodal_kappa_)).asDiagonal() * G);
  const std::vector<int> at = solvers::positions_in(GtDG, K);
  for (std::size_t i = 0; i < at.size(); ++i) K_values[at[i]] += GtDG.valuePtr()[i];
}

}  // namespace roifem::fem
