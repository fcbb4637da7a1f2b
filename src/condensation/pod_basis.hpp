// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Generalized coordinates for the static part learnt from the full model's own response: a proper
/// orthogonal decomposition (POD) of its step responses, in fixed-interface form.
///
/// Why: the error of condensation on the paper case lives in many local, weakly driven modes of
/// the static part near the interface; Craig-Bampton needs 150-200 of its lowest fixed-interface
/// modes for a 10x lower error peak, and Krylov (load-dependent Ritz) vectors do no better. The
/// response the load actually excites is far more compact: a few dozen POD vectors of it do what
/// 200 modes do.
///
/// How: the full model (lumped M, C = alpha M allowed) is stepped by the trapezoidal rule from rest
/// under a unit step of each load input in turn (the patterns of the terms that share a time
/// history, summed; `steps` steps of `dt`); every snapshot's static
/// part less its Guyan part, w = u_s + X u_I (zero motion of the interface), is kept. The
/// M_ss-weighted POD of those snapshots (the SVD of M_ss^1/2 S, by a thin QR) gives the `count`
/// dominant vectors (singular values above 1e-10 of the largest), rotated by Rayleigh-Ritz on
/// (K_ss, M_ss) so that
/// Phi^T M_ss Phi = I and Phi^T K_ss Phi = W^2, as Craig-Bampton's modes. The time history of
/// the load is free: the basis is trained on steps and used for any ramp.
///
/// Cost: one factorization of the full model's K_eff and steps x patterns solves with it, once at
/// setup, and a dense #s x (steps x patterns) snapshot matrix.
#include "model/second_order_system.hpp"
#include "model/spectrum.hpp"
#include "roi/roi.hpp"

namespace roifem::condensation {

struct PodTraining {
  const model::SecondOrderSystem& full;  ///< lumped M and C
  const roi::Partition& partition;
  const DenseMatrix& X;  ///< K_ss^-1 K_sI (#s x #I)
  double dt = 0.05;      ///< s
  long steps = 200;
};

/// The `count` dominant POD vectors (fewer when the snapshots span fewer), with W from Rayleigh-Ritz.
/// Throws ModelError when the loads do not move the static part relative to the interface.
model::Modes pod_basis(const PodTraining& training, Index count);

struct BasisRequest;  // static_basis.hpp

/// The POD reduction's basis maker: the reduction's count of vectors, trained on its snapshot run.
model::Modes pod_modes(const BasisRequest& request);

}  // namespace roifem::condensation
