// SPDX-License-Identifier: GPL-3.0-or-later
#include "serve/hand_message.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace roifem::serve {
namespace {

std::variant<HandMessage, std::string> decode(const std::string& bytes) {
  return decode_hand_message(std::span(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()));
}

TEST(HandMessage, EveryKindReadsBackWhatWasWritten) {
  for (const HandKind kind :
       {HandKind::pick, HandKind::target, HandKind::release, HandKind::model, HandKind::save, HandKind::compare}) {
    const HandMessage sent{.kind = kind, .sequence = 4000000001U, .point_mm = Vec3(-12.5, 0.1, 1e3), .model = 3};
    const auto got = decode(encode_hand_message(sent));
    ASSERT_TRUE(std::holds_alternative<HandMessage>(got)) << std::get<std::string>(got);
    const HandMessage& m = std::get<HandMessage>(got);
    EXPECT_EQ(m.kind, kind);
    EXPECT_EQ(m.sequence, sent.sequence);
    if (kind == HandKind::pick || kind == HandKind::target) {
      EXPECT_EQ(m.point_mm, sent.point_mm);
    }
    if (kind == HandKind::model || kind == HandKind::compare) {
      EXPECT_EQ(m.model, 3U);
    }
  }
}

TEST(HandMessage, MalformedFramesAreRefusedWithTheReason) {
  const std::string target =
      encode_hand_message({.kind = HandKind::target, .sequence = 1, .point_mm = Vec3(1, 2, 3), .model = 0});
  auto refused = [](const std::string& bytes) {
    const auto got = decode(bytes);
    return std::holds_alternative<std::string>(got) ? std::get<std::string>(got) : std::string("accepted");
  };
  EXPECT_EQ(refused(""), "a message of 0 bytes (the header alone is 8)");
  EXPECT_EQ(refused(target.substr(0, 5)), "a message of 5 bytes (the header alone is 8)");
  EXPECT_EQ(refused(target.substr(0, 31)), "a target message of 31 bytes (it has 32)");
  EXPECT_EQ(refused(target + "x"), "a target message of 33 bytes (it has 32)");
  std::string unknown = target;
  unknown[0] = 9;
  EXPECT_EQ(refused(unknown), "an unknown kind 9 (1 pick, 2 target, 3 release, 4 model, 5 save, 6 compare)");
  std::string padded = target;
  padded[2] = 1;
  EXPECT_EQ(refused(padded), "a header whose padding bytes 1-3 are not zero");
  for (const double bad : {std::nan(""), std::numeric_limits<double>::infinity()}) {
    const std::string pick =
        encode_hand_message({.kind = HandKind::pick, .sequence = 2, .point_mm = Vec3(0, bad, 0), .model = 0});
    EXPECT_EQ(refused(pick), "a pick at a point that is not finite");
  }
  EXPECT_EQ(
      refused(encode_hand_message({.kind = HandKind::release, .sequence = 1, .point_mm = Vec3::Zero(), .model = 0}) + "abcd"),
      "a release message of 12 bytes (it has 8)");
}

}  // namespace
}  // namespace roifem::serve
