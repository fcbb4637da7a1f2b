// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Wall-clock stopwatch (steady clock).
#include <chrono>

namespace roifem {

class Stopwatch {
 public:
  Stopwatch() : start_(Clock::now()) {}
  void restart() { start_ = Clock::now(); }
  /// Seconds since construction or the last restart().
  double seconds() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }

 private:
  using Clock = std::chrono::steady_clock;
  Clock::time_point start_;
};

}  // namespace roifem
