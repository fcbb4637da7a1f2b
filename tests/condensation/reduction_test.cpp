// SPDX-License-Identifier: GPL-3.0-or-later
// Guyan, Craig-Bampton and POD reductions against their definitions: K_r = T^T K T, M_r = T^T M T,
// C_r = T^T C T with T read back column by column from expand(); with every fixed-interface mode
// Craig-Bampton is a change of basis and reproduces the full model.
#include <gtest/gtest.h>

#include <cmath>

#include "common/errors.hpp"
#include "condensation/reduced_model.hpp"
#include "integrators/trapezoid.hpp"
#include "mesh/box_mesh.hpp"
#include "model/fem_model.hpp"
#include "model/spectrum.hpp"
#include "test_models.hpp"

namespace roifem::condensation {
namespace {

using test::Beam;

/// T: the full free displacement of each reduced unit vector (at t = 0 the ramped loads are zero).
DenseMatrix transformation(ReducedModel& r) {
  const Index n_r = r.system().size();
  DenseMatrix T(r.partition().d.size() + r.partition().s.size(), n_r);
  for (Index j = 0; j < n_r; ++j) T.col(j) = r.expand(Vector::Unit(n_r, j), 0.0);
  return T;
}

double relative(const DenseMatrix& a, const DenseMatrix& b) { return (a - b).norm() / b.norm(); }

void expect_projection(ReducedModel& r, const model::SecondOrderSystem& full, bool mass_projected) {
  const DenseMatrix T = transformation(r);
  const double dK = relative(DenseMatrix(r.system().K), T.transpose() * DenseMatrix(full.K) * T);
  const double dM = relative(DenseMatrix(r.system().M), T.transpose() * DenseMatrix(full.M) * T);
  const double dC = relative(DenseMatrix(r.system().C), T.transpose() * DenseMatrix(full.C) * T);
  std::printf("%-18s %3lld dofs: |K_r - T'KT| %.1e, |M_r - T'MT| %.1e, |C_r - T'CT| %.1e (relative)\n",
              r.reduction().label().c_str(), static_cast<long long>(r.system().size()), dK, dM, dC);
  EXPECT_LT(dK, 1e-10);
  // The split forms (products) equal the assembled ones (factorizations).
  const Vector x = Vector::LinSpaced(r.system().size(), -1.0, 2.0);
  Vector Kx(x.size()), Mx(x.size());
  r.system().apply_stiffness(x, Kx);
  r.system().apply_mass(x, Mx);
  EXPECT_LT((Kx - r.system().K * x).norm() / Kx.norm(), 1e-13);
  EXPECT_LT((Mx - r.system().M * x).norm() / Mx.norm(), 1e-13);
  if (mass_projected) {
    EXPECT_LT(dM, 1e-10);
    EXPECT_LT(dC, 1e-10);
  } else {
    EXPECT_GT(dM, 1e-3);  // static condensation keeps M_dd: the static part has no inertia
  }
}

TEST(Reduction, EachReducedMatrixIsTheProjectionThroughItsTransformation) {
  const Beam beam;
  const auto p = beam.partition();
  ASSERT_GT(p.s.size(), 20u);
  const auto& full = beam.model.system;
  ReducedModel plain(full, p, *beam.model.dofs), guyan(full, p, *beam.model.dofs, parse_reduction("guyan"));
  expect_projection(plain, full, false);
  expect_projection(guyan, full, true);
  ReducedModel cb(full, p, *beam.model.dofs, parse_reduction("craig-bampton-5"));
  EXPECT_EQ(cb.num_modes(), 5);
  EXPECT_EQ(cb.system().size(), static_cast<Index>(p.d.size()) + 5);
  expect_projection(cb, full, true);
  ReducedModel pod(full, p, *beam.model.dofs, {.kind = &reduction_named("pod"), .modes = 5, .snapshot_dt_s = 0.01});
  EXPECT_EQ(pod.num_modes(), 5);
  expect_projection(pod, full, true);
}

TEST(Reduction, PodReproducesTheRunItLearntFromAndBeatsCraigBamptonOnAnotherLoadHistory) {
  // Trained on the full model's response to the load switched on just after t = 0 (30 steps of
  // 0.01 s), with a vector per snapshot the basis spans that run: the reduced model must replay
  // it exactly, since the full trajectory lies in the reduced space (Galerkin is then exact).
  Beam beam;
  beam.model.system.load = beam.model.system.load.with_ramp(model::Ramp{0.01});  // on at t_1, as in training
  const auto p = beam.partition();
  const auto& full = beam.model.system;
  const double dt = 0.01;
  auto error_against_full = [&](ReducedModel& r, const model::SecondOrderSystem& full_system, long steps) {
    model::State a = model::State::at_rest(full_system.size());
    model::State b = model::State::at_rest(r.system().size());
    integrators::Trapezoid ta(dt), tb(dt);
    ta.reset(full_system, a);
    tb.reset(r.system(), b);
    double worst = 0, peak = 0;
    for (long k = 0; k < steps; ++k) {
      ta.step(a);
      tb.step(b);
      peak = std::max(peak, a.u.norm());
      worst = std::max(worst, (r.expand(b.u, b.t) - a.u).norm());
    }
    return worst / peak;
  };
  const Reduction every{.kind = &reduction_named("pod"), .modes = 30, .snapshot_dt_s = dt, .snapshot_steps = 30};
  ReducedModel replay(full, p, *beam.model.dofs, every);
  ASSERT_GT(replay.num_modes(), 5);
  const double replayed = error_against_full(replay, full, 30);
  std::printf("POD with %lld vectors, the training run replayed: %.2e (relative)\n", static_cast<long long>(replay.num_modes()),
              replayed);
  EXPECT_LT(replayed, 1e-9);

  // The same 4 vectors learnt from the step, run under a 0.1 s ramp: closer to the full model than
  // 4 Craig-Bampton modes (the load history was never seen).
  model::SecondOrderSystem ramped = full;
  ramped.load = full.load.with_ramp(model::Ramp{0.1});
  ReducedModel pod(ramped, p, *beam.model.dofs,
                   {.kind = &reduction_named("pod"), .modes = 4, .snapshot_dt_s = dt, .snapshot_steps = 30});
  ReducedModel cb(ramped, p, *beam.model.dofs, parse_reduction("craig-bampton-4"));
  ReducedModel plain(ramped, p, *beam.model.dofs);
  const double e_pod = error_against_full(pod, ramped, 60), e_cb = error_against_full(cb, ramped, 60),
               e_plain = error_against_full(plain, ramped, 60);
  std::printf("0.1 s ramp, 60 steps, max |u_r - u| / max |u|: static %.2e, craig-bampton-4 %.2e, pod-4 %.2e\n", e_plain, e_cb,
              e_pod);
  EXPECT_LT(e_pod, e_cb);
  EXPECT_LT(e_pod, e_plain);
}

TEST(Reduction, PodNeedsVectorsAndALoad) {
  const Beam beam;
  const auto p = beam.partition();
  EXPECT_THROW(ReducedModel(beam.model.system, p, *beam.model.dofs, Reduction{.kind = &reduction_named("pod"), .modes = 0}),
               InputError);
  model::SecondOrderSystem unloaded = beam.model.system;
  unloaded.load = model::LoadHistory(unloaded.size());
  EXPECT_THROW(ReducedModel(unloaded, p, *beam.model.dofs, parse_reduction("pod-3")), InputError);
  EXPECT_EQ(parse_reduction("pod-40").modes, 40);
  EXPECT_EQ(parse_reduction("pod-40").label(), "pod-40");
  EXPECT_THROW(parse_reduction("pod-"), InputError);
}

TEST(Reduction, CraigBamptonWithEveryModeReproducesTheFullModel) {
  const Beam beam;
  const auto p = beam.partition();
  const auto& full = beam.model.system;
  const Index all = static_cast<Index>(p.s.size());
  ReducedModel cb(full, p, *beam.model.dofs, {.kind = &reduction_named("craig-bampton"), .modes = all});
  ASSERT_EQ(cb.num_modes(), all);
  model::State a = model::State::at_rest(full.size());
  model::State b = model::State::at_rest(cb.system().size());
  integrators::Trapezoid ta(0.01), tb(0.01);
  ta.reset(full, a);
  tb.reset(cb.system(), b);
  double worst = 0;
  for (int k = 0; k < 100; ++k) {
    ta.step(a);
    tb.step(b);
    worst = std::max(worst, (cb.expand(b.u, b.t) - a.u).norm() / a.u.norm());
  }
  std::printf("Craig-Bampton with all %lld modes vs the full model, 100 steps: %.2e (relative)\n", static_cast<long long>(all),
              worst);
  EXPECT_LT(worst, 1e-9);
}

TEST(Reduction, CutOffKeepsExactlyTheModesBelowIt) {
  const Beam beam;
  const auto p = beam.partition();
  ReducedModel ten(beam.model.system, p, *beam.model.dofs, parse_reduction("craig-bampton-10"));
  const double cutoff = 0.5 * (ten.mode_frequencies()[5] + ten.mode_frequencies()[6]);
  ReducedModel cut(beam.model.system, p, *beam.model.dofs, {.kind = &reduction_named("craig-bampton"), .cutoff_rad_s = cutoff});
  EXPECT_EQ(cut.num_modes(), 6);
  EXPECT_LT((cut.mode_frequencies() - ten.mode_frequencies().head(6)).norm() / ten.mode_frequencies().head(6).norm(), 1e-9);
}

TEST(Reduction, LanczosModesEqualDenseOnes) {
  const Beam beam;
  const auto p = beam.partition();
  const SparseMatrix K_ss = roi::submatrix(beam.model.system.K, p.s, p.s);
  const Vector M_ss = roi::gather(beam.model.system.M.diagonal(), p.s);
  solvers::Cholesky factor;
  factor.compute(K_ss);
  const auto lanczos = model::lowest_modes(M_ss, factor, 8);
  const auto dense = model::lowest_modes(M_ss, factor, static_cast<Index>(p.s.size()));
  std::printf("lowest fixed-interface mode %.6f rad/s (Lanczos) vs %.6f (dense)\n", lanczos.omega[0], dense.omega[0]);
  EXPECT_LT((lanczos.omega - dense.omega.head(8)).norm() / dense.omega.head(8).norm(), 1e-9);
  // M-orthonormal, K-orthogonal: Phi^T K Phi = W^2.
  const DenseMatrix PtKP = lanczos.shapes.transpose() * K_ss * lanczos.shapes;
  EXPECT_LT((PtKP - DenseMatrix(lanczos.omega.cwiseAbs2().asDiagonal())).norm() / PtKP.norm(), 1e-9);
}

TEST(Reduction, EveryRowOfTheTableBuildsAProjectionWithTheBasisItNames) {
  // A kind is its table row: each row's maker (or none) must give a model that is a projection of
  // the full one, with as many extra coordinates as the row's count asks and none without a maker.
  const Beam beam;
  const auto p = beam.partition();
  for (const ReductionInfo& row : reduction_table()) {
    Reduction reduction{.kind = &row, .modes = row.counted ? 3 : 0};
    reduction = reduction.trained_on(0.01, 40);
    ReducedModel model(beam.model.system, p, *beam.model.dofs, reduction);
    EXPECT_EQ(model.num_modes(), row.make_basis != nullptr ? 3 : 0) << row.key;
    EXPECT_EQ(&parse_reduction(reduction.label()).info(), &row) << reduction.label();
    expect_projection(model, beam.model.system, row.carries_mass);
  }
  EXPECT_TRUE(Reduction{}.is_static_condensation());
  EXPECT_THROW(reduction_named("no-such-reduction"), Error);
}

TEST(Reduction, CraigBamptonWithoutModesOrCutOffIsAnInputError) {
  const Beam beam;
  try {
    ReducedModel(beam.model.system, beam.partition(), *beam.model.dofs, {.kind = &reduction_named("craig-bampton")});
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("craig-bampton reduction: give a positive number of modes"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace roifem::condensation

// Guyan, Craig-Bampton and POD hand the integrators a full M: every integrator the factory names
// integrates each of them (ERK and GSL through a Cholesky solve with M, ARKODE's implicit methods
// with KLU on the sparse M^-1 K of the block-diagonal M, the Schur solver or M as the mass matrix,
// IDA in residual form, the trapezoidal rules with M in K_eff) and meets its tolerance against the
// exact modal solution of the same reduced system.
#include "integrators/factory.hpp"
#include "model/energy.hpp"
#include "model/mass_inverse.hpp"
#include "model/modal_reference.hpp"

namespace roifem::condensation {
namespace {

void expect_every_named_integrator_meets_the_modal_solution(const Reduction& reduction) {
  const Beam beam;
  ReducedModel r(beam.model.system, beam.partition(), *beam.model.dofs, reduction);
  const auto& sys = r.system();
  ASSERT_FALSE(model::is_diagonal(sys.M)) << reduction.label();
  const model::State rest = model::State::at_rest(sys.size());
  const Vector exact = model::ModalReference(sys, rest).displacement(0.4);
  for (const integrators::IntegratorInfo& info : integrators::integrator_table()) {
    if (info.needs_tools || info.needs_uncondensed) continue;  // DAE forms of other models: tested on their own
    const std::string& name = info.name;
    // The trapezoidal rules (hand-written and ARKODE's table) have a fixed step only (second
    // order: 1e-4 s for ~1e-6); every other method runs error-controlled at a tolerance that
    // tightens with its order (10^-(p+3), at most 1e-8), so that a low-order method's step stays
    // affordable, and must land within 100 times it.
    const bool fixed = !info.adaptive;
    const double rtol = std::max(1e-8, std::pow(10.0, -(info.order + 3)));
    const integrators::StepControl control =
        fixed ? integrators::StepControl{.dt = 1e-4}
              : integrators::StepControl{.dt = 1e-3, .adaptive = true, .rtol = rtol, .atol = 1e-6 * rtol};
    auto integrator = integrators::make_integrator(name, control);
    model::State s = rest;
    integrator->reset(sys, s);
    integrator->advance_to(0.4, s);
    const double err = (s.u - exact).norm() / exact.norm();
    std::printf("%-16s beam, %-27s: relative error %.2e\n", reduction.label().c_str(), name.c_str(), err);
    EXPECT_LT(err, fixed ? 1e-4 : 100 * rtol) << reduction.label() << ", " << name;
  }
}

TEST(Reduction, EveryNamedIntegratorIntegratesGuyanAgainstTheModalSolution) {
  expect_every_named_integrator_meets_the_modal_solution(parse_reduction("guyan"));
}

TEST(Reduction, EveryNamedIntegratorIntegratesCraigBamptonAgainstTheModalSolution) {
  expect_every_named_integrator_meets_the_modal_solution(parse_reduction("craig-bampton-5"));
}

TEST(Reduction, EveryNamedIntegratorIntegratesPodAgainstTheModalSolution) {
  expect_every_named_integrator_meets_the_modal_solution(parse_reduction("pod-4").trained_on(0.01, 60));
}

TEST(Reduction, TheTrapezoidalRuleEliminatesModalCoordinatesAndStepsAsTheWholeSolveDoes) {
  // Craig-Bampton and POD systems declare their modal coordinates; the trapezoidal rule eliminates
  // them in closed form (the factor is plain condensation's size) and must step exactly as it does
  // when it factors K_eff whole (the same system with the declaration removed, or with a general
  // damping declared: the elimination folds C = alpha M into M).
  const Beam beam;
  for (const Reduction& reduction : {parse_reduction("craig-bampton-5"), parse_reduction("pod-4").trained_on(0.01, 60)}) {
    ReducedModel r(beam.model.system, beam.partition(), *beam.model.dofs, reduction);
    const auto& eliminated = r.system();
    ASSERT_TRUE(eliminated.modal.has_value()) << reduction.label();
    ASSERT_EQ(eliminated.modal->count, r.num_modes()) << reduction.label();
    model::SecondOrderSystem whole = eliminated;
    whole.modal.reset();
    model::SecondOrderSystem perturbed = eliminated;  // a general C: factored whole, C's own product
    perturbed.damping = {};
    integrators::Trapezoid a(0.01), b(0.01), c(0.01);
    model::State sa = model::State::at_rest(eliminated.size()), sb = sa, sc = sa;
    a.reset(eliminated, sa);
    b.reset(whole, sb);
    c.reset(perturbed, sc);
    EXPECT_TRUE(a.eliminates_modal_coordinates()) << reduction.label();
    EXPECT_FALSE(b.eliminates_modal_coordinates()) << reduction.label();
    EXPECT_FALSE(c.eliminates_modal_coordinates()) << reduction.label();
    double worst_u = 0, worst_v = 0, worst_perturbed = 0, peak_u = 0, peak_v = 0, modal_share = 0;
    for (int k = 0; k < 100; ++k) {
      a.step(sa);
      b.step(sb);
      c.step(sc);
      peak_u = std::max(peak_u, sb.u.norm());
      peak_v = std::max(peak_v, sb.v.norm());
      worst_u = std::max(worst_u, (sa.u - sb.u).norm());
      worst_v = std::max(worst_v, (sa.v - sb.v).norm());
      worst_perturbed = std::max(worst_perturbed, (sc.u - sb.u).norm());
      Vector without_modes = sb.u;  // the modes' share of the full displacement field
      without_modes.tail(r.num_modes()).setZero();
      const Vector u = r.expand(sb.u, sb.t);
      modal_share = std::max(modal_share, (u - r.expand(without_modes, sb.t)).norm() / u.norm());
    }
    std::printf("%s beam, 100 steps: eliminated vs whole |du| / |u| <= %.1e, |dv| / |v| <= %.1e (modes' share of u up to %.2f)\n",
                reduction.label().c_str(), worst_u / peak_u, worst_v / peak_v, modal_share);
    EXPECT_GT(modal_share, 0.02) << reduction.label() << ": the modes must take part";
    EXPECT_LT(worst_u / peak_u, 1e-12) << reduction.label();
    EXPECT_LT(worst_v / peak_v, 1e-12) << reduction.label();
    EXPECT_LT(worst_perturbed / peak_u, 1e-12) << reduction.label();
  }
}

TEST(Reduction, TheEnergyLedgerOfAReducedModelReadsItsSplitMatricesRight) {
  // The ledger takes its products through the split M and K (dense blocks read as blocks); the
  // assembled matrices give the same energies, and the trapezoidal rule's discrete balance
  // E_n + D_n - W_n = E_0 holds with the Craig-Bampton model's full, damped mass.
  const Beam beam;
  ReducedModel cb(beam.model.system, beam.partition(), *beam.model.dofs, parse_reduction("craig-bampton-5"));
  const auto& sys = cb.system();
  ASSERT_FALSE(sys.M_split.empty());
  model::State s = model::State::at_rest(sys.size());
  integrators::Trapezoid trapezoid(0.01);
  trapezoid.reset(sys, s);
  model::EnergyLedger ledger(sys, s);
  double worst_balance = 0, worst_kinetic = 0, worst_strain = 0;
  for (int k = 0; k < 100; ++k) {
    trapezoid.step(s);
    ledger.record(s);
    worst_balance = std::max(worst_balance, std::abs(ledger.balance_residual()) / ledger.external_work());
    const double kinetic = 0.5 * s.v.dot(sys.M * s.v), strain = 0.5 * s.u.dot(sys.K * s.u);
    worst_kinetic = std::max(worst_kinetic, std::abs(ledger.kinetic() - kinetic) / kinetic);
    worst_strain = std::max(worst_strain, std::abs(ledger.strain() - strain) / strain);
  }
  std::printf("Craig-Bampton-5 beam, 100 steps: |E + D - W - E0| / W <= %.1e, kinetic %.1e, strain %.1e (vs assembled)\n",
              worst_balance, worst_kinetic, worst_strain);
  EXPECT_GT(ledger.dissipated(), 1e-3 * ledger.external_work());
  EXPECT_LT(worst_balance, 1e-10);
  EXPECT_LT(worst_kinetic, 1e-12);
  EXPECT_LT(worst_strain, 1e-12);
}

}  // namespace
}  // namespace roifem::condensation
