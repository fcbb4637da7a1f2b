// SPDX-License-Identifier: GPL-3.0-or-later
#include "distributed/condensed_roi.hpp"

#include <algorithm>

namespace roifem::distributed {

std::vector<Index> roi_free_dofs(const fem::DofMap& dofs, const std::vector<int>& roi_nodes) {
  std::vector<Index> d;
  for (const int n : roi_nodes)
    for (int c = 0; c < 3; ++c)
      if (const int i = dofs.free_dof(n, c); i >= 0) d.push_back(i);
  std::sort(d.begin(), d.end());
  return d;
}

model::SecondOrderSystem condensed_roi_system(const DistributedModel& model, const DistributedCondensation& condensed,
                                              const std::vector<Index>& roi_dofs) {
  const auto n = static_cast<Index>(roi_dofs.size());
  const model::SecondOrderSystem& full = model.frame->system;
  Vector m(n);
  for (Index i = 0; i < n; ++i) m(i) = full.M.coeff(roi_dofs[static_cast<std::size_t>(i)], roi_dofs[static_cast<std::size_t>(i)]);
  model::SecondOrderSystem roi;
  roi.K = condensed.K_tilde.sparseView();
  roi.M = model::diagonal_matrix(m);
  roi.C = model::diagonal_matrix(model.alpha * m);
  roi.damping = model::Damping::mass_proportional(model.alpha);
  roi.load = model::LoadHistory(n);
  for (std::size_t k = 0; k < condensed.f_tilde.size(); ++k) roi.load.add(condensed.f_tilde[k], model.loads[k].ramp);
  return roi;
}

}  // namespace roifem::distributed
