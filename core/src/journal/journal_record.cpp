#include "twister/journal/journal_record.hpp"

#include <bit>
#include <cmath>

#include "twister/journal/crc32.hpp"

namespace twister::journal {
namespace {

constexpr std::uint8_t kMethodCount = 3;
constexpr std::size_t kPoseBytes = std::size_t{9} * 8;
constexpr std::size_t kStrokeFixedBytes = 4 + 1 + 1 + 2 + 8;
constexpr std::size_t kMoveBytes = 4 + 1 + 2 * kPoseBytes;
constexpr std::size_t kSequenceOnlyBytes = 4;
static_assert(kStrokeFixedBytes + 4 * kPoseBytes <= kMaxPayloadBytes);

// Little-endian writer over a span that is known to be large enough.
class Writer {
 public:
  explicit Writer(std::span<std::byte> out) : out_(out) {}
  void u8(std::uint8_t v) { out_[pos_++] = std::byte{v}; }
  void u16(std::uint16_t v) { uint(v, 2); }
  void u32(std::uint32_t v) { uint(v, 4); }
  void f64(double v) { uint(std::bit_cast<std::uint64_t>(v), 8); }
  void vec(const glm::dvec3& v) {
    f64(v.x);
    f64(v.y);
    f64(v.z);
  }
  void pose(const JournalPose& p) {
    vec(p.origin_m);
    vec(p.u);
    vec(p.v);
  }
  std::size_t pos() const { return pos_; }

 private:
  void uint(std::uint64_t v, int bytes) {
    for (int i = 0; i < bytes; ++i)
      out_[pos_++] = std::byte(static_cast<std::uint8_t>(v >> (8 * i)));
  }
  std::span<std::byte> out_;
  std::size_t pos_ = 0;
};

// Little-endian reader over a span whose length was checked against the type.
class Reader {
 public:
  explicit Reader(std::span<const std::byte> in) : in_(in) {}
  std::uint8_t u8() { return static_cast<std::uint8_t>(uint(1)); }
  std::uint16_t u16() { return static_cast<std::uint16_t>(uint(2)); }
  std::uint32_t u32() { return static_cast<std::uint32_t>(uint(4)); }
  double f64() { return std::bit_cast<double>(uint(8)); }
  glm::dvec3 vec() {
    const double x = f64();
    const double y = f64();
    return {x, y, f64()};
  }
  JournalPose pose() {
    JournalPose p;
    p.origin_m = vec();
    p.u = vec();
    p.v = vec();
    return p;
  }

 private:
  std::uint64_t uint(int bytes) {
    std::uint64_t v = 0;
    for (int i = 0; i < bytes; ++i)
      v |= std::uint64_t(static_cast<std::uint8_t>(in_[pos_++])) << (8 * i);
    return v;
  }
  std::span<const std::byte> in_;
  std::size_t pos_ = 0;
};

std::size_t stroke_bytes(std::uint8_t hand_mask) {
  const auto hands = static_cast<std::size_t>(std::popcount(static_cast<unsigned>(hand_mask)));
  return kStrokeFixedBytes + 2 * hands * kPoseBytes;
}

std::size_t payload_bytes(const JournalRecord& r) {
  switch (r.type) {
    case RecordType::stroke:
      return stroke_bytes(r.stroke.hand_mask);
    case RecordType::object_move:
      return kMoveBytes;
    case RecordType::undo:
    case RecordType::redo:
      return kSequenceOnlyBytes;
  }
  return 0;
}

bool finite(const JournalPose& p) {
  for (const glm::dvec3* v : {&p.origin_m, &p.u, &p.v}) {
    if (!std::isfinite(v->x) || !std::isfinite(v->y) || !std::isfinite(v->z)) return false;
  }
  return true;
}

bool valid_mask(std::uint8_t mask) { return mask >= 1 && mask <= 3; }

}  // namespace

Result<std::size_t> encode_record(const JournalRecord& r, std::span<std::byte> out) {
  if (r.type == RecordType::stroke &&
      (!valid_mask(r.stroke.hand_mask) || r.stroke.method >= kMethodCount)) {
    return StatusCode::invalid_argument;
  }
  if (r.type == RecordType::object_move && r.move.hand > 1) return StatusCode::invalid_argument;
  const std::size_t payload = payload_bytes(r);
  if (payload == 0) return StatusCode::invalid_argument;
  const std::size_t total = kRecordHeaderBytes + payload + kRecordCrcBytes;
  if (out.size() < total) return StatusCode::resource_exhausted;

  Writer w(out);
  w.u32(static_cast<std::uint32_t>(payload));
  w.u8(kRecordVersion);
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
        w.pose(r.stroke.start[h]);
        w.pose(r.stroke.end[h]);
      }
      break;
    case RecordType::object_move:
      w.u8(r.move.hand);
      w.pose(r.move.object_before);
      w.pose(r.move.object_after);
      break;
    case RecordType::undo:
    case RecordType::redo:
      break;
  }
  w.u32(crc32(out.first(w.pos())));
  return total;
}

Result<JournalRecord> decode_payload(std::uint8_t version, std::uint8_t type,
                                     std::span<const std::byte> payload) {
  if (version != kRecordVersion) return StatusCode::data_loss;
  if (payload.size() < kSequenceOnlyBytes) return StatusCode::data_loss;
  JournalRecord r;
  Reader in(payload);
  r.sequence = in.u32();
  switch (type) {
    case static_cast<std::uint8_t>(RecordType::stroke): {
      r.type = RecordType::stroke;
      if (payload.size() < kStrokeFixedBytes) return StatusCode::data_loss;
      r.stroke.method = in.u8();
      r.stroke.hand_mask = in.u8();
      if (!valid_mask(r.stroke.hand_mask) || r.stroke.method >= kMethodCount ||
          payload.size() != stroke_bytes(r.stroke.hand_mask)) {
        return StatusCode::data_loss;
      }
      r.stroke.chain_step = in.u16();
      r.stroke.radius_m = in.f64();
      if (!std::isfinite(r.stroke.radius_m) || r.stroke.radius_m <= 0.0)
        return StatusCode::data_loss;
      for (std::size_t h = 0; h < 2; ++h) {
        if ((r.stroke.hand_mask & (1u << h)) == 0) continue;
        r.stroke.start[h] = in.pose();
        r.stroke.end[h] = in.pose();
        if (!finite(r.stroke.start[h]) || !finite(r.stroke.end[h])) return StatusCode::data_loss;
      }
      return r;
    }
    case static_cast<std::uint8_t>(RecordType::object_move):
      r.type = RecordType::object_move;
      if (payload.size() != kMoveBytes) return StatusCode::data_loss;
      r.move.hand = in.u8();
      r.move.object_before = in.pose();
      r.move.object_after = in.pose();
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
