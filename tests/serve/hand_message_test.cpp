// SPDX-License-Identifier: GPL-3.0-or-later
#include "serve/hand_message.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <regex>

namespace roifem::serve {
namespace {

std::variant<HandMessage, std::string> decode(const std::string& bytes) {
  return decode_hand_message(std::span(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()));
}

TEST(HandMessage, EveryKindReadsBackWhatWasWritten) {
  for (const HandKind kind : {HandKind::pick, HandKind::target, HandKind::release, HandKind::model, HandKind::save,
                              HandKind::compare, HandKind::whole}) {
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
  // A scalpel's stroke: its edge and move, each of the nine numbers as sent.
  const HandMessage stroke{.kind = HandKind::cut,
                           .sequence = 7,
                           .point_mm = Vec3(1.25, -3, 60),
                           .model = 0,
                           .edge_to_mm = Vec3(1.25, -3, 50.5),
                           .move_mm = Vec3(0, 4.125, -1e-3)};
  const std::string bytes = encode_hand_message(stroke);
  EXPECT_EQ(bytes.size(), 80U);
  const auto got = decode(bytes);
  ASSERT_TRUE(std::holds_alternative<HandMessage>(got)) << std::get<std::string>(got);
  const HandMessage& m = std::get<HandMessage>(got);
  EXPECT_EQ(m.kind, HandKind::cut);
  EXPECT_EQ(m.point_mm, stroke.point_mm);
  EXPECT_EQ(m.edge_to_mm, stroke.edge_to_mm);
  EXPECT_EQ(m.move_mm, stroke.move_mm);
  EXPECT_TRUE(m.crossed.empty());  // the server's to find
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
  EXPECT_EQ(refused(unknown), "an unknown kind 9 (1 pick, 2 target, 3 release, 4 model, 5 save, 6 compare, 7 cut, 8 whole)");
  std::string padded = target;
  padded[2] = 1;
  EXPECT_EQ(refused(padded), "a header whose padding bytes 1-3 are not zero");
  for (const double bad : {std::nan(""), std::numeric_limits<double>::infinity()}) {
    const std::string pick =
        encode_hand_message({.kind = HandKind::pick, .sequence = 2, .point_mm = Vec3(0, bad, 0), .model = 0});
    EXPECT_EQ(refused(pick), "a pick at a point that is not finite");
  }
  // A stroke that is not finite, whose edge has no length, or that does not move.
  const auto cut = [](const Vec3& from, const Vec3& to, const Vec3& move) {
    return encode_hand_message(
        {.kind = HandKind::cut, .sequence = 3, .point_mm = from, .model = 0, .edge_to_mm = to, .move_mm = move});
  };
  EXPECT_EQ(refused(cut(Vec3(0, 0, 1), Vec3(0, 0, 0), Vec3(0, std::nan(""), 0))), "a cut whose blade is not finite");
  EXPECT_EQ(refused(cut(Vec3(0, 0, 1), Vec3(0, 0, 1), Vec3(1, 0, 0))), "a cut whose blade's edge has no length");
  EXPECT_EQ(refused(cut(Vec3(0, 0, 1), Vec3(0, 0, 0), Vec3(0, 0, 0))), "a cut whose blade does not move (it sweeps nothing)");
  EXPECT_EQ(refused(cut(Vec3(0, 0, 1), Vec3(0, 0, 0), Vec3(1, 0, 0)).substr(0, 32)), "a cut message of 32 bytes (it has 80)");
  EXPECT_EQ(
      refused(encode_hand_message({.kind = HandKind::release, .sequence = 1, .point_mm = Vec3::Zero(), .model = 0}) + "abcd"),
      "a release message of 12 bytes (it has 8)");
}

// The page builds its frames from the table the hello carries (web/app.js's send): frames built so,
// as a page would, for every kind of the protocol's documented codes, decode to that kind with
// the numbers written.
TEST(HandMessage, FramesBuiltFromTheHellosTableAreTheKindsTheyName) {
  const std::string json = hand_protocol_json();
  const std::regex header(R"re("header_bytes":(\d+))re");
  std::smatch h;
  ASSERT_TRUE(std::regex_search(json, h, header)) << json;
  const std::size_t at = std::stoul(h[1]);
  const std::vector<std::pair<std::string, HandKind>> documented{
      {"pick", HandKind::pick}, {"target", HandKind::target},   {"release", HandKind::release}, {"model", HandKind::model},
      {"save", HandKind::save}, {"compare", HandKind::compare}, {"cut", HandKind::cut},         {"whole", HandKind::whole}};
  for (const auto& [name, expected] : documented) {
    const std::regex entry("\"" + name + R"re(":\{"code":(\d+),"bytes":(\d+),"payload":"(\w+)"\})re");
    std::smatch e;
    ASSERT_TRUE(std::regex_search(json, e, entry)) << name << " is not in " << json;
    std::string frame(std::stoul(e[2]), '\0');
    frame[0] = static_cast<char>(std::stoi(e[1]));
    const std::uint32_t sequence = 17;
    std::memcpy(frame.data() + 4, &sequence, 4);
    const std::string payload = e[3];
    const std::vector<double> numbers{1.5, -2.25, 3, 4, 5.5, 6, 7, 8.75, -9};
    if (payload == "point" || payload == "stroke")
      for (std::size_t k = 0; k < (payload == "point" ? 3U : 9U); ++k) std::memcpy(frame.data() + at + 8 * k, &numbers[k], 8);
    const std::uint32_t index = 2;
    if (payload == "index") std::memcpy(frame.data() + at, &index, 4);
    const auto got = decode(frame);
    ASSERT_TRUE(std::holds_alternative<HandMessage>(got)) << name << ": " << std::get<std::string>(got);
    const HandMessage& m = std::get<HandMessage>(got);
    EXPECT_EQ(m.kind, expected) << name;
    EXPECT_EQ(m.sequence, sequence) << name;
    if (payload != "none" && payload != "index") {
      EXPECT_EQ(m.point_mm, Vec3(1.5, -2.25, 3)) << name;
    }
    if (payload == "stroke") {
      EXPECT_EQ(m.move_mm, Vec3(7, 8.75, -9)) << name;
    }
    if (payload == "index") {
      EXPECT_EQ(m.model, index) << name;
    }
  }
  EXPECT_EQ(std::count(json.begin(), json.end(), '{'), 2 + static_cast<long>(documented.size()))
      << "a kind the test does not know: " << json;
}

}  // namespace
}  // namespace roifem::serve
