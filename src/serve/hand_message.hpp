// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// What the page sends the server (`roifem serve`): small binary WebSocket frames, little-endian.
///   byte 0      kind: 1 pick, 2 target, 3 release, 4 model, 5 save the hand's path, 6 compare, 7 cut,
///               8 make the cut model whole again
///   bytes 1-3   zero
///   bytes 4-7   uint32 sequence number (the page's; frames echo the last one applied)
///   then        pick, target: three float64, a point in mm (32 bytes in all)
///               model: uint32, the model's index; compare: uint32, 1 on, 0 off (12 bytes in all)
///               release, save, whole: nothing (8 bytes in all)
///               cut: nine float64, a scalpel's stroke as a [[cut]] states it (mm): the blade's edge
///               from, its edge to, and the straight move it sweeps (80 bytes in all)
/// Anything else (another size, kind or padding, a point that is not finite, a blade with no edge
/// or no move) is refused with the reason, before it reaches the physics. The table of kinds in
/// hand_message.cpp is the protocol's one source: the page builds its frames from the table the
/// server sends in its hello (hand_protocol_json), not from a copy of its own.
#include <cstdint>
#include <span>
#include <string>
#include <variant>
#include <vector>

#include "common/types.hpp"

namespace roifem::serve {

enum class HandKind : std::uint8_t { pick = 1, target = 2, release = 3, model = 4, save = 5, compare = 6, cut = 7, whole = 8 };

struct HandMessage {
  HandKind kind = HandKind::target;
  std::uint32_t sequence = 0;
  Vec3 point_mm = Vec3::Zero();                            ///< pick, target; cut: the blade's edge from
  std::uint32_t model = 0;                                 ///< model: its index; compare: 1 on, 0 off
  Vec3 edge_to_mm = Vec3::Zero(), move_mm = Vec3::Zero();  ///< cut: the edge's other end, the move it sweeps
  /// cut: the tetrahedra its blade crosses, ascending (the server's, from the mesh: not on the wire)
  std::vector<Index> crossed;
};

/// The message, or why it is refused (a sentence for the server's log and the page).
std::variant<HandMessage, std::string> decode_hand_message(std::span<const std::uint8_t> bytes);
/// The frame decode_hand_message reads back (the page's encoding; tests).
std::string encode_hand_message(const HandMessage& message);
/// The kinds as the page builds them, from the same table: {"header_bytes":8,"kinds":{"pick":
/// {"code":1,"bytes":32,"payload":"point"}, ...}}; payloads: "point" (three float64 from byte 8),
/// "index" (a uint32 at byte 8), "stroke" (nine float64 from byte 8), "none".
std::string hand_protocol_json();

}  // namespace roifem::serve
