// SPDX-License-Identifier: GPL-3.0-or-later
#include "condensation/reduced_model.hpp"

#include "common/errors.hpp"
#include "common/timer.hpp"
#include "condensation/reduced_operators.hpp"
#include "condensation/static_basis.hpp"
#include "model/internal_force.hpp"
#include "model/mass_inverse.hpp"

namespace roifem::condensation {

ReducedModel::ReducedModel(const model::SecondOrderSystem& full, const roi::Partition& partition, const fem::DofMap& dofs,
                           const Reduction& reduction)
    : partition_(partition), reduction_(reduction) {
  validate(full);
  factor_ = std::make_unique<StaticPartFactor>(full.K, partition_, dofs);
  timings_.factorization_s = factor_->factorization_s();
  Stopwatch clock;
  const DenseMatrix X = reduction_.info().carries_mass ? factor_->static_modes() : DenseMatrix();
  timings_.interface_solve_s = factor_->schur_s() + clock.seconds();
  clock.restart();
  basis_ = static_basis(reduction_, full, partition_, *factor_, X);
  timings_.modes_s = clock.seconds();
  clock.restart();
  assemble(full, X);
  timings_.assembly_s = clock.seconds();
}

void ReducedModel::validate(const model::SecondOrderSystem& full) const {
  if (full.is_nonlinear())
    throw InputError("static condensation and every reduction of the static part take a linear model; this one is " +
                     full.internal_force->describe() + " (give [material] model = \"linear\", or run the full model)");
  if (partition_.d.empty()) throw ModelError("static condensation: the ROI has no free dof");
  const ReductionInfo& info = reduction_.info();
  if (info.counted && reduction_.modes <= 0 && !(info.takes_cutoff && reduction_.cutoff_rad_s > 0))
    throw InputError(std::string(info.key) + " reduction: give a positive number of " +
                     (info.takes_cutoff ? "modes or a positive cut-off frequency" : "vectors"));
  if (info.carries_mass && !(model::is_diagonal(full.M) && model::is_diagonal(full.C)))
    throw InputError(reduction_.label() + " reduction: needs the lumped (diagonal) M and C of the full model");
}

void ReducedModel::assemble(const model::SecondOrderSystem& full, const DenseMatrix& X) {
  const bool carries_mass = reduction_.info().carries_mass;
  const Index k = num_modes();
  reduced_.K_split = reduced_stiffness(full.K, partition_, factor_->interface_schur(), basis_.omega);
  reduced_.K = assembled(reduced_.K_split);
  reduced_.M_split = reduced_diagonal_operator(full.M, partition_, X, basis_, carries_mass);
  // Phi is M_ss-orthonormal, so its block of M is I (as computed, I to ~1e-13): set exactly, as
  // ModalBlock promises.
  if (k > 0) reduced_.M_split.block.bottomRightCorner(k, k).setIdentity();
  reduced_.M = assembled(reduced_.M_split);
  reduced_.C = assembled(reduced_diagonal_operator(full.C, partition_, X, basis_, carries_mass));
  reduced_.damping = full.damping;  // T^T (alpha M) T = alpha M_r
  if (k > 0) reduced_.modal = model::ModalBlock{.count = k, .interface_dofs = static_cast<Index>(partition_.interface.size())};
  if (!carries_mass) reduced_.M_split = {};  // diagonal: the plain product is the fast one
  ReducedLoads loads = reduce_loads(full.load, partition_, *factor_, basis_);
  reduced_.load = std::move(loads.reduced);
  static_response_ = std::move(loads.static_response);
}

Vector ReducedModel::recover_static(const Vector& y, double t) {
  Vector u_s = static_response_.at(t);
  if (u_s.size() == 0) return u_s;
  Vector u_i(static_cast<Index>(partition_.interface.size()));
  for (std::size_t a = 0; a < partition_.interface.size(); ++a) u_i[static_cast<Index>(a)] = y[partition_.interface[a]];
  u_s -= factor_->solve_static(factor_->K_sI() * u_i);  // X u_I
  if (num_modes() > 0) u_s.noalias() += basis_.shapes * y.tail(num_modes());
  return u_s;
}

Vector ReducedModel::expand(const Vector& y, double t) {
  const Vector u_s = recover_static(y, t);
  Vector u(static_cast<Index>(partition_.d.size() + partition_.s.size()));
  for (std::size_t k = 0; k < partition_.d.size(); ++k) u[partition_.d[k]] = y[static_cast<Index>(k)];
  for (std::size_t k = 0; k < partition_.s.size(); ++k) u[partition_.s[k]] = u_s[static_cast<Index>(k)];
  return u;
}

}  // namespace roifem::condensation
