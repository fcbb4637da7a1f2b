#include "integrators/stability.hpp"

#include <arkode/arkode_butcher.h>
#include <arkode/arkode_butcher_erk.h>

#include <complex>
#include <limits>
#include <map>

#include "common/errors.hpp"

namespace roifem::integrators {

namespace {

using complex = std::complex<double>;

struct Table {
  Eigen::MatrixXd A;
  Eigen::VectorXd b;
};

Table explicit_table(const std::string& method) {
  static const std::map<std::string, int> erk = {{"arkode-erk2", ARKODE_HEUN_EULER_2_1_2},
                                                 {"arkode-erk3", ARKODE_BOGACKI_SHAMPINE_4_2_3},
                                                 {"arkode-erk4", ARKODE_ZONNEVELD_5_3_4},
                                                 {"arkode-erk5", ARKODE_DORMAND_PRINCE_7_4_5}};
  Table t;
  if (auto it = erk.find(method); it != erk.end()) {
    ARKodeButcherTable B = ARKodeButcherTable_LoadERK(static_cast<ARKODE_ERKTableID>(it->second));
    t.A.resize(B->stages, B->stages);
    t.b.resize(B->stages);
    for (int i = 0; i < B->stages; ++i) {
      t.b[i] = B->b[i];
      for (int j = 0; j < B->stages; ++j) t.A(i, j) = B->A[i][j];
    }
    ARKodeButcherTable_Free(B);
  } else if (method == "gsl-rk4") {  // the classical fourth-order Runge-Kutta method
    t.A = Eigen::MatrixXd::Zero(4, 4);
    t.A(1, 0) = 0.5;
    t.A(2, 1) = 0.5;
    t.A(3, 2) = 1.0;
    t.b = Eigen::Vector4d(1.0 / 6, 1.0 / 3, 1.0 / 3, 1.0 / 6);
  }
  return t;
}

/// R(z) = 1 + z b^T (I - z A)^-1 1, for explicit A by forward substitution.
complex stability_function(const Table& t, complex z) {
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

bool stable(const Table& t, const Vector& frequencies, double alpha, double h) {
  for (Index i = 0; i < frequencies.size(); ++i) {
    const complex root = std::sqrt(complex(alpha * alpha / 4 - frequencies[i] * frequencies[i], 0.0));
    for (const complex lambda : {-alpha / 2 + root, -alpha / 2 - root})
      if (std::abs(stability_function(t, h * lambda)) > 1.0 + 1e-12) return false;
  }
  return true;
}

}  // namespace

double predicted_stability_limit(const std::string& method, const Vector& frequencies, double alpha) {
  const Table t = explicit_table(method);
  if (t.b.size() == 0) return std::numeric_limits<double>::infinity();
  // Bisection on h in [0, 8 / w_max]: stable near 0 when the damping is positive.
  double lo = 0, hi = 8.0 / frequencies.maxCoeff();
  for (int k = 0; k < 200 && hi - lo > 1e-12 * hi; ++k) {
    const double mid = 0.5 * (lo + hi);
    (stable(t, frequencies, alpha, mid) ? lo : hi) = mid;
  }
  return lo;
}

}  // namespace roifem::integrators
