// SPDX-License-Identifier: GPL-3.0-or-later
// Loads as patterns times ramps (load_history.hpp): the ramp's shape, superposition of terms, and
// the derived histories, checked against the closed form r(t) = min(t / T, 1).
#include "model/load_history.hpp"

#include <gtest/gtest.h>

#include "common/errors.hpp"

namespace roifem::model {
namespace {

TEST(Ramp, RisesLinearlyThenHoldsAndAZeroDurationIsAStepAtZero) {
  const Ramp half{0.5};
  EXPECT_EQ(half.value(-1.0), 0.0);
  EXPECT_EQ(half.value(0.0), 0.0);
  EXPECT_DOUBLE_EQ(half.value(0.125), 0.25);
  EXPECT_DOUBLE_EQ(half.value(0.5), 1.0);
  EXPECT_EQ(half.value(7.0), 1.0);
  const Ramp step{0.0};
  EXPECT_EQ(step.value(-1e-9), 0.0);
  EXPECT_EQ(step.value(0.0), 1.0);
  EXPECT_EQ(step.value(3.0), 1.0);
}

TEST(LoadHistory, IsTheSumOfEachPatternTimesItsRamp) {
  LoadHistory load(3);
  const Vector p1 = Vector::LinSpaced(3, 1.0, 3.0), p2 = Vector::Constant(3, -0.5);
  load.add(p1, Ramp{1.0});
  load.add(p2, Ramp{2.0});
  for (double t : {0.0, 0.3, 1.0, 1.7, 2.0, 10.0}) {
    const Vector expected = std::min(t / 1.0, 1.0) * p1 + std::min(t / 2.0, 1.0) * p2;
    EXPECT_LT((load.at(t) - expected).norm(), 1e-15) << "t = " << t;
    Vector f = Vector::Constant(3, 99.0);  // evaluate overwrites, never accumulates
    load.evaluate(t, f);
    EXPECT_EQ(f, load.at(t));
  }
}

TEST(LoadHistory, DerivedHistoriesKeepPatternsOrRamps) {
  LoadHistory load(2);
  load.add(Vector::Ones(2), Ramp{1.0});
  load.add(Vector::Constant(2, 2.0), Ramp{4.0});
  const LoadHistory steps = load.with_ramp(Ramp{0.0});
  EXPECT_EQ(steps.at(0.01), Vector::Constant(2, 3.0));
  const LoadHistory doubled = load.mapped(1, [](const Vector& p) { return Vector::Constant(1, 2 * p.sum()); });
  ASSERT_EQ(doubled.size(), 1);
  EXPECT_DOUBLE_EQ(doubled.at(2.0)[0], 2 * (2.0 * 1.0 + 4.0 * 0.5));
}

TEST(LoadHistory, RefusesANegativeRampAndAPatternOfTheWrongSize) {
  LoadHistory load(2);
  EXPECT_THROW(load.add(Vector::Ones(2), Ramp{-1.0}), InputError);
  EXPECT_THROW(load.add(Vector::Ones(3), Ramp{1.0}), Error);
}

}  // namespace
}  // namespace roifem::model

namespace roifem::model {
namespace {

TEST(Ramp, RatesAndAccelerationsAreTheValuesDerivatives) {
  for (const auto shape : {Ramp::Shape::linear, Ramp::Shape::smooth}) {
    const Ramp r{0.4, shape};
    EXPECT_EQ(r.value(0.0), 0.0);
    EXPECT_EQ(r.value(0.4), 1.0);
    EXPECT_EQ(r.value(0.9), 1.0);
    EXPECT_NEAR(r.value(0.2), 0.5, 1e-15);  // both are symmetric about the middle
    const double h = 1e-6;
    for (const double t : {0.05, 0.13, 0.2, 0.31, 0.39}) {
      EXPECT_NEAR(r.rate(t), (r.value(t + h) - r.value(t - h)) / (2 * h), 1e-6) << t;
      EXPECT_NEAR(r.acceleration(t), (r.rate(t + h) - r.rate(t - h)) / (2 * h), 1e-4) << t;
    }
    EXPECT_EQ(r.rate(0.5), 0.0);
  }
  const Ramp smooth{0.4, Ramp::Shape::smooth};  // at rest at both ends: no kink for a DAE to restart at
  EXPECT_EQ(smooth.rate(0.0), 0.0);
  EXPECT_NEAR(smooth.rate(0.4 - 1e-12), 0.0, 1e-9);
  EXPECT_EQ(smooth.acceleration(0.0), 0.0);
  EXPECT_NEAR(Ramp{0.4}.rate(0.0), 2.5, 1e-15);  // linear: 1 / duration from t = 0 on
}

}  // namespace
}  // namespace roifem::model
