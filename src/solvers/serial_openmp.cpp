// SPDX-License-Identifier: GPL-3.0-or-later
#include "solvers/serial_openmp.hpp"

#include <omp.h>

namespace roifem::solvers {

SerialOpenMpScope::SerialOpenMpScope(bool active) {
  if (!active) return;
  previous_levels_ = omp_get_max_active_levels();
  omp_set_max_active_levels(0);  // no level may be active: every region runs on its one thread
}

SerialOpenMpScope::~SerialOpenMpScope() {
  if (previous_levels_ >= 0) omp_set_max_active_levels(previous_levels_);
}

}  // namespace roifem::solvers
