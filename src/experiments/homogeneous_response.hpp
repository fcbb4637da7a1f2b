// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// A hyperelastic law's response to the homogeneous deformations of a tissue test, computed from
/// the law's own stress (fem/hyperelastic_law.hpp), not from a closed form:
///   uniaxial tension or compression: F = diag(lambda, t, t), the lateral stretch t found so that
///     the lateral stress P_22 = P_33 vanishes (Brent's method, GSL), the answer P_11;
///   simple shear: F = I + gamma e_1 e_2^T exactly, the answer P_12 (= sigma_12, J = 1).
/// Nominal (first Piola-Kirchhoff) stresses in Pa, as Budday et al. (2017) report theirs.
#include "fem/hyperelastic_law.hpp"

namespace roifem::experiments {

/// The lateral stretch t at which diag(lambda, t, t) leaves the lateral faces free (SolverError if
/// no t in (0, 10 / sqrt(lambda)] does).
double uniaxial_lateral_stretch(const fem::HyperelasticLaw& law, double lambda);
/// P_11 under uniaxial stretch lambda with free lateral faces (Pa).
double uniaxial_nominal_stress(const fem::HyperelasticLaw& law, double lambda);
/// P_12 under simple shear of amount gamma (Pa).
double simple_shear_stress(const fem::HyperelasticLaw& law, double gamma);

}  // namespace roifem::experiments
