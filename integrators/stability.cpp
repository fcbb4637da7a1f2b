// SPDX-License-Identifier: GPL-3.0-or-later
#include "integrators/stability.hpp"

#include <complex>
#include <limits>

namespace roifem::integrators {

namespace {

using complex = std::complex<double>;

/// R(z) = 1 + z b^T (I - z A)^-1 1, for explicit A by forward substitution.
complex stability_function(const ButcherTableau& t, complex z) {
  const Index s = t.b.size();
  std::vector<complex> k(static_cast<std::size_t>(s));
  complex sum = 0;
  for (Index i = 0; i < s; ++i) {
    complex stage = 1.0;
    for (Index j = 0; j < i; ++j) stage += z * t.A(i, j) * k[static_cast<std::size_t>(j)];
    k[static_cast<std::size_t>(i)] = stage;
    sum += t.b[i] * stage;
  }
  return 1.0 + z * sum;
}

bool stable(const ButcherTableau& t, const Vector& frequencies, double alpha, double h) {
  for (Index i = 0; i < frequencies.size(); ++i) {
    const complex root = std::sqrt(complex(alpha * alpha / 4 - frequencies[i] * frequencies[i], 0.0));
    for (const complex lambda : {-alpha / 2 + root, -alpha / 2 - root})
      if (std::abs(stability_function(t, h * lambda)) > 1.0 + 1e-12) return false;
  }
  return true;
}

}  // namespace

double predicted_stability_limit(const IntegratorInfo& method, const Vector& frequencies, double alpha) {
  if (!method.is_explicit || !method.tableau) return std::numeric_limits<double>::infinity();
  const ButcherTableau t = method.tableau();
  // Bisection on h in [0, 8 / w_max]: stable near 0 when the damping is positive.
  double lo = 0, hi = 8.0 / frequencies.maxCoeff();
  for (int k = 0; k < 200 && hi - lo > 1e-12 * hi; ++k) {
    const double mid = 0.5 * (lo + hi);
    (stable(t, frequencies, alpha, mid) ? lo : hi) = mid;
  }
  return lo;
}

}  // namespace roifem::integrators
