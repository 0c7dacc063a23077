// JournalRecord: one entry of the stroke journal, and its byte encoding.
//
// File: a header ("TWJL", u32 format version, ...), then records; the file formats
// (version 1, and version 2 whose records carry the journal's identity and whose
// sequences are checked) are in journal_format.hpp. A version 1 record:
//   u32 payload_length | u8 record_version | u8 type | u16 reserved (0)
//   payload (payload_length bytes) | u32 CRC-32 over header and payload
// All integers little-endian; reals are IEEE float64 bit patterns, so replay sees
// exactly the numbers the live session used. Layout details: docs/interaction.md.
// Record version 1 for every record, except a stroke with a hand that turned past a
// half turn (long_turns != 0): version 2, whose payload ends with one more byte (the
// long_turns mask). A reader that only knows version 1 refuses such a record rather
// than replaying the turn the short way round. A stroke whose commit refined the
// mesh (refine_threshold_m > 0) is version 3: the long_turns byte (0 allowed), then
// the threshold (f64, metres), so a replay refines exactly as the live commit did
// whatever the station's configuration is at replay time. Version 4 is version 3
// refined over the stroke's region only (refine_local). Versions 1 and 2 read as
// not refined, so journals written before refinement replay as they did. A stroke
// under a symmetry group (docs/math.md §11; symmetry.kind != 0) is version 5: the
// long_turns byte, the threshold (f64, 0: not refined), a refine_local byte (0 or 1,
// 0 without a threshold), then the group: kind, mirrors, axis, order (one byte each,
// math::SymmetrySpec's canonical form). Strokes without symmetry keep versions 1-4
// byte for byte, so older journals replay unchanged and older readers refuse only
// the symmetric strokes.
// Poses are in the object frame of the time (metres; U, V unit axes, W = U x V).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <span>

#include "twister/base/pose.hpp"
#include "twister/base/result.hpp"

namespace twister::journal {

inline constexpr std::array<std::byte, 4> kFileMagic{std::byte{'T'}, std::byte{'W'}, std::byte{'J'},
                                                     std::byte{'L'}};
inline constexpr std::uint8_t kRecordVersion = 1;
// A stroke record with long_turns != 0 (and no refinement).
inline constexpr std::uint8_t kRecordVersionLongTurns = 2;
// A stroke record whose commit refined the mesh.
inline constexpr std::uint8_t kRecordVersionRefined = 3;
// A stroke refined over the triangles its weights touch (refine_local): version 3's
// payload, refined by mesh::MeshRefiner::refine_around at replay (docs/refinement.md).
inline constexpr std::uint8_t kRecordVersionRefinedLocal = 4;
// A stroke under a symmetry group (any refinement, any turns).
inline constexpr std::uint8_t kRecordVersionSymmetric = 5;
inline constexpr std::size_t kRecordHeaderBytes = 8;
inline constexpr std::size_t kRecordCrcBytes = 4;
inline constexpr std::size_t kMaxPayloadBytes = 512;
// Version 2 records carry the journal's identity after the record header.
inline constexpr std::size_t kRecordIdBytes = 4;
inline constexpr std::size_t kMaxRecordBytes =
    kRecordHeaderBytes + kRecordIdBytes + kMaxPayloadBytes + kRecordCrcBytes;

enum class RecordType : std::uint8_t {
  stroke = 1,       // a committed warp (release, freeze step, or hand-set change)
  object_move = 2,  // a committed rigid move of the whole object
  undo = 3,
  redo = 4,
};

// A record's poses are twister::Pose (origin in metres). The journal stores origin, U
// and V; W is rebuilt as U x V when a record is read, so a record round-trips exactly
// when its poses are as_stored() ones.
inline Pose as_stored(const Pose& p) { return {p.origin, p.u, p.v, glm::cross(p.u, p.v)}; }

// A stroke's symmetry group (math::SymmetrySpec as bytes; kind 0: none, 1: mirrors with
// the plane bits 1 x, 2 y, 4 z; 2: n-fold rotation, 3: with a mirror, about axis 0..2,
// order 2..12). Unused fields are 0.
struct StrokeSymmetry {
  std::uint8_t kind = 0;
  std::uint8_t mirrors = 0;
  std::uint8_t axis = 0;
  std::uint8_t order = 0;
  friend bool operator==(const StrokeSymmetry&, const StrokeSymmetry&) = default;
};

// Whether `s` names a group in the canonical form (kind 0 with every field 0 included).
bool valid_symmetry(const StrokeSymmetry& s);

struct StrokeRecord {
  std::uint8_t method = 0;       // math::WarpMethod as a number
  std::uint8_t hand_mask = 0;    // bit h set: hand h took part (1, 2 or 3)
  std::uint16_t chain_step = 0;  // 0: first selection; k > 0: k-th freeze step, same weights
  // Bit h: hand h's screw turns the long way round (past a half turn: the minimal screw
  // of its poses, math::long_way_round). A subset of hand_mask; 0 in version 1.
  std::uint8_t long_turns = 0;
  double radius_m = 0.0;
  // > 0: the commit refined the mesh until every edge's midpoint error under the warp
  // was at most this (metres; version 3). 0: not refined (versions 1 and 2). With
  // chain_step > 0: the commit that ended a clutch chain, refined under the chain's
  // combined warp (docs/refinement.md "Clutch chains").
  double refine_threshold_m = 0.0;
  // With a threshold: refined over the triangles the stroke's weights touch and their
  // conforming closure (version 4) rather than the whole mesh (version 3).
  bool refine_local = false;
  StrokeSymmetry symmetry{};    // kind != 0: version 5
  std::array<Pose, 2> start{};  // per hand, meaningful where hand_mask says
  std::array<Pose, 2> end{};
  friend bool operator==(const StrokeRecord&, const StrokeRecord&) = default;
};

struct ObjectMoveRecord {
  std::uint8_t hand = 0;
  Pose object_before{};  // object pose in the world before and after the move
  Pose object_after{};
  friend bool operator==(const ObjectMoveRecord&, const ObjectMoveRecord&) = default;
};

struct JournalRecord {
  RecordType type = RecordType::stroke;
  std::uint32_t sequence = 0;  // increases by one per record
  StrokeRecord stroke{};       // type stroke
  ObjectMoveRecord move{};     // type object_move
  friend bool operator==(const JournalRecord&, const JournalRecord&) = default;
};

// Writes the whole record (header, payload, CRC) into out in the version 1 layout;
// returns its size (encode_record(record, out, format) in journal_format.hpp: any format).
// invalid_argument: the record breaks the rules above (hand_mask 0, method > 2,
// long_turns outside hand_mask, refine_threshold_m negative or not finite).
// resource_exhausted: out is smaller than the encoded record.
Result<std::size_t> encode_record(const JournalRecord& record, std::span<std::byte> out);

// Decodes a payload whose header and CRC have already been checked.
// data_loss: wrong version (2 only for a stroke with long turns, 3 only for a refined
// stroke), unknown type, wrong length for the type and version, or a field
// out of its range (the record must not be applied).
Result<JournalRecord> decode_payload(std::uint8_t version, std::uint8_t type,
                                     std::span<const std::byte> payload);

}  // namespace twister::journal
