// SPDX-License-Identifier: GPL-3.0-or-later
#include "integrators/sundials/vector_ops.hpp"

#include <nvector/nvector_serial.h>

#include <cmath>

#include "common/types.hpp"

namespace roifem::integrators::sundials {

namespace {

using Map = Eigen::Map<roifem::Vector>;

Map map(N_Vector v) { return {NV_DATA_S(v), static_cast<Index>(NV_LENGTH_S(v))}; }

void linear_sum(double a, N_Vector x, double b, N_Vector y, N_Vector z) { map(z) = a * map(x) + b * map(y); }
void constant(double c, N_Vector z) { map(z).setConstant(c); }
void product(N_Vector x, N_Vector y, N_Vector z) { map(z) = map(x).cwiseProduct(map(y)); }
void scale(double c, N_Vector x, N_Vector z) { map(z) = c * map(x); }
void absolute(N_Vector x, N_Vector z) { map(z) = map(x).cwiseAbs(); }
void inverse(N_Vector x, N_Vector z) { map(z) = map(x).cwiseInverse(); }
void add_constant(N_Vector x, double b, N_Vector z) { map(z) = map(x).array() + b; }
double dot(N_Vector x, N_Vector y) { return map(x).dot(map(y)); }
double max_norm(N_Vector x) { return NV_LENGTH_S(x) == 0 ? 0.0 : map(x).lpNorm<Eigen::Infinity>(); }
double weighted_square_sum(N_Vector x, N_Vector w) { return map(x).cwiseProduct(map(w)).squaredNorm(); }
double wrms_norm(N_Vector x, N_Vector w) { return std::sqrt(weighted_square_sum(x, w) / static_cast<double>(NV_LENGTH_S(x))); }

// z = sum_i c_i X_i; z may be one of the X_i (SUNDIALS allows X[0] == z).
int linear_combination(int count, double* c, N_Vector* X, N_Vector z) {
  if (count < 1) return -1;
  auto out = map(z);
  if (X[0] == z)
    out *= c[0];
  else
    out = c[0] * map(X[0]);
  for (int i = 1; i < count; ++i) {
    if (X[i] == z) return -1;  // not a form SUNDIALS uses; refuse rather than compute it wrongly
    out += c[i] * map(X[i]);
  }
  return 0;
}

// Z_i = a_i x + Y_i.
int scale_add_multi(int count, double* a, N_Vector x, N_Vector* Y, N_Vector* Z) {
  const auto in = map(x);
  for (int i = 0; i < count; ++i) map(Z[i]) = a[i] * in + map(Y[i]);
  return 0;
}

}  // namespace

void use_vectorized_ops(N_Vector v) {
  N_Vector_Ops ops = v->ops;
  ops->nvlinearsum = linear_sum;
  ops->nvconst = constant;
  ops->nvprod = product;
  ops->nvscale = scale;
  ops->nvabs = absolute;
  ops->nvinv = inverse;
  ops->nvaddconst = add_constant;
  ops->nvdotprod = dot;
  ops->nvmaxnorm = max_norm;
  ops->nvwrmsnorm = wrms_norm;
  ops->nvwsqrsumlocal = weighted_square_sum;
  ops->nvlinearcombination = linear_combination;
  ops->nvscaleaddmulti = scale_add_multi;
}

}  // namespace roifem::integrators::sundials
