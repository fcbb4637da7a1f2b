// SPDX-License-Identifier: GPL-3.0-or-later
#include "condensation/pod_basis.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <string>

#include "common/errors.hpp"
#include "condensation/static_basis.hpp"
#include "model/average_acceleration.hpp"
#include "solvers/cholesky.hpp"

namespace roifem::condensation {

namespace {

/// Snapshots w = u_s + X u_I of the full model's response to a unit step of each load pattern, by
/// the trapezoidal rule (model::AverageAcceleration, the recurrence integrators::Trapezoid steps).
DenseMatrix fixed_interface_snapshots(const PodTraining& in) {
  const auto& d = in.partition.d;
  const auto& s = in.partition.s;
  const auto& full = in.full;
  const Index n = full.size();
  const model::AverageAcceleration rule(in.dt);
  solvers::Cholesky K_eff;
  K_eff.compute(rule.effective_stiffness(full));
  // One training input per time history: terms that share a ramp always act together (the two
  // walls of the opening), so their patterns are summed rather than learnt apart.
  std::vector<std::pair<double, Vector>> inputs;  // (ramp duration, summed pattern)
  for (const auto& term : full.load.terms()) {
    auto same = std::find_if(inputs.begin(), inputs.end(), [&](const auto& i) { return i.first == term.ramp.duration; });
    if (same == inputs.end())
      inputs.emplace_back(term.ramp.duration, term.pattern);
    else
      same->second += term.pattern;
  }
  DenseMatrix snapshots(static_cast<Index>(s.size()), in.steps * static_cast<Index>(inputs.size()));
  Vector u_I(static_cast<Index>(in.partition.interface.size()));
  Index column = 0;
  for (const auto& input : inputs) {
    const Vector& pattern = input.second;
    model::State state = model::State::at_rest(n);
    Vector a = Vector::Zero(n), f(n), w(n), rhs(n), u_next(n), work(n);
    for (long k = 0; k < in.steps; ++k) {  // the load is switched on just after t = 0
      f = pattern;
      rule.history(full, state, a, f, w);
      rhs = f + full.M * w;
      K_eff.solve(rhs, u_next);
      rule.advance(state, a, u_next, work);
      const Vector& u = state.u;
      for (std::size_t i = 0; i < in.partition.interface.size(); ++i)
        u_I[static_cast<Index>(i)] = u[d[static_cast<std::size_t>(in.partition.interface[i])]];
      snapshots.col(column++) = roi::gather(u, s) + in.X * u_I;
    }
  }
  return snapshots;
}

}  // namespace

model::Modes pod_basis(const PodTraining& in, Index count) {
  if (!(in.dt > 0) || in.steps < 1) throw InputError("POD reduction: the training needs dt > 0 and at least one step");
  if (in.full.load.terms().empty()) throw InputError("POD reduction: the model has no load to train on");
  const DenseMatrix S = fixed_interface_snapshots(in);
  const Vector M_s = roi::gather(in.full.M.diagonal(), in.partition.s);

  // POD in the M_ss inner product: the left singular vectors of M_ss^1/2 S, by a thin QR of it and
  // an SVD of R (accurate down to round-off, where the Gram matrix's eigenvectors would square the
  // conditioning), mapped back by M_ss^-1/2: M_ss-orthonormal.
  const Vector root_mass = M_s.cwiseSqrt();
  const DenseMatrix A = root_mass.asDiagonal() * S;
  const Eigen::HouseholderQR<DenseMatrix> qr(A);
  const Index m = std::min(A.rows(), A.cols());
  const DenseMatrix R = qr.matrixQR().topRows(m).triangularView<Eigen::Upper>();
  const Eigen::JacobiSVD<DenseMatrix> svd(R, Eigen::ComputeThinU);
  const Vector& sigma = svd.singularValues();  // descending
  if (!(sigma[0] > 0)) throw ModelError("POD reduction: the loads do not move the static part against the interface");
  Index kept = 0;
  while (kept < std::min(count, m) && sigma[kept] > 1e-10 * sigma[0]) ++kept;
  const DenseMatrix Q = qr.householderQ() * DenseMatrix::Identity(A.rows(), m);
  const DenseMatrix W = root_mass.cwiseInverse().asDiagonal() * (Q * svd.matrixU().leftCols(kept));

  // Rayleigh-Ritz on (K_ss, M_ss) within span W.
  const SparseMatrix K_ss = roi::submatrix(in.full.K, in.partition.s, in.partition.s);
  DenseMatrix projected = W.transpose() * (K_ss * W);
  projected = (0.5 * (projected + projected.transpose())).eval();
  const Eigen::SelfAdjointEigenSolver<DenseMatrix> ritz(projected);
  if (ritz.info() != Eigen::Success || !(ritz.eigenvalues().minCoeff() > 0))
    throw SolverError("POD reduction: the projected K_ss is not positive definite");
  return {.omega = ritz.eigenvalues().cwiseSqrt(), .shapes = W * ritz.eigenvectors()};
}

model::Modes pod_modes(const BasisRequest& request) {
  const Reduction& r = request.reduction;
  return pod_basis({request.full, request.partition, request.X, r.snapshot_dt_s, r.snapshot_steps},
                   std::min(r.modes, request.static_dofs()));
}

}  // namespace roifem::condensation
