// SPDX-License-Identifier: GPL-3.0-or-later
#include "serve/hand_message.hpp"

#include <array>
#include <cmath>
#include <cstring>

namespace roifem::serve {

namespace {

constexpr std::size_t header_bytes = 8;

/// What follows a kind's header, and per payload (in the enum's order) its name in the hello and
/// the message's size with it.
enum class Payload { none, point, index, stroke };

struct PayloadInfo {
  const char* name;
  std::size_t bytes;
};

constexpr std::array<PayloadInfo, 4> payloads{{{"none", header_bytes},
                                               {"point", header_bytes + 3 * sizeof(double)},
                                               {"index", header_bytes + sizeof(std::uint32_t)},
                                               {"stroke", header_bytes + 9 * sizeof(double)}}};

const char* payload_name(Payload payload) { return payloads[static_cast<std::size_t>(payload)].name; }
std::size_t size_of(Payload payload) { return payloads[static_cast<std::size_t>(payload)].bytes; }

struct KindInfo {
  HandKind kind;
  const char* name;
  Payload payload;
};

/// Every kind once, in the order of their codes (1, 2, ...): decode, encode and the refusals read it.
constexpr std::array<KindInfo, 8> kinds{{{HandKind::pick, "pick", Payload::point},
                                         {HandKind::target, "target", Payload::point},
                                         {HandKind::release, "release", Payload::none},
                                         {HandKind::model, "model", Payload::index},
                                         {HandKind::save, "save", Payload::none},
                                         {HandKind::compare, "compare", Payload::index},
                                         {HandKind::cut, "cut", Payload::stroke},
                                         {HandKind::whole, "whole", Payload::none}}};

constexpr bool in_code_order() {
  for (std::size_t k = 0; k < kinds.size(); ++k)
    if (static_cast<std::size_t>(kinds[k].kind) != k + 1) return false;
  return true;
}
static_assert(in_code_order(), "the kinds' table is indexed by code - 1");

const KindInfo& info(HandKind kind) { return kinds[static_cast<std::size_t>(kind) - 1]; }

/// "1 pick, 2 target, ...".
std::string kind_list() {
  std::string list;
  for (std::size_t k = 0; k < kinds.size(); ++k) list += (k ? ", " : "") + std::to_string(k + 1) + " " + kinds[k].name;
  return list;
}

template <class T>
T read_at(std::span<const std::uint8_t> bytes, std::size_t offset) {
  T value;
  std::memcpy(&value, bytes.data() + offset, sizeof(T));  // x86-64 and the page: little-endian both
  return value;
}

}  // namespace

std::variant<HandMessage, std::string> decode_hand_message(std::span<const std::uint8_t> bytes) {
  if (bytes.size() < header_bytes)
    return "a message of " + std::to_string(bytes.size()) + " bytes (the header alone is " + std::to_string(header_bytes) + ")";
  const std::uint8_t code = bytes[0];
  if (code < 1 || code > kinds.size()) return "an unknown kind " + std::to_string(code) + " (" + kind_list() + ")";
  if (bytes[1] != 0 || bytes[2] != 0 || bytes[3] != 0) return "a header whose padding bytes 1-3 are not zero";
  HandMessage m;
  m.kind = static_cast<HandKind>(code);
  const KindInfo& kind = info(m.kind);
  if (bytes.size() != size_of(kind.payload))
    return std::string("a ") + kind.name + " message of " + std::to_string(bytes.size()) + " bytes (it has " +
           std::to_string(size_of(kind.payload)) + ")";
  m.sequence = read_at<std::uint32_t>(bytes, 4);
  if (kind.payload == Payload::point) {
    for (int c = 0; c < 3; ++c)
      m.point_mm[c] = read_at<double>(bytes, header_bytes + sizeof(double) * static_cast<std::size_t>(c));
    if (!m.point_mm.allFinite()) return std::string("a ") + kind.name + " at a point that is not finite";
  }
  if (kind.payload == Payload::index) m.model = read_at<std::uint32_t>(bytes, header_bytes);
  if (kind.payload == Payload::stroke) {
    std::array<Vec3*, 3> points{&m.point_mm, &m.edge_to_mm, &m.move_mm};
    for (std::size_t p = 0; p < 3; ++p)
      for (int c = 0; c < 3; ++c)
        (*points[p])[c] = read_at<double>(bytes, header_bytes + sizeof(double) * (3 * p + static_cast<std::size_t>(c)));
    if (!m.point_mm.allFinite() || !m.edge_to_mm.allFinite() || !m.move_mm.allFinite())
      return std::string("a cut whose blade is not finite");
    if (m.point_mm == m.edge_to_mm) return std::string("a cut whose blade's edge has no length");
    if (m.move_mm.isZero(0.0)) return std::string("a cut whose blade does not move (it sweeps nothing)");
  }
  return m;
}

std::string hand_protocol_json() {
  std::string kinds_json;
  for (const KindInfo& k : kinds)
    kinds_json += std::string(kinds_json.empty() ? "" : ",") + "\"" + k.name +
                  "\":{\"code\":" + std::to_string(static_cast<int>(k.kind)) +
                  ",\"bytes\":" + std::to_string(size_of(k.payload)) + ",\"payload\":\"" + payload_name(k.payload) + "\"}";
  return "{\"header_bytes\":" + std::to_string(header_bytes) + ",\"kinds\":{" + kinds_json + "}}";
}

std::string encode_hand_message(const HandMessage& message) {
  const Payload payload = info(message.kind).payload;
  std::string out(size_of(payload), '\0');
  out[0] = static_cast<char>(message.kind);
  std::memcpy(out.data() + 4, &message.sequence, sizeof(std::uint32_t));
  if (payload == Payload::point)
    for (int c = 0; c < 3; ++c) {
      const double x = message.point_mm[c];
      std::memcpy(out.data() + header_bytes + sizeof(double) * static_cast<std::size_t>(c), &x, sizeof(double));
    }
  if (payload == Payload::index) std::memcpy(out.data() + header_bytes, &message.model, sizeof(std::uint32_t));
  if (payload == Payload::stroke) {
    const std::array<const Vec3*, 3> points{&message.point_mm, &message.edge_to_mm, &message.move_mm};
    for (std::size_t p = 0; p < 3; ++p)
      for (int c = 0; c < 3; ++c) {
        const double x = (*points[p])[c];
        std::memcpy(out.data() + header_bytes + sizeof(double) * (3 * p + static_cast<std::size_t>(c)), &x, sizeof(double));
      }
  }
  return out;
}

}  // namespace roifem::serve
