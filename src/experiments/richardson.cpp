// SPDX-License-Identifier: GPL-3.0-or-later
#include "experiments/richardson.hpp"

#include <cmath>

#include "common/errors.hpp"

namespace roifem::experiments {

std::optional<double> observed_order(double h1, double h2, double h3, double q1, double q2, double q3) {
  const double d12 = q1 - q2, d23 = q2 - q3;
  if (d12 == 0 || d23 == 0 || (d12 > 0) != (d23 > 0)) return std::nullopt;
  const double ratio = d12 / d23;
  auto rhs = [&](double p) { return (std::pow(h1, p) - std::pow(h2, p)) / (std::pow(h2, p) - std::pow(h3, p)); };
  double lo = 0.05, hi = 8.0;
  if (ratio < rhs(lo) || ratio > rhs(hi)) return std::nullopt;
  for (int k = 0; k < 200 && hi - lo > 1e-12; ++k) {
    const double mid = (lo + hi) / 2;
    (rhs(mid) < ratio ? lo : hi) = mid;
  }
  return (lo + hi) / 2;
}

double extrapolate(double h2, double h3, double q2, double q3, double order) {
  return q3 + (q3 - q2) / (std::pow(h2 / h3, order) - 1);
}

Extrapolation richardson(std::span<const double> h, std::span<const double> q, double formal_order, double min_order,
                         double max_order) {
  const std::size_t n = h.size();
  if (n < 2 || q.size() != n) throw InputError("Richardson extrapolation needs at least two meshes, with one value each");
  for (std::size_t i = 1; i < n; ++i)
    if (!(h[i] < h[i - 1])) throw InputError("Richardson extrapolation needs meshes ordered coarse to fine (h descending)");
  Extrapolation e{.value = 0, .order = formal_order, .observed = false};
  if (n >= 3)
    if (const auto p = observed_order(h[n - 3], h[n - 2], h[n - 1], q[n - 3], q[n - 2], q[n - 1]);
        p && *p >= min_order && *p <= max_order) {
      e.order = *p;
      e.observed = true;
    }
  e.value = extrapolate(h[n - 2], h[n - 1], q[n - 2], q[n - 1], e.order);
  return e;
}

}  // namespace roifem::experiments
