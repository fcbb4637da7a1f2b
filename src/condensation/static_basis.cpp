// SPDX-License-Identifier: GPL-3.0-or-later
#include "condensation/static_basis.hpp"

#include <algorithm>

namespace roifem::condensation {

model::Modes static_basis(const Reduction& reduction, const model::SecondOrderSystem& full, const roi::Partition& partition,
                          StaticPartFactor& factor, const DenseMatrix& X) {
  const BasisMaker make = reduction.info().make_basis;
  if (make == nullptr || !factor.has_static_part())
    return {.omega = Vector(0), .shapes = DenseMatrix(static_cast<Index>(partition.s.size()), 0)};
  return make({.reduction = reduction,
               .full = full,
               .partition = partition,
               .X = X,
               .M_s = roi::gather(full.M.diagonal(), partition.s),
               .solve_K_ss = [&factor](const Vector& b, Vector& x) { factor.solve_static(b, x); }});
}

model::Modes fixed_interface_modes(const BasisRequest& request) {
  const Reduction& r = request.reduction;
  if (r.modes > 0) return model::lowest_modes(request.M_s, request.solve_K_ss, std::min(r.modes, request.static_dofs()));
  return model::modes_below(request.M_s, request.solve_K_ss, r.cutoff_rad_s);
}

}  // namespace roifem::condensation
