#include "condensation/static_condensation.hpp"

#include "common/errors.hpp"
#include "common/timer.hpp"
#include "solvers/cholesky.hpp"

namespace roifem::condensation {

StaticCondensation::StaticCondensation(const model::SecondOrderSystem& full, const roi::Partition& partition,
                                       const fem::DofMap& dofs)
    : partition_(partition) {
  const auto& d = partition_.d;
  const auto& s = partition_.s;
  if (d.empty()) throw ModelError("static condensation: the ROI has no free dof");
  const Index n_i = static_cast<Index>(partition_.interface.size());
  std::vector<Index> interface_dofs;  // the interface as free dof indices
  for (Index k : partition_.interface) interface_dofs.push_back(d[static_cast<std::size_t>(k)]);

  Stopwatch clock;
  solvers::Cholesky K_ss_factor;
  if (!s.empty()) {
    const SparseMatrix K_ss = roi::submatrix(full.K, s, s);
    try {
      K_ss_factor.compute(K_ss);
    } catch (const solvers::NotPositiveDefinite& e) {
      std::string where = "a part of it is free to move as a rigid body";
      if (e.column >= 0) {
        const Index node = dofs.full_dof(s[static_cast<std::size_t>(e.column)]) / 3;
        where = "the factorization stopped at node " + std::to_string(node);
      }
      throw ModelError("static part K_ss is singular: " + where +
                       "; every static piece needs a fixed node or a connection to the ROI");
    }
    timings_.factorization_s = clock.seconds();
    clock.restart();
    const DenseMatrix K_sI(roi::submatrix(full.K, s, interface_dofs));
    X_ = K_ss_factor.solve_matrix(K_sI);
    schur_ = K_sI.transpose() * X_;
    // S is symmetric in exact arithmetic; make it so in floating point, so that products (which
    // read one triangle) and factorizations (which read the other) see the same matrix.
    schur_ = (0.5 * (schur_ + schur_.transpose())).eval();
    timings_.interface_solve_s = clock.seconds();
  } else {
    X_.resize(0, n_i);
    schur_ = DenseMatrix::Zero(n_i, n_i);
  }
  clock.restart();

  // K~ = K_dd - S on the interface block (the block becomes dense; the rest stays sparse).
  const SparseMatrix K_dd = roi::submatrix(full.K, d, d);
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(static_cast<std::size_t>(K_dd.nonZeros() + n_i * n_i));
  for (Index j = 0; j < K_dd.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(K_dd, j); it; ++it) triplets.emplace_back(it.row(), it.col(), it.value());
  for (Index b = 0; b < n_i; ++b)
    for (Index a = 0; a < n_i; ++a)
      triplets.emplace_back(partition_.interface[static_cast<std::size_t>(a)],
                            partition_.interface[static_cast<std::size_t>(b)], -schur_(a, b));
  reduced_.K.resize(K_dd.rows(), K_dd.cols());
  reduced_.K.setFromTriplets(triplets.begin(), triplets.end());
  reduced_.K_split.sparse = K_dd;
  reduced_.K_split.index = partition_.interface;
  reduced_.K_split.block = -schur_;
  reduced_.M = roi::submatrix(full.M, d, d);
  reduced_.C = roi::submatrix(full.C, d, d);

  // f~ = f_d - X^T f_s per load pattern; K_ss^-1 f_s kept for recovering u_s.
  reduced_.load = full.load.mapped(static_cast<Index>(d.size()), [&](const Vector& p) {
    Vector f = roi::gather(p, d);
    if (!s.empty()) {
      const Vector correction = X_.transpose() * roi::gather(p, s);
      for (Index a = 0; a < n_i; ++a) f[partition_.interface[static_cast<std::size_t>(a)]] -= correction[a];
    }
    return f;
  });
  static_response_ = full.load.mapped(static_cast<Index>(s.size()), [&](const Vector& p) {
    return s.empty() ? Vector() : K_ss_factor.solve(roi::gather(p, s));
  });
  timings_.assembly_s = clock.seconds();
}

Vector StaticCondensation::recover_static(const Vector& u_d, double t) const {
  Vector u_s = static_response_.at(t);
  if (u_s.size() == 0) return u_s;
  Vector u_i(static_cast<Index>(partition_.interface.size()));
  for (std::size_t a = 0; a < partition_.interface.size(); ++a)
    u_i[static_cast<Index>(a)] = u_d[partition_.interface[a]];
  u_s.noalias() -= X_ * u_i;
  return u_s;
}

Vector StaticCondensation::expand(const Vector& u_d, double t) const {
  const Vector u_s = recover_static(u_d, t);
  Vector u(static_cast<Index>(partition_.d.size() + partition_.s.size()));
  for (std::size_t k = 0; k < partition_.d.size(); ++k) u[partition_.d[k]] = u_d[static_cast<Index>(k)];
  for (std::size_t k = 0; k < partition_.s.size(); ++k) u[partition_.s[k]] = u_s[static_cast<Index>(k)];
  return u;
}

}  // namespace roifem::condensation
