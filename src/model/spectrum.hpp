#pragma once
/// The highest angular eigenfrequency of M u'' + K u = 0, w_max = sqrt(lambda_max(M^-1 K)): what
/// limits an explicit integrator's step (dt <= c / w_max for a method-dependent c). Lanczos
/// (Spectra's implicitly restarted SymEigsSolver) on the symmetric M^-1/2 K M^-1/2, so that it
/// costs a few dozen products with K at any size, where a dense eigensolver stops at a few
/// thousand dofs.
#include "model/second_order_system.hpp"

namespace roifem::model {

/// Throws InputError unless M is diagonal and positive; SolverError when Lanczos does not converge.
double highest_frequency(const SecondOrderSystem& system, double tolerance = 1e-10);

}  // namespace roifem::model
