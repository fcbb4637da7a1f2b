// SPDX-License-Identifier: GPL-3.0-or-later
#include "simulation/progress.hpp"

#include <unistd.h>

#include <cstdio>
#include <ostream>

namespace roifem::simulation {

namespace {

std::string io_seconds(double s) {
  char text[32];
  std::snprintf(text, sizeof text, s < 100 ? "%.1f s" : "%.0f s", s);
  return text;
}

}  // namespace

ProgressReporter::ProgressReporter(std::string label, long total, double delay_s, std::string unit, std::ostream* log,
                                   ProgressLogged logged)
    : label_(std::move(label)),
      unit_(std::move(unit)),
      total_(total),
      delay_s_(delay_s),
      log_(log),
      logged_(logged),
      enabled_(::isatty(STDERR_FILENO) != 0) {}

ProgressReporter::~ProgressReporter() {
  if (drawn_) std::fprintf(stderr, "\r\033[K");
}

void ProgressReporter::update(long done, const std::string& detail) {
  const double t = (enabled_ || log_) ? clock_.seconds() : 0.0;
  if (log_ && done < total_ && done > 0 && t >= logged_.after_s && (last_logged_ < 0 || t - last_logged_ >= logged_.every_s)) {
    last_logged_ = t;
    const double left = t / static_cast<double>(done) * static_cast<double>(total_ - done);
    if (drawn_) std::fprintf(stderr, "\r\033[K");
    *log_ << "  " << label_ << ": " << done << " of " << total_ << " " << unit_ << " in " << io_seconds(t) << "; about "
          << io_seconds(left) << " to go" << (detail.empty() ? "" : " (" + detail + ")") << "\n"
          << std::flush;
  }
  if (!enabled_) return;
  if (t < delay_s_ || (t - last_draw_ < 0.2 && done < total_)) return;
  last_draw_ = t;
  drawn_ = true;
  const double fraction = total_ > 0 ? static_cast<double>(done) / static_cast<double>(total_) : 1.0;
  const double eta = fraction > 0 ? t * (1 - fraction) / fraction : 0.0;
  std::fprintf(stderr, "\r\033[K%s  %ld/%ld %s  %3.0f%%  eta %.0f s%s%s", label_.c_str(), done, total_, unit_.c_str(),
               100 * fraction, eta, detail.empty() ? "" : "  ", detail.c_str());
  std::fflush(stderr);
}

}  // namespace roifem::simulation
