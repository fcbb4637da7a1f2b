// SPDX-License-Identifier: GPL-3.0-or-later
#include "model/second_order_system.hpp"

#include <algorithm>
#include <cmath>

#include "model/internal_force.hpp"
#include "solvers/dense_blas.hpp"

namespace roifem::model {

SparseMatrix diagonal_matrix(const Vector& d) {
  SparseMatrix D(d.size(), d.size());
  D.reserve(Eigen::VectorXi::Ones(d.size()));
  for (Index i = 0; i < d.size(); ++i) D.insert(i, i) = d[i];
  D.makeCompressed();
  return D;
}

void SplitMatrix::apply(const Eigen::Ref<const Vector>& x, Eigen::Ref<Vector> y) const {
  // Symmetric: A x = A^T x, and the transposed product of a column-major matrix runs as row dot
  // products (no scattered writes), faster (docs/design-figures.md).
  y.noalias() = sparse.transpose() * x;
  const Index m = static_cast<Index>(index.size());
  if (m == 0) return;
  thread_local Vector gathered, product;
  gathered.resize(m);
  product.resize(m);
  for (Index a = 0; a < m; ++a) gathered[a] = x[index[static_cast<std::size_t>(a)]];
  solvers::multiply_symmetric(block, gathered, 0.0, product);  // reads half the block
  for (Index a = 0; a < m; ++a) y[index[static_cast<std::size_t>(a)]] += product[a];
}

void SecondOrderSystem::apply_stiffness(const Eigen::Ref<const Vector>& x, Eigen::Ref<Vector> y) const {
  if (K_split.empty())
    y.noalias() = K.transpose() * x;  // symmetric; see SplitMatrix::apply
  else
    K_split.apply(x, y);
}

void SecondOrderSystem::apply_mass(const Eigen::Ref<const Vector>& x, Eigen::Ref<Vector> y) const {
  if (M_split.empty())
    y.noalias() = M.transpose() * x;
  else
    M_split.apply(x, y);
}

std::vector<Index> SecondOrderSystem::dense_block_dofs() const {
  std::vector<Index> dofs = K_split.index;
  dofs.insert(dofs.end(), M_split.index.begin(), M_split.index.end());
  std::sort(dofs.begin(), dofs.end());
  dofs.erase(std::unique(dofs.begin(), dofs.end()), dofs.end());
  return dofs;
}

double mass_proportional_damping(const SecondOrderSystem& system, double tolerance) {
  const double m2 = system.M.squaredNorm();
  const double alpha = m2 > 0 ? system.C.cwiseProduct(system.M).sum() / m2 : 0.0;
  return (system.C - alpha * system.M).norm() <= tolerance * system.C.norm() ? alpha : NAN;
}

SecondOrderSystem with_ramp(const SecondOrderSystem& system, const Ramp& ramp) {
  SecondOrderSystem ramped = system;
  ramped.load = system.load.with_ramp(ramp);
  if (system.internal_force) ramped.internal_force = system.internal_force->with_ramp(ramp);
  return ramped;
}

double kinetic_energy(const SecondOrderSystem& sys, const State& s) {
  Vector Mv(s.v.size());
  sys.apply_mass(s.v, Mv);
  return 0.5 * s.v.dot(Mv);
}

double strain_energy(const SecondOrderSystem& sys, const State& s) {
  if (sys.internal_force) return sys.internal_force->energy(s.t, s.u);
  Vector Ku(s.u.size());
  sys.apply_stiffness(s.u, Ku);
  return 0.5 * s.u.dot(Ku);
}

}  // namespace roifem::model
