// SPDX-License-Identifier: GPL-3.0-or-later
#include "experiments/homogeneous_response.hpp"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_roots.h>

#include <cfloat>
#include <cmath>
#include <memory>
#include <string>

#include "common/errors.hpp"
#include "common/number_text.hpp"

namespace roifem::experiments {

namespace {

Mat3 stress_at(const fem::HyperelasticLaw& law, const Mat3& H) {
  return std::visit([&](const auto& l) -> Mat3 { return l.stress(H); }, law);
}

Mat3 uniaxial_gradient(double lambda, double t) {
  Mat3 H = Mat3::Zero();
  H(0, 0) = lambda - 1;
  H(1, 1) = H(2, 2) = t - 1;
  return H;
}

struct Lateral {
  const fem::HyperelasticLaw* law;
  double lambda;
};

double lateral_stress(double t, void* data) {
  const auto* p = static_cast<const Lateral*>(data);
  return stress_at(*p->law, uniaxial_gradient(p->lambda, t))(1, 1);
}

struct RootSolverFree {
  void operator()(gsl_root_fsolver* s) const { gsl_root_fsolver_free(s); }
};

}  // namespace

double uniaxial_lateral_stretch(const fem::HyperelasticLaw& law, double lambda) {
  if (!(lambda > 0) || !std::isfinite(lambda))
    throw InputError("uniaxial stretch " + number_text(lambda) + ": a stretch must be positive and finite");
  gsl_set_error_handler_off();  // GSL's default handler aborts the process; roifem reports errors itself
  Lateral data{&law, lambda};
  gsl_function f{&lateral_stress, &data};
  // P_22 grows with t: negative where the lateral faces are squeezed (t small), positive where
  // they are pulled. Bracket from the incompressible guess t = lambda^(-1/2) outwards.
  const double guess = 1 / std::sqrt(lambda);
  double lo = guess, hi = guess;
  for (int k = 0; k < 60 && lateral_stress(lo, &data) > 0; ++k) lo *= 0.9;
  for (int k = 0; k < 60 && lateral_stress(hi, &data) < 0; ++k) hi = std::min(hi * 1.1, 10 * guess);
  if (lateral_stress(lo, &data) > 0 || lateral_stress(hi, &data) < 0)
    throw SolverError("uniaxial stretch " + number_text(lambda) + ": no lateral stretch in [" + number_text(lo) + ", " +
                      number_text(hi) + "] leaves the lateral faces free");
  if (lo == hi) return lo;
  const std::unique_ptr<gsl_root_fsolver, RootSolverFree> solver(gsl_root_fsolver_alloc(gsl_root_fsolver_brent));
  gsl_root_fsolver_set(solver.get(), &f, lo, hi);
  for (int iteration = 0; iteration < 200; ++iteration) {
    gsl_root_fsolver_iterate(solver.get());
    const double a = gsl_root_fsolver_x_lower(solver.get()), b = gsl_root_fsolver_x_upper(solver.get());
    if (gsl_root_test_interval(a, b, 0, 4 * DBL_EPSILON) == GSL_SUCCESS) return gsl_root_fsolver_root(solver.get());
  }
  return gsl_root_fsolver_root(solver.get());
}

double uniaxial_nominal_stress(const fem::HyperelasticLaw& law, double lambda) {
  return stress_at(law, uniaxial_gradient(lambda, uniaxial_lateral_stretch(law, lambda)))(0, 0);
}

double simple_shear_stress(const fem::HyperelasticLaw& law, double gamma) {
  Mat3 H = Mat3::Zero();
  H(0, 1) = gamma;
  return stress_at(law, H)(0, 1);
}

}  // namespace roifem::experiments
