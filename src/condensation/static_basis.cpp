#include "condensation/static_basis.hpp"

#include <algorithm>

#include "common/errors.hpp"
#include "condensation/pod_basis.hpp"

namespace roifem::condensation {

model::Modes static_basis(const Reduction& reduction, const model::SecondOrderSystem& full, const roi::Partition& partition,
                          StaticPartFactor& factor, const DenseMatrix& X) {
  const auto n_s = static_cast<Index>(partition.s.size());
  model::Modes none{.omega = Vector(0), .shapes = DenseMatrix(n_s, 0)};
  if (!factor.has_static_part()) return none;
  const Vector M_s = roi::gather(full.M.diagonal(), partition.s);
  const model::SolveK solve_K_ss = [&factor](const Vector& b, Vector& x) { factor.solve_static(b, x); };
  switch (reduction.info().basis) {
    case StaticBasis::none:
      return none;
    case StaticBasis::fixed_interface_modes:
      if (reduction.modes > 0) return model::lowest_modes(M_s, solve_K_ss, std::min(reduction.modes, n_s));
      return model::modes_below(M_s, solve_K_ss, reduction.cutoff_rad_s);
    case StaticBasis::pod:
      return pod_basis({full, partition, X, reduction.snapshot_dt_s, reduction.snapshot_steps}, std::min(reduction.modes, n_s));
  }
  return none;
}

}  // namespace roifem::condensation
