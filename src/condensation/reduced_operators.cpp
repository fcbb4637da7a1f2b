// SPDX-License-Identifier: GPL-3.0-or-later
#include "condensation/reduced_operators.hpp"

namespace roifem::condensation {

namespace {

using Triplets = std::vector<Eigen::Triplet<double>>;

SparseMatrix from_triplets(Index n, const Triplets& t) {
  SparseMatrix A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

/// A with its rows and columns extended by zeros to n.
SparseMatrix padded(const SparseMatrix& A, Index n) {
  SparseMatrix B = A;
  B.conservativeResize(n, n);
  return B;
}

}  // namespace

SparseMatrix assembled(const model::SplitMatrix& A) {
  Triplets t;
  t.reserve(static_cast<std::size_t>(A.sparse.nonZeros() + A.block.size()));
  for (Index j = 0; j < A.sparse.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(A.sparse, j); it; ++it) t.emplace_back(it.row(), it.col(), it.value());
  for (Index b = 0; b < A.block.cols(); ++b)
    for (Index a = 0; a < A.block.rows(); ++a)
      t.emplace_back(A.index[static_cast<std::size_t>(a)], A.index[static_cast<std::size_t>(b)], A.block(a, b));
  return from_triplets(A.sparse.rows(), t);
}

model::SplitMatrix reduced_stiffness(const SparseMatrix& K, const roi::Partition& partition, const DenseMatrix& schur,
                                     const Vector& omega) {
  const auto n_d = static_cast<Index>(partition.d.size());
  const Index k = omega.size();
  Triplets t;
  const SparseMatrix K_dd = roi::submatrix(K, partition.d, partition.d);
  for (Index j = 0; j < K_dd.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(K_dd, j); it; ++it) t.emplace_back(it.row(), it.col(), it.value());
  for (Index j = 0; j < k; ++j) t.emplace_back(n_d + j, n_d + j, omega[j] * omega[j]);
  model::SplitMatrix K_r;
  K_r.sparse = from_triplets(n_d + k, t);
  K_r.index = partition.interface;
  K_r.block = -schur;
  return K_r;
}

model::SplitMatrix reduced_diagonal_operator(const SparseMatrix& D_full, const roi::Partition& partition, const DenseMatrix& X,
                                             const model::Modes& basis, bool carries_mass) {
  const auto n_d = static_cast<Index>(partition.d.size());
  const auto n_i = static_cast<Index>(partition.interface.size());
  const Index k = basis.omega.size();
  const DenseMatrix& Phi = basis.shapes;
  model::SplitMatrix D;
  D.sparse = padded(roi::submatrix(D_full, partition.d, partition.d), n_d + k);
  if (!carries_mass) return D;
  const Vector D_s = roi::gather(D_full.diagonal(), partition.s);
  D.index = partition.interface;
  for (Index j = 0; j < k; ++j) D.index.push_back(n_d + j);
  const DenseMatrix DX = D_s.asDiagonal() * X;
  D.block.resize(n_i + k, n_i + k);
  const DenseMatrix XtDX = X.transpose() * DX;
  D.block.topLeftCorner(n_i, n_i) = 0.5 * (XtDX + XtDX.transpose());
  if (k > 0) {
    D.block.topRightCorner(n_i, k) = -DX.transpose() * Phi;  // -P^T X^T D_s Phi
    D.block.bottomLeftCorner(k, n_i) = D.block.topRightCorner(n_i, k).transpose();
    const DenseMatrix PtDP = Phi.transpose() * D_s.asDiagonal() * Phi;
    D.block.bottomRightCorner(k, k) = 0.5 * (PtDP + PtDP.transpose());
  }
  return D;
}

ReducedLoads reduce_loads(const model::LoadHistory& load, const roi::Partition& partition, StaticPartFactor& factor,
                          const model::Modes& basis) {
  const auto n_d = static_cast<Index>(partition.d.size());
  const auto n_i = static_cast<Index>(partition.interface.size());
  const Index k = basis.omega.size();
  ReducedLoads out{model::LoadHistory(n_d + k), model::LoadHistory(static_cast<Index>(partition.s.size()))};
  // One K_ss solve per pattern serves both f_r and the recovery of u_s.
  for (const auto& term : load.terms()) {
    Vector f = Vector::Zero(n_d + k);
    f.head(n_d) = roi::gather(term.pattern, partition.d);
    Vector z;
    if (factor.has_static_part()) {
      const Vector p_s = roi::gather(term.pattern, partition.s);
      z = factor.solve_static(p_s);
      const Vector correction = factor.K_sI().transpose() * z;  // X^T p_s
      for (Index a = 0; a < n_i; ++a) f[partition.interface[static_cast<std::size_t>(a)]] -= correction[a];
      if (k > 0) {
        const Vector participation = basis.shapes.transpose() * p_s;
        f.tail(k) = participation;
        z.noalias() -= basis.shapes * participation.cwiseQuotient(basis.omega.cwiseAbs2());
      }
    }
    out.reduced.add(std::move(f), term.ramp);
    out.static_response.add(std::move(z), term.ramp);
  }
  return out;
}

}  // namespace roifem::condensation
