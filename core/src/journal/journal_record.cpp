#include "twister/journal/journal_record.hpp"

#include <bit>
#include <cmath>

#include "twister/base/checksum.hpp"
#include "twister/base/internal/byte_cursor.hpp"

namespace twister::journal {
namespace {

constexpr std::uint8_t kMethodCount = 3;
constexpr std::size_t kPoseBytes = std::size_t{9} * 8;
constexpr std::size_t kStrokeFixedBytes = 4 + 1 + 1 + 2 + 8;
constexpr std::size_t kMoveBytes = 4 + 1 + 2 * kPoseBytes;
constexpr std::size_t kSequenceOnlyBytes = 4;
constexpr std::size_t kRefinedTailBytes = 1 + 8;  // long_turns, refine_threshold_m
// long_turns, refine_threshold_m, refine_local, symmetry kind, mirrors, axis, order
constexpr std::size_t kSymmetricTailBytes = 1 + 8 + 1 + 4;
static_assert(kStrokeFixedBytes + 4 * kPoseBytes + kSymmetricTailBytes <= kMaxPayloadBytes);

using twister::internal::ByteReader;
using twister::internal::ByteWriter;

// The pose's edge: origin, U, V on the wire; W = U x V when read (as_stored).
void write_pose(ByteWriter& w, const Pose& p) {
  w.vec(p.origin);
  w.vec(p.u);
  w.vec(p.v);
}

Pose read_pose(ByteReader& r) {
  Pose p;
  p.origin = r.vec();
  p.u = r.vec();
  p.v = r.vec();
  return as_stored(p);
}

// Version 2 strokes end with the long_turns byte, version 3 with it and the threshold.
std::size_t stroke_bytes(std::uint8_t hand_mask, std::uint8_t version) {
  const auto hands = static_cast<std::size_t>(std::popcount(static_cast<unsigned>(hand_mask)));
  const std::size_t tail =
      version == kRecordVersionSymmetric ? kSymmetricTailBytes
      : version == kRecordVersionRefined || version == kRecordVersionRefinedLocal
          ? kRefinedTailBytes
      : version == kRecordVersionLongTurns ? 1
                                           : 0;
  return kStrokeFixedBytes + 2 * hands * kPoseBytes + tail;
}

std::uint8_t record_version(const JournalRecord& r) {
  if (r.type != RecordType::stroke) return kRecordVersion;
  if (r.stroke.symmetry.kind != 0) return kRecordVersionSymmetric;
  if (r.stroke.refine_threshold_m > 0.0) {
    return r.stroke.refine_local ? kRecordVersionRefinedLocal : kRecordVersionRefined;
  }
  return r.stroke.long_turns != 0 ? kRecordVersionLongTurns : kRecordVersion;
}

bool valid_threshold(double t) { return std::isfinite(t) && t >= 0.0; }

std::size_t payload_bytes(const JournalRecord& r) {
  switch (r.type) {
    case RecordType::stroke:
      return stroke_bytes(r.stroke.hand_mask, record_version(r));
    case RecordType::object_move:
      return kMoveBytes;
    case RecordType::undo:
    case RecordType::redo:
      return kSequenceOnlyBytes;
  }
  return 0;
}

bool finite(const Pose& p) {
  for (const glm::dvec3* v : {&p.origin, &p.u, &p.v}) {
    if (!std::isfinite(v->x) || !std::isfinite(v->y) || !std::isfinite(v->z)) return false;
  }
  return true;
}

bool valid_mask(std::uint8_t mask) { return mask >= 1 && mask <= 3; }

bool valid_turns(std::uint8_t long_turns, std::uint8_t hand_mask) {
  return (long_turns & ~hand_mask) == 0;
}

// Version 5's tail (after long_turns): threshold, local, the group (not none).
bool read_symmetric_tail(ByteReader& in, StrokeRecord& s) {
  s.refine_threshold_m = in.f64();
  const std::uint8_t local = in.u8();
  s.symmetry.kind = in.u8();
  s.symmetry.mirrors = in.u8();
  s.symmetry.axis = in.u8();
  s.symmetry.order = in.u8();
  s.refine_local = local == 1;
  return valid_threshold(s.refine_threshold_m) && local <= 1 &&
         (local == 0 || s.refine_threshold_m > 0.0) && s.symmetry.kind != 0 &&
         valid_symmetry(s.symmetry);
}

// The versioned end of a stroke. Canonical: version 2 only when some hand turned the
// long way, version 3 only with a threshold, version 5 only with a symmetry.
bool read_stroke_tail(ByteReader& in, std::uint8_t version, StrokeRecord& s) {
  if (version == kRecordVersion) return true;
  s.long_turns = in.u8();
  if ((version == kRecordVersionLongTurns && s.long_turns == 0) ||
      !valid_turns(s.long_turns, s.hand_mask)) {
    return false;
  }
  if (version == kRecordVersionSymmetric) return read_symmetric_tail(in, s);
  if (version != kRecordVersionRefined && version != kRecordVersionRefinedLocal) return true;
  s.refine_local = version == kRecordVersionRefinedLocal;
  s.refine_threshold_m = in.f64();
  return valid_threshold(s.refine_threshold_m) && s.refine_threshold_m > 0.0;
}

}  // namespace

bool valid_symmetry(const StrokeSymmetry& s) {
  switch (s.kind) {
    case 0:
      return s.mirrors == 0 && s.axis == 0 && s.order == 0;
    case 1:
      return s.mirrors >= 1 && s.mirrors <= 7 && s.axis == 0 && s.order == 0;
    case 2:
    case 3:
      return s.mirrors == 0 && s.axis <= 2 && s.order >= 2 && s.order <= 12;
    default:
      return false;
  }
}

Result<std::size_t> encode_record(const JournalRecord& r, std::span<std::byte> out) {
  if (r.type == RecordType::stroke &&
      (!valid_mask(r.stroke.hand_mask) || r.stroke.method >= kMethodCount ||
       !valid_turns(r.stroke.long_turns, r.stroke.hand_mask) ||
       !valid_threshold(r.stroke.refine_threshold_m) ||
       (r.stroke.refine_local && !(r.stroke.refine_threshold_m > 0.0)) ||
       !valid_symmetry(r.stroke.symmetry))) {
    return StatusCode::invalid_argument;
  }
  if (r.type == RecordType::object_move && r.move.hand > 1) return StatusCode::invalid_argument;
  const std::size_t payload = payload_bytes(r);
  if (payload == 0) return StatusCode::invalid_argument;
  const std::size_t total = kRecordHeaderBytes + payload + kRecordCrcBytes;
  if (out.size() < total) return StatusCode::resource_exhausted;

  ByteWriter w(out);
  w.u32(static_cast<std::uint32_t>(payload));
  w.u8(record_version(r));
  w.u8(static_cast<std::uint8_t>(r.type));
  w.u16(0);
  w.u32(r.sequence);
  switch (r.type) {
    case RecordType::stroke:
      w.u8(r.stroke.method);
      w.u8(r.stroke.hand_mask);
      w.u16(r.stroke.chain_step);
      w.f64(r.stroke.radius_m);
      for (std::size_t h = 0; h < 2; ++h) {
        if ((r.stroke.hand_mask & (1u << h)) == 0) continue;
        write_pose(w, r.stroke.start[h]);
        write_pose(w, r.stroke.end[h]);
      }
      if (record_version(r) != kRecordVersion) w.u8(r.stroke.long_turns);
      if (record_version(r) == kRecordVersionSymmetric) {
        w.f64(r.stroke.refine_threshold_m);
        w.u8(r.stroke.refine_local ? 1 : 0);
        w.u8(r.stroke.symmetry.kind);
        w.u8(r.stroke.symmetry.mirrors);
        w.u8(r.stroke.symmetry.axis);
        w.u8(r.stroke.symmetry.order);
      } else if (r.stroke.refine_threshold_m > 0.0) {
        w.f64(r.stroke.refine_threshold_m);
      }
      break;
    case RecordType::object_move:
      w.u8(r.move.hand);
      write_pose(w, r.move.object_before);
      write_pose(w, r.move.object_after);
      break;
    case RecordType::undo:
    case RecordType::redo:
      break;
  }
  w.u32(crc32(out.first(w.size())));
  return total;
}

Result<JournalRecord> decode_payload(std::uint8_t version, std::uint8_t type,
                                     std::span<const std::byte> payload) {
  const bool stroke = type == static_cast<std::uint8_t>(RecordType::stroke);
  if (version != kRecordVersion &&
      !(stroke && (version == kRecordVersionLongTurns || version == kRecordVersionRefined ||
                   version == kRecordVersionRefinedLocal || version == kRecordVersionSymmetric))) {
    return StatusCode::data_loss;
  }
  if (payload.size() < kSequenceOnlyBytes) return StatusCode::data_loss;
  JournalRecord r;
  ByteReader in(payload);
  r.sequence = in.u32();
  switch (type) {
    case static_cast<std::uint8_t>(RecordType::stroke): {
      r.type = RecordType::stroke;
      if (payload.size() < kStrokeFixedBytes) return StatusCode::data_loss;
      r.stroke.method = in.u8();
      r.stroke.hand_mask = in.u8();
      if (!valid_mask(r.stroke.hand_mask) || r.stroke.method >= kMethodCount ||
          payload.size() != stroke_bytes(r.stroke.hand_mask, version)) {
        return StatusCode::data_loss;
      }
      r.stroke.chain_step = in.u16();
      r.stroke.radius_m = in.f64();
      if (!std::isfinite(r.stroke.radius_m) || r.stroke.radius_m <= 0.0)
        return StatusCode::data_loss;
      for (std::size_t h = 0; h < 2; ++h) {
        if ((r.stroke.hand_mask & (1u << h)) == 0) continue;
        r.stroke.start[h] = read_pose(in);
        r.stroke.end[h] = read_pose(in);
        if (!finite(r.stroke.start[h]) || !finite(r.stroke.end[h])) return StatusCode::data_loss;
      }
      if (!read_stroke_tail(in, version, r.stroke)) return StatusCode::data_loss;
      return r;
    }
    case static_cast<std::uint8_t>(RecordType::object_move):
      r.type = RecordType::object_move;
      if (payload.size() != kMoveBytes) return StatusCode::data_loss;
      r.move.hand = in.u8();
      r.move.object_before = read_pose(in);
      r.move.object_after = read_pose(in);
      if (r.move.hand > 1 || !finite(r.move.object_before) || !finite(r.move.object_after)) {
        return StatusCode::data_loss;
      }
      return r;
    case static_cast<std::uint8_t>(RecordType::undo):
    case static_cast<std::uint8_t>(RecordType::redo):
      r.type = static_cast<RecordType>(type);
      if (payload.size() != kSequenceOnlyBytes) return StatusCode::data_loss;
      return r;
    default:
      return StatusCode::data_loss;
  }
}

}  // namespace twister::journal
