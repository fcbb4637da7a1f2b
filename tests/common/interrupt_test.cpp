// SPDX-License-Identifier: GPL-3.0-or-later
// SIGINT / SIGTERM as a request (common/interrupt.hpp): heard under a guard, by the run loop and
// inside a step's callbacks, and forgotten with the last guard, so that a later integration
// without one does not stop for an old signal.
#include "common/interrupt.hpp"

#include <gtest/gtest.h>

#include <csignal>

#include "common/errors.hpp"
#include "integrators/factory.hpp"
#include "integrators/test_problems.hpp"

namespace roifem {
namespace {

TEST(InterruptGuard, HearsASignalWhileAliveAndForgetsItWithTheLastGuard) {
  {
    const InterruptGuard outer;
    {
      const InterruptGuard inner;
      std::raise(SIGTERM);
      EXPECT_EQ(InterruptGuard::signal_received(), SIGTERM);
    }
    EXPECT_EQ(InterruptGuard::signal_received(), SIGTERM) << "the outer guard still owes the answer";
  }
  EXPECT_EQ(InterruptGuard::signal_received(), 0);
}

TEST(InterruptGuard, AnIntegratorStopsInsideAStepUnderAGuardAndNotAfterIt) {
  const integrators::test_problems::Cantilever c(-0.02, 0.1);
  auto run = [&] {
    auto ida = integrators::make_integrator("ida-bdf5", {.dt = 0.01, .adaptive = true, .rtol = 1e-8, .atol = 1e-12});
    model::State s = c.rest();
    ida->reset(c.sys(), s);
    ida->advance_to(0.1, s);
  };
  {
    const InterruptGuard guard;
    std::raise(SIGINT);
    try {
      run();
      FAIL() << "the step did not hear the signal";
    } catch (const Interrupted& e) {
      EXPECT_EQ(e.signal, SIGINT);
      EXPECT_NE(std::string(e.what()).find("inside a step"), std::string::npos) << e.what();
    }
  }
  EXPECT_NO_THROW(run());  // the old signal is gone with its guard
}

}  // namespace
}  // namespace roifem
