// SPDX-License-Identifier: GPL-3.0-or-later
// The progress reporter's lines in a log (simulation/progress.hpp), terminal or not: none before
// the phase has run its stated time, then one with the estimate, then none until its interval.
#include "simulation/progress.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <regex>
#include <sstream>
#include <thread>

namespace roifem::simulation {
namespace {

TEST(ProgressReporter, LogsALineWithItsEstimateOnceThePhaseHasRunItsStatedTime) {
  std::ostringstream log;
  {
    ProgressReporter progress("reference ida-bdf5", 200, 2.0, "outputs", &log, {.after_s = 0.05, .every_s = 60});
    progress.update(10);
    EXPECT_EQ(log.str(), "") << "before after_s";
    std::this_thread::sleep_for(std::chrono::milliseconds(80));
    progress.update(50);
    progress.update(60);   // within every_s of the first: no second line
    progress.update(200);  // done: nothing to estimate
  }
  const std::string said = log.str();
  EXPECT_TRUE(
      std::regex_match(said, std::regex("  reference ida-bdf5: 50 of 200 outputs in 0\\.[0-9] s; about 0\\.[0-9] s to go\n")))
      << said;
}

TEST(ProgressReporter, WithoutALogSaysNothingThere) {
  ProgressReporter progress("run", 10, 2.0, "steps", nullptr, {.after_s = 0, .every_s = 0});
  EXPECT_NO_THROW(progress.update(5));
}

}  // namespace
}  // namespace roifem::simulation
