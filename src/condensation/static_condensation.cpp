#include "condensation/static_condensation.hpp"

#include <algorithm>

#include "common/errors.hpp"
#include "common/timer.hpp"
#include "condensation/pod_basis.hpp"
#include "model/mass_inverse.hpp"
#include "model/spectrum.hpp"
#include "solvers/partial_cholesky.hpp"

namespace roifem::condensation {

namespace {

using Triplets = std::vector<Eigen::Triplet<double>>;

SparseMatrix from_triplets(Index n, const Triplets& t) {
  SparseMatrix A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

/// The split matrix assembled: sparse part plus P^T B P.
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

/// A with its rows and columns extended by zeros to n.
SparseMatrix padded(const SparseMatrix& A, Index n) {
  SparseMatrix B = A;
  B.conservativeResize(n, n);
  return B;
}

}  // namespace

StaticCondensation::StaticCondensation(const model::SecondOrderSystem& full, const roi::Partition& partition,
                                       const fem::DofMap& dofs, const Reduction& reduction)
    : partition_(partition), reduction_(reduction) {
  const auto& d = partition_.d;
  const auto& s = partition_.s;
  if (d.empty()) throw ModelError("static condensation: the ROI has no free dof");
  const bool with_mass = reduction.kind != ReductionKind::static_condensation;
  const bool with_pod = reduction.kind == ReductionKind::pod;
  const bool with_modes = reduction.kind == ReductionKind::craig_bampton || with_pod;
  if (with_pod && reduction.modes <= 0) throw InputError("POD reduction: give a positive number of vectors");
  if (with_modes && reduction.modes <= 0 && !(reduction.cutoff_rad_s > 0))
    throw InputError("Craig-Bampton: give a positive number of modes or a positive cut-off frequency");
  if (with_mass && !(model::is_diagonal(full.M) && model::is_diagonal(full.C)))
    throw InputError(reduction.label() + " reduction: needs the lumped (diagonal) M and C of the full model");
  const Index n_i = static_cast<Index>(partition_.interface.size());
  const Index n_d = static_cast<Index>(d.size());
  std::vector<Index> interface_dofs;  // the interface as free dof indices
  for (Index k : partition_.interface) interface_dofs.push_back(d[static_cast<std::size_t>(k)]);

  Stopwatch clock;
  if (!s.empty()) {
    // One factorization of K over the static dofs and the interface, the interface ordered last:
    // its trailing block is K_II - S, and its leading block solves with K_ss (no solve per
    // interface column, no dense #s x #I matrix).
    std::vector<Index> static_and_interface = s;
    static_and_interface.insert(static_and_interface.end(), interface_dofs.begin(), interface_dofs.end());
    std::sort(static_and_interface.begin(), static_and_interface.end());
    std::vector<Index> trailing;
    for (Index dof : interface_dofs)
      trailing.push_back(std::lower_bound(static_and_interface.begin(), static_and_interface.end(), dof) -
                         static_and_interface.begin());
    try {
      K_ss_factor_ = std::make_shared<const solvers::PartialCholesky>(
          roi::submatrix(full.K, static_and_interface, static_and_interface), trailing);
    } catch (const solvers::NotPositiveDefinite& e) {
      std::string where = "a part of it is free to move as a rigid body";
      if (e.column >= 0) {
        const Index node = dofs.full_dof(static_and_interface[static_cast<std::size_t>(e.column)]) / 3;
        where = "the factorization stopped at node " + std::to_string(node);
      }
      throw ModelError("static part K_ss is singular: " + where +
                       "; every static piece needs a fixed node or a connection to the ROI");
    }
    timings_.factorization_s = clock.seconds();
    clock.restart();
    K_sI_ = roi::submatrix(full.K, s, interface_dofs);
    // S = K_II - (K_II - S); symmetric in exact arithmetic, and made so in floating point, so that
    // products (which read one triangle) and factorizations (the other) see the same matrix.
    const DenseMatrix K_II(roi::submatrix(full.K, interface_dofs, interface_dofs));
    schur_ = K_II - K_ss_factor_->trailing_schur_complement();
    schur_ = (0.5 * (schur_ + schur_.transpose())).eval();
    if (with_mass) {  // Guyan and Craig-Bampton carry the static part's mass through X = K_ss^-1 K_sI
      X_.resize(static_cast<Index>(s.size()), n_i);
      const DenseMatrix K_sI(K_sI_);
      for (Index j = 0; j < n_i; ++j) X_.col(j) = K_ss_factor_->solve_leading(K_sI.col(j));
    }
    timings_.interface_solve_s = clock.seconds();
  } else {
    schur_ = DenseMatrix::Zero(n_i, n_i);
  }
  if (s.empty()) X_.resize(0, n_i);

  const Vector M_s = roi::gather(full.M.diagonal(), s), C_s = roi::gather(full.C.diagonal(), s);
  if (with_modes && !s.empty()) {
    clock.restart();
    const model::SolveK solve_K_ss = [factor = K_ss_factor_](const Vector& b, Vector& x) { factor->solve_leading(b, x); };
    const Index most = static_cast<Index>(s.size());
    const model::Modes modes = [&] {
      if (with_pod)
        return pod_basis({full, partition_, X_, reduction.snapshot_dt_s, reduction.snapshot_steps}, std::min(reduction.modes, most));
      if (reduction.modes > 0) return model::lowest_modes(M_s, solve_K_ss, std::min(reduction.modes, most));
      return model::modes_below(M_s, solve_K_ss, reduction.cutoff_rad_s);
    }();
    omega_ = modes.omega;
    Phi_ = modes.shapes;
    timings_.modes_s = clock.seconds();
  }
  const Index k = num_modes();
  Phi_.resize(static_cast<Index>(s.size()), k);
  clock.restart();

  // Index lists of the reduced system: the interface rows, and the modal coordinates after d.
  std::vector<Index> modal(static_cast<std::size_t>(k));
  for (Index j = 0; j < k; ++j) modal[static_cast<std::size_t>(j)] = n_d + j;
  const Index n_r = n_d + k;

  // K_r = diag(K_dd - S on the interface block, W^2); kept split (products) and assembled (factorizations).
  {
    Triplets t;
    const SparseMatrix K_dd = roi::submatrix(full.K, d, d);
    for (Index j = 0; j < K_dd.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(K_dd, j); it; ++it) t.emplace_back(it.row(), it.col(), it.value());
    for (Index j = 0; j < k; ++j) t.emplace_back(n_d + j, n_d + j, omega_[j] * omega_[j]);
    reduced_.K_split.sparse = from_triplets(n_r, t);
    reduced_.K_split.index = partition_.interface;
    reduced_.K_split.block = -schur_;
    reduced_.K = assembled(reduced_.K_split);
  }

  // M_r and C_r: T^T D T for the diagonal D = M, C of the full model, a dense block on the interface
  // and the modal coordinates, [[X^T D_s X, -X^T D_s Phi], [sym, Phi^T D_s Phi]] (or D_dd alone).
  auto reduce_diagonal = [&](const SparseMatrix& D_full, const Vector& D_s) {
    model::SplitMatrix D;
    D.sparse = padded(roi::submatrix(D_full, d, d), n_r);
    if (!with_mass) return D;
    D.index = partition_.interface;
    D.index.insert(D.index.end(), modal.begin(), modal.end());
    const DenseMatrix DX = D_s.asDiagonal() * X_;
    D.block.resize(n_i + k, n_i + k);
    const DenseMatrix XtDX = X_.transpose() * DX;
    D.block.topLeftCorner(n_i, n_i) = 0.5 * (XtDX + XtDX.transpose());
    if (k > 0) {
      D.block.topRightCorner(n_i, k) = -DX.transpose() * Phi_;  // -P^T X^T D_s Phi
      D.block.bottomLeftCorner(k, n_i) = D.block.topRightCorner(n_i, k).transpose();
      const DenseMatrix PtDP = Phi_.transpose() * D_s.asDiagonal() * Phi_;
      D.block.bottomRightCorner(k, k) = 0.5 * (PtDP + PtDP.transpose());
    }
    return D;
  };
  reduced_.M_split = reduce_diagonal(full.M, M_s);
  // Phi is M_ss-orthonormal, so its block of M is I (as computed, I to ~1e-13): set exactly, as
  // SecondOrderSystem::modal_coordinates promises.
  if (k > 0) reduced_.M_split.block.bottomRightCorner(k, k).setIdentity();
  reduced_.M = assembled(reduced_.M_split);
  reduced_.C = assembled(reduce_diagonal(full.C, C_s));
  reduced_.damping = full.damping;  // T^T (alpha M) T = alpha M_r
  if (k > 0) reduced_.modal = model::ModalBlock{.count = k, .interface_dofs = n_i};
  if (!with_mass) reduced_.M_split = {};  // diagonal: the plain product is the fast one

  // f_r = [f_d - X^T f_s on the interface; Phi^T f_s] per load pattern; K_ss^-1 f_s kept for
  // recovering u_s (less its modal part, which eta carries). One K_ss solve per pattern serves both.
  reduced_.load = model::LoadHistory(n_r);
  static_response_ = model::LoadHistory(static_cast<Index>(s.size()));
  for (const auto& term : full.load.terms()) {
    Vector f = Vector::Zero(n_r);
    f.head(n_d) = roi::gather(term.pattern, d);
    Vector z;
    if (!s.empty()) {
      const Vector p_s = roi::gather(term.pattern, s);
      z = K_ss_factor_->solve_leading(p_s);
      const Vector correction = K_sI_.transpose() * z;  // X^T p_s
      for (Index a = 0; a < n_i; ++a) f[partition_.interface[static_cast<std::size_t>(a)]] -= correction[a];
      if (k > 0) {
        const Vector participation = Phi_.transpose() * p_s;
        f.tail(k) = participation;
        z.noalias() -= Phi_ * participation.cwiseQuotient(omega_.cwiseAbs2());
      }
    }
    reduced_.load.add(std::move(f), term.ramp);
    static_response_.add(std::move(z), term.ramp);
  }
  timings_.assembly_s = clock.seconds();
}

Vector StaticCondensation::recover_static(const Vector& y, double t) const {
  Vector u_s = static_response_.at(t);
  if (u_s.size() == 0) return u_s;
  Vector u_i(static_cast<Index>(partition_.interface.size()));
  for (std::size_t a = 0; a < partition_.interface.size(); ++a) u_i[static_cast<Index>(a)] = y[partition_.interface[a]];
  u_s -= K_ss_factor_->solve_leading(K_sI_ * u_i);  // X u_I
  if (num_modes() > 0) u_s.noalias() += Phi_ * y.tail(num_modes());
  return u_s;
}

Vector StaticCondensation::expand(const Vector& y, double t) const {
  const Vector u_s = recover_static(y, t);
  Vector u(static_cast<Index>(partition_.d.size() + partition_.s.size()));
  for (std::size_t k = 0; k < partition_.d.size(); ++k) u[partition_.d[k]] = y[static_cast<Index>(k)];
  for (std::size_t k = 0; k < partition_.s.size(); ++k) u[partition_.s[k]] = u_s[static_cast<Index>(k)];
  return u;
}

}  // namespace roifem::condensation
