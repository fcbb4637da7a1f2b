// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Linear stability of explicit Runge-Kutta methods on M u'' + C u' + K u = 0 with C = alpha M.
/// Every mode w_i gives the eigenvalues lambda = -alpha/2 +- sqrt(alpha^2/4 - w_i^2) of the
/// first-order system; a step h is stable when |R(h lambda)| <= 1 for all of them, with the
/// method's stability function R(z) = 1 + z b^T (I - z A)^-1 1 computed from its Butcher table
/// (IntegratorInfo::tableau).
#include "common/types.hpp"
#include "integrators/integrator_table.hpp"

namespace roifem::integrators {

/// The largest stable step of an explicit method with a tableau for the given modal frequencies
/// (rad/s) and damping alpha (1/s). Infinity for every other method (the implicit ones are
/// A-stable; GSL's multistep and rk8pd have no tableau here).
double predicted_stability_limit(const IntegratorInfo& method, const Vector& frequencies, double alpha);

}  // namespace roifem::integrators
