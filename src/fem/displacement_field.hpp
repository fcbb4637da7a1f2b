// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// A displacement over the free dofs as the field results files hold: every node's (x, y, z) in
/// mm, row-major #N x 3, constrained components 0.
#include <vector>

#include "common/types.hpp"
#include "fem/dof_map.hpp"

namespace roifem::fem {

inline std::vector<double> displacement_field_mm(const DofMap& dofs, const Vector& u_free) {
  const Vector full = dofs.expand(u_free) / mm;
  return {full.data(), full.data() + full.size()};
}

}  // namespace roifem::fem
