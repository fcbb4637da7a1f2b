// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// A progress line on a terminal for long runs (after `delay_s` seconds), redrawn at most every
/// 0.2 s on stderr: "label  120/200 steps  60%  eta 3 s  detail". Silent when stderr is not a terminal.
/// With a log, also a line there, terminal or not, once a phase has run ProgressLogged::after_s and then
/// every ProgressLogged::every_s: "  label: 120 of 200 steps in 31.0 s; about 21 s to go" (a run
/// whose log says nothing for minutes looks hung).
#include <iosfwd>
#include <string>

#include "common/timer.hpp"

namespace roifem::simulation {

/// When a progress reporter's log gets its lines: the first after `after_s` of the phase, then
/// every `every_s`.
struct ProgressLogged {
  double after_s = 5, every_s = 60;
};

class ProgressReporter {
 public:
  ProgressReporter(std::string label, long total, double delay_s = 2.0, std::string unit = "steps", std::ostream* log = nullptr,
                   ProgressLogged logged = {});
  ~ProgressReporter();
  ProgressReporter(const ProgressReporter&) = delete;
  ProgressReporter& operator=(const ProgressReporter&) = delete;
  /// `detail`: what is being done now, shown after the estimate.
  void update(long done, const std::string& detail = {});

 private:
  std::string label_, unit_;
  long total_;
  double delay_s_, last_draw_ = -1, last_logged_ = -1;
  std::ostream* log_;
  ProgressLogged logged_;
  bool enabled_, drawn_ = false;
  Stopwatch clock_;
};

}  // namespace roifem::simulation
