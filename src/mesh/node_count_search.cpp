// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesh/node_count_search.hpp"

#include <cmath>

namespace roifem::mesh {

bool NodeCountSearch::record(double nodes, double tolerance) {
  if (std::abs(nodes / target_ - 1) <= tolerance) return true;
  (nodes > target_ ? h_fine_ : h_coarse_) = h_;
  if (stuck()) return false;
  if (prev_n_ > 0 && std::abs(std::log(h_ / prev_h_)) > 1e-4) {
    const double measured = std::log(nodes / prev_n_) / std::log(h_ / prev_h_);
    if (measured < -1.0 && measured > -4.0) slope_ = measured;
  }
  prev_h_ = h_;
  prev_n_ = nodes;
  h_ *= std::exp(std::log(target_ / nodes) / slope_);
  if (h_fine_ > 0 && h_coarse_ > 0 && !(h_ > h_fine_ && h_ < h_coarse_)) h_ = std::sqrt(h_fine_ * h_coarse_);
  return false;
}

}  // namespace roifem::mesh
