// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// The neo-Hookean tet4's excess force (fem/hyperelastic_element.hpp's tet4_excess_force: the law's
/// force less the linear element's, P(F) - sigma_lin(H) integrated over the element) on
/// kTet4Lanes elements at once, for a haptic tick's loop over a hybrid ROI's law. The fields are
/// laid out lane by lane (entry [i][l] is element l's), so that every operation is one loop over
/// the lanes that the compiler turns into vector instructions; on x86-64 a second copy is built for
/// AVX2 with FMA and chosen at load time where the processor has them. J^(1/3) comes from Halley's
/// iteration (no call inside the loops); a lane outside the range where four iterations reach
/// rounding takes std::cbrt. The answer agrees with tet4_excess_force to rounding (the tests:
/// fem/hyperelastic_test.cpp), not bit for bit.
#include <array>

namespace roifem::fem {

inline constexpr int kTet4Lanes = 8;

/// kTet4Lanes elements' geometry and law. A lane with no element has zero gradients and volume (its
/// excess is zero, its J one).
struct Tet4ExcessBatch {
  double grad[4][3][kTet4Lanes] = {};  ///< [a][i][l]: d N_a / d x_i of element l
  double volume[kTet4Lanes] = {};      ///< |V|
  double mu[kTet4Lanes] = {}, kappa[kTet4Lanes] = {}, lambda[kTet4Lanes] = {};
};

/// u[k][l]: element l's displacement dof k (node k / 3, component k % 3). Writes excess[k][l] and
/// J[l] = det F; where J[l] <= 0 the element has inverted and its excess is meaningless.
void tet4_excess_force_batch(const Tet4ExcessBatch& batch, const double (&u)[12][kTet4Lanes], double (&excess)[12][kTet4Lanes],
                             double (&J)[kTet4Lanes]);

}  // namespace roifem::fem
