// SPDX-License-Identifier: GPL-3.0-or-later
#include "fem/nodal_volumetric_energy.hpp"

#include <algorithm>
#include <cmath>

#include "common/errors.hpp"
#include "common/format.hpp"
#include "fem/neo_hookean.hpp"
#include "fem/tet4.hpp"

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
  SparseMatrix G0(N, dofs.num_free());
  G0.setFromTriplets(g_entries.begin(), g_entries.end());
  pattern_ = SparseMatrix(SparseMatrix(G0.transpose()) * G0);
  pattern_.makeCompressed();
  std::fill(pattern_.valuePtr(), pattern_.valuePtr() + pattern_.nonZeros(), 0.0);
  // The patches: G0's rows, as row-major.
  const Eigen::SparseMatrix<double, Eigen::RowMajor, int> rows(G0);
  patch_begin_.assign(rows.outerIndexPtr(), rows.outerIndexPtr() + N + 1);
  patch_dofs_.assign(rows.innerIndexPtr(), rows.innerIndexPtr() + rows.nonZeros());
  element_local_.assign(as_size(48 * T), -1);
  for (Index e = 0; e < T; ++e) {
    const auto& tet = mesh.tets[as_size(e)];
    for (int a = 0; a < 4; ++a) {
      const int* begin = patch_dofs_.data() + patch_begin_[as_size(tet[as_size(a)])];
      const int* end = patch_dofs_.data() + patch_begin_[as_size(tet[as_size(a)]) + 1];
      for (int k = 0; k < 12; ++k)
        if (const int dof = dofs.free_dof(tet[as_size(k / 3)], k % 3); dof >= 0)
          element_local_[as_size(48 * e + 12 * a + k)] = static_cast<int>(std::lower_bound(begin, end, dof) - begin);
    }
  }
  std::size_t entries = 0;
  block_begin_.assign(as_size(N) + 1, 0);
  for (Index a = 0; a < N; ++a) {
    const auto m = static_cast<std::size_t>(patch_begin_[as_size(a) + 1] - patch_begin_[as_size(a)]);
    entries += m * m;
    block_begin_[as_size(a) + 1] = entries;
  }
  constexpr std::size_t budget = std::size_t{32} << 20;
  if (entries > budget) return;
  block_positions_.resize(entries);
  for (Index a = 0; a < N; ++a) {
    const int m = patch_begin_[as_size(a) + 1] - patch_begin_[as_size(a)];
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i)
        block_positions_[block_begin_[as_size(a)] + as_size(j * m + i)] = position(pattern_, false, a, i, j);
  }
}

int NodalVolumetricEnergy::position(const SparseMatrix& K, bool cached, Index a, int i, int j) const {
  const int m = patch_begin_[as_size(a) + 1] - patch_begin_[as_size(a)];
  if (cached) return block_positions_[block_begin_[as_size(a)] + as_size(j * m + i)];
  const int* dofs = patch_dofs_.data() + patch_begin_[as_size(a)];
  const int* inner = K.innerIndexPtr();
  const int* begin = inner + K.outerIndexPtr()[dofs[j]];
  const int* end = inner + K.outerIndexPtr()[dofs[j] + 1];
  return static_cast<int>(std::lower_bound(begin, end, dofs[i]) - inner);
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
  // Positions cached against pattern() hold for K in that very pattern.
  const bool cached = !block_positions_.empty() && K.nonZeros() == pattern_.nonZeros() && K.rows() == pattern_.rows();
  std::vector<double> G(patch_dofs_.size(), 0.0);  // G_a = dJ_a/dx over a's patch
  double* K_values = K.valuePtr();
  for (Index e = 0; e < mesh_.num_tets(); ++e) {
    const auto& tet = mesh_.tets[as_size(e)];
    const auto& g = grad_[as_size(e)];
    const Mat3 F = Mat3::Identity() + s.H[as_size(e)];
    const Mat3 cof_F = Mat3::Identity() + cofactor_of_F_minus_identity(s.H[as_size(e)]);
    const double p = element_pressure(s, e), V = volume_[e];
    const Eigen::Matrix<double, 12, 1> dJ = element_vector(g, cof_F, 1.0);  // dJ_e/dx_e
    scatter(e, V * p * dJ, f);
    // dJ_a/dx = sum over a's elements of (V_e / 4) dJ_e/dx / V_a.
    for (int a = 0; a < 4; ++a) {
      const auto node = as_size(tet[as_size(a)]);
      double* G_a = G.data() + patch_begin_[node];
      const double share = V / 4 / nodal_volume_[tet[as_size(a)]];
      for (int k = 0; k < 12; ++k)
        if (const int l = element_local_[as_size(48 * e + 12 * a + k)]; l >= 0) G_a[l] += share * dJ[k];
    }
    // V p d^2J/dx_bi dx_ck = V p sum_m eps_ikm (F (g_b x g_c))_m, in corner 0's patch, which holds
    // every dof of the element.
    const int* local = element_local_.data() + 48 * e;
    for (int c = 0; c < 4; ++c)
      for (int k = 0; k < 3; ++k) {
        const int column = local[3 * c + k];
        if (column < 0) continue;
        for (int b = 0; b < 4; ++b) {
          if (b == c) continue;  // g_b x g_b = 0
          const Vec3 w = V * p * (F * Vec3(g.row(b)).cross(Vec3(g.row(c))));
          for (int i = 0; i < 3; ++i) {
            const int row = local[3 * b + i];
            if (i == k || row < 0) continue;
            const int m = 3 - i - k;
            const double sign = (i + 1) % 3 == k ? 1.0 : -1.0;  // eps_ikm
            K_values[position(K, cached, tet[0], row, column)] += sign * w[m];
          }
        }
      }
  }
  // sum_a V_a kappa_a G_a G_a^T, block by block.
  for (Index a = 0; a < mesh_.num_nodes(); ++a) {
    const int m = patch_begin_[as_size(a) + 1] - patch_begin_[as_size(a)];
    const double* G_a = G.data() + patch_begin_[as_size(a)];
    const double weight = nodal_volume_[a] * nodal_kappa_[a];
    for (int j = 0; j < m; ++j) {
      const double column = weight * G_a[j];
      if (column == 0) continue;
      for (int i = 0; i < m; ++i) K_values[position(K, cached, a, i, j)] += column * G_a[i];
    }
  }
}

}  // namespace roifem::fem
