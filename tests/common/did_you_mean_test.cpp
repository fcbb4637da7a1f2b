// SPDX-License-Identifier: GPL-3.0-or-later
// "Did you mean" (did_you_mean.hpp): edit distances of textbook pairs, and a suggestion only for
// names close enough to be typos.
#include "common/did_you_mean.hpp"

#include <gtest/gtest.h>

namespace roifem {
namespace {

TEST(EditDistance, CountsInsertionsDeletionsAndSubstitutions) {
  EXPECT_EQ(edit_distance("kitten", "sitting"), 3u);
  EXPECT_EQ(edit_distance("", "abc"), 3u);
  EXPECT_EQ(edit_distance("radius_mm", "radus_mm"), 1u);
  EXPECT_EQ(edit_distance("steps", "stesp"), 2u);
  EXPECT_EQ(edit_distance("same", "same"), 0u);
}

TEST(DidYouMean, SuggestsTheClosestNameOnlyWhenItLooksLikeATypo) {
  const std::vector<std::string> integrators{"trapezoid", "trapezoid-cg", "arkode-erk4", "ida-bdf5"};
  EXPECT_EQ(did_you_mean("trapezoidal", integrators), " (did you mean 'trapezoid'?)");
  EXPECT_EQ(did_you_mean("arkode-erk5", integrators), " (did you mean 'arkode-erk4'?)");
  EXPECT_EQ(did_you_mean("newmark", integrators), "");    // nothing close
  EXPECT_EQ(did_you_mean("trapezoid", integrators), "");  // already valid
  EXPECT_EQ(closest_name("--hlep", {"--help", "--out"}), "--help");
  // A name without its family's prefix: the shortest name that contains it.
  EXPECT_EQ(closest_name("esdirk4", {"arkode-esdirk4-mass", "arkode-esdirk4", "ida-bdf5"}), "arkode-esdirk4");
  // Equally close: the one that contains the name ("ramp" is 2 edits from both).
  EXPECT_EQ(edit_distance("ramp", "name"), edit_distance("ramp", "ramp_s"));
  EXPECT_EQ(closest_name("ramp", {"center_mm", "name", "ramp_s"}), "ramp_s");
}

}  // namespace
}  // namespace roifem
