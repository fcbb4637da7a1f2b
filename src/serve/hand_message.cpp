// SPDX-License-Identifier: GPL-3.0-or-later
#include "serve/hand_message.hpp"

#include <cmath>
#include <cstring>

namespace roifem::serve {

namespace {

constexpr std::size_t header_bytes = 8;

std::size_t size_of(HandKind kind) {
  switch (kind) {
    case HandKind::pick:
    case HandKind::target:
      return header_bytes + 3 * sizeof(double);
    case HandKind::model:
    case HandKind::compare:
      return header_bytes + sizeof(std::uint32_t);
    case HandKind::release:
    case HandKind::save:
      return header_bytes;
  }
  return 0;
}

const char* name_of(HandKind kind) {
  switch (kind) {
    case HandKind::pick:
      return "pick";
    case HandKind::target:
      return "target";
    case HandKind::model:
      return "model";
    case HandKind::release:
      return "release";
    case HandKind::save:
      return "save";
    case HandKind::compare:
      return "compare";
  }
  return "?";
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
  const std::uint8_t kind = bytes[0];
  if (kind < 1 || kind > 6)
    return "an unknown kind " + std::to_string(kind) + " (1 pick, 2 target, 3 release, 4 model, 5 save, 6 compare)";
  if (bytes[1] != 0 || bytes[2] != 0 || bytes[3] != 0) return "a header whose padding bytes 1-3 are not zero";
  HandMessage m;
  m.kind = static_cast<HandKind>(kind);
  if (bytes.size() != size_of(m.kind))
    return std::string("a ") + name_of(m.kind) + " message of " + std::to_string(bytes.size()) + " bytes (it has " +
           std::to_string(size_of(m.kind)) + ")";
  m.sequence = read_at<std::uint32_t>(bytes, 4);
  if (m.kind == HandKind::pick || m.kind == HandKind::target) {
    for (int c = 0; c < 3; ++c)
      m.point_mm[c] = read_at<double>(bytes, header_bytes + sizeof(double) * static_cast<std::size_t>(c));
    if (!m.point_mm.allFinite()) return std::string("a ") + name_of(m.kind) + " at a point that is not finite";
  }
  if (m.kind == HandKind::model || m.kind == HandKind::compare) m.model = read_at<std::uint32_t>(bytes, header_bytes);
  return m;
}

std::string encode_hand_message(const HandMessage& message) {
  std::string out(size_of(message.kind), '\0');
  out[0] = static_cast<char>(message.kind);
  std::memcpy(out.data() + 4, &message.sequence, sizeof(std::uint32_t));
  if (message.kind == HandKind::pick || message.kind == HandKind::target)
    for (int c = 0; c < 3; ++c) {
      const double x = message.point_mm[c];
      std::memcpy(out.data() + header_bytes + sizeof(double) * static_cast<std::size_t>(c), &x, sizeof(double));
    }
  if (message.kind == HandKind::model || message.kind == HandKind::compare)
    std::memcpy(out.data() + header_bytes, &message.model, sizeof(std::uint32_t));
  return out;
}

}  // namespace roifem::serve
