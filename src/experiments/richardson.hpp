// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Richardson extrapolation on meshes whose sizes are not in a fixed ratio (generated meshes land
/// near, not at, the node counts asked for). For a quantity q(h) = q0 + c h^p + ..., three meshes
/// h1 > h2 > h3 give the observed order p from
///   (q1 - q2) / (q2 - q3) = (h1^p - h2^p) / (h2^p - h3^p),
/// solved by bisection (the right side grows monotonically in p), and the extrapolated value
///   q0 = q3 + (q3 - q2) / ((h2 / h3)^p - 1).
/// When the differences change sign (not yet in the asymptotic range) or p falls outside the
/// plausible range, the extrapolation uses the method's formal order instead and says so.
#include <optional>
#include <span>

namespace roifem::experiments {

/// The observed order of three values on meshes h1 > h2 > h3, or none when the differences change
/// sign, vanish, or give an order outside [0.05, 8].
std::optional<double> observed_order(double h1, double h2, double h3, double q1, double q2, double q3);

struct Extrapolation {
  double value = 0;       ///< q0
  double order = 0;       ///< the p used
  bool observed = false;  ///< p was observed (else the formal order was used)
};

/// From meshes ordered coarse to fine (h descending, at least two): the three finest give the
/// observed order when it lies within [min_order, max_order], else formal_order is used; the two
/// finest then extrapolate. Throws InputError for fewer than two meshes or h not descending.
Extrapolation richardson(std::span<const double> h, std::span<const double> q, double formal_order, double min_order = 0.3,
                         double max_order = 4.0);
/// The two finest meshes extrapolated with a given order.
double extrapolate(double h2, double h3, double q2, double q3, double order);

}  // namespace roifem::experiments
