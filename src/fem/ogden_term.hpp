// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// One term of an Ogden law (fem/ogden.hpp): 2 mu / alpha^2 (lbar_1^alpha + lbar_2^alpha + lbar_3^alpha - 3).

namespace roifem::fem {

struct OgdenTerm {
  double mu = 0;     ///< Pa, > 0
  double alpha = 0;  ///< dimensionless, != 0
};

}  // namespace roifem::fem
