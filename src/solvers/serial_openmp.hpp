// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// OpenMP's parallel regions made inactive (one thread each) for one scope, restored when it ends.
///
/// SuiteSparse 5's CHOLMOD opens an OpenMP region of a fixed 4 threads (CHOLMOD_OMP_NUM_THREADS)
/// around each supernode's copies in its numeric factorization. On a small factor that is a region
/// per supernode for little work, and on two cores 4 threads oversubscribe them: the threads meet
/// at futexes some 8,000 times a Newton step, and kernel time exceeded user time
/// (docs/design-figures.md). The regions copy and zero (no reductions), so the factor is the same,
/// bit for bit, on one thread. roifem's own regions (the assembly) are outside such a scope.
namespace roifem::solvers {

class SerialOpenMpScope {
 public:
  /// active: make the regions inactive for this scope; false: change nothing.
  explicit SerialOpenMpScope(bool active);
  SerialOpenMpScope(const SerialOpenMpScope&) = delete;
  SerialOpenMpScope& operator=(const SerialOpenMpScope&) = delete;
  ~SerialOpenMpScope();

 private:
  int previous_levels_ = -1;  ///< -1: nothing to restore
};

}  // namespace roifem::solvers
