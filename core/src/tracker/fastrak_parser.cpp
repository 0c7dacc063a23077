// Byte-wise hunting parser (docs/fastrak-protocol.md §3.7/§3.8). Candidates are examined in place
// in the caller's buffer when they fit; only a candidate cut by the end of a read is copied into
// pending_, so the common case costs no copy.
#include "twister/tracker/fastrak_parser.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "fastrak_fields.hpp"
#include "fastrak_plausibility.hpp"
#include "twister/base/internal/byte_cursor.hpp"

namespace twister::tracker {

using internal::ch;
using internal::check_plausibility;
using internal::is_digit;
using internal::is_letter;

const char* pose_error_name(PoseError e) {
  switch (e) {
    case PoseError::nonfinite:
      return "nonfinite";
    case PoseError::position_range:
      return "position_range";
    case PoseError::angle_range:
      return "angle_range";
    case PoseError::bad_dcm:
      return "bad_dcm";
    case PoseError::bad_quaternion:
      return "bad_quaternion";
  }
  return "unknown";
}

namespace {

// Reads the `n` numbers of a number item into `out`; false on a malformed field.
bool read_numbers(const std::byte* p, const FastrakConfig& config, Item item, std::size_t n,
                  float* out) {
  const Format format = config.format;
  if (format == Format::binary16) {
    const double scale = internal::packed16_scale(item, config.units);
    for (std::size_t i = 0; i < n; ++i) out[i] = internal::read_packed16(p + 2 * i, scale);
    return true;
  }
  if (format == Format::binary) {
    twister::internal::ByteReader r({p, 4 * n});
    for (std::size_t i = 0; i < n; ++i) out[i] = r.f32();
    return true;
  }
  for (std::size_t i = 0; i < n; ++i) {
    const bool ok =
        internal::is_extended(item)
            ? internal::parse_extended(p + 13 * i, out[i])
            : internal::parse_fixed(p + 7 * i, 7, internal::ascii_decimals(item), out[i]);
    if (!ok) return false;
  }
  return true;
}

}  // namespace

FastrakParser::FastrakParser(const FastrakConfig& config) { configure(config).ignore(); }

Status FastrakParser::configure(const FastrakConfig& config) {
  config_ = config;
  scan_.forget_pending();
  const Status s = validate(config);
  config_ok_ = s.ok();
  for (std::size_t i = 0; i < record_len_.size(); ++i) {
    const ReceiverConfig& st = config.stations[i];
    record_len_[i] = (config_ok_ && st.enabled)
                         ? record_length(st.list, config.format, config.ascii_stylus_width)
                         : 0;
  }
  return s;
}

void FastrakParser::reset() { scan_.reset(); }

FastrakParser::Candidate FastrakParser::examine(const std::byte* p, std::size_t avail,
                                                FastrakEvent& out) const {
  if (ch(p[0]) == kReplyType) return examine_reply(p, avail, out);
  if (can_start(p[0])) return examine_record(p, avail, out);
  return {Verdict::drop, 1};
}

bool FastrakParser::can_start(std::byte b) const {
  if (ch(b) == kReplyType) return true;
  return config_.format == Format::binary16 ? std::to_integer<unsigned>(b) == kPacked16Start
                                            : ch(b) == kRecordType;
}

FastrakParser::Candidate FastrakParser::examine_record(const std::byte* p, std::size_t avail,
                                                       FastrakEvent& out) const {
  // In binary16 wire bytes 1 and 2 are also the station digit and the status: their
  // high bits (0 for ASCII) travel in the group's eighth byte, checked after unpacking.
  if (avail < 2) return {Verdict::need_more, 2};
  const int station = ch(p[1]) - '1';
  if (station < 0 || station >= kMaxStations) return {Verdict::drop, 1};
  const std::size_t len = record_len_[static_cast<std::size_t>(station)];
  if (len == 0) return {Verdict::drop, 1};
  if (avail < 3) return {Verdict::need_more, 3};
  const char status = ch(p[2]);
  if (status != ' ' && !is_letter(status)) return {Verdict::drop, 1};
  if (avail < len) return {Verdict::need_more, len};
  if (config_.format != Format::binary16) {
    return decode_record(p, static_cast<std::size_t>(station), len, out);
  }
  std::array<std::byte, kMaxRecordBytes> rec{};
  // A byte with bit 7 set inside the record means lost sync (§5).
  if (!unpack16(p, len, rec.data())) return {Verdict::drop, 1};
  if (ch(rec[0]) != kRecordType || rec[1] != p[1] || rec[2] != p[2]) return {Verdict::drop, 1};
  return decode_record(rec.data(), static_cast<std::size_t>(station), len, out);
}

FastrakParser::Candidate FastrakParser::decode_record(const std::byte* rec, std::size_t station,
                                                      std::size_t consumed,
                                                      FastrakEvent& out) const {
  const ReceiverConfig& st = config_.stations[station];
  FastrakPose pose{};
  pose.station = static_cast<std::uint8_t>(station + 1);
  pose.status = ch(rec[2]);
  unsigned dcm_rows = 0;
  std::size_t off = kHeaderBytes;
  for (std::size_t i = 0; i < st.list.count; ++i) {
    const Item item = st.list.items[i];
    if (!read_item(item, rec + off, pose, dcm_rows)) return {Verdict::drop, 1};
    off += item_width(item, config_.format, config_.ascii_stylus_width);
  }
  pose.has.dcm = dcm_rows == 7u;

  if (const auto err = check_plausibility(pose, dcm_rows, config_)) {
    out.kind = EventKind::error;
    out.station = pose.station;
    out.error = *err;
  } else {
    out.kind = EventKind::pose;
    out.pose = pose;
  }
  return {Verdict::accept, consumed};
}

bool FastrakParser::read_item(Item item, const std::byte* q, FastrakPose& pose,
                              unsigned& dcm_rows) const {
  const Format fmt = config_.format;
  switch (item) {
    case Item::space:
      return ch(q[0]) == ' ';
    case Item::crlf:
      return ch(q[0]) == kCr && ch(q[1]) == kLf;
    case Item::position:
    case Item::position_ext:
      pose.has_position = true;
      return read_numbers(q, config_, item, 3, pose.position.data());
    case Item::euler:
    case Item::euler_ext:
      pose.has.euler = true;
      return read_numbers(q, config_, item, 3, pose.euler_deg.data());
    case Item::dcm_x:
    case Item::dcm_y:
    case Item::dcm_z:
    case Item::dcm_x_ext:
    case Item::dcm_y_ext:
    case Item::dcm_z_ext: {
      const std::size_t row = internal::dcm_row(item);
      dcm_rows |= 1u << static_cast<unsigned>(row);
      return read_numbers(q, config_, item, 3, pose.dcm.data() + 3 * row);
    }
    case Item::quaternion:
    case Item::quaternion_ext:
      pose.has.quaternion = true;
      return read_numbers(q, config_, item, 4, pose.quaternion.data());
    case Item::stylus:
    case Item::stylus_ext: {
      // Only the last byte carries the state; the first of two is unconfirmed (§3.5).
      const std::size_t w = fmt == Format::ascii ? config_.ascii_stylus_width : 2;
      const char s = ch(q[w - 1]);
      pose.has_button = true;
      pose.button = s == '1';
      return s == '0' || s == '1';
    }
  }
  return false;
}

void FastrakParser::count(const FastrakEvent& ev) {
  switch (ev.kind) {
    case EventKind::pose:
      ++counters_.poses;
      break;
    case EventKind::error:
      ++counters_.errors;
      break;
    case EventKind::status:
    case EventKind::reply:
      ++counters_.replies;
      break;
    case EventKind::resync:
      break;
  }
}

// A record or reply cut off by the end of the stream: its first byte is dropped.
FastrakParser::Candidate FastrakParser::at_end(const Candidate&, const std::byte*,
                                               std::size_t) const {
  return {Verdict::drop, 1};
}

Result<FastrakEvent> FastrakParser::next(std::span<const std::byte>& input) {
  return config_ok_ ? scan_.next(*this, counters_, input) : scan_.drop_all(counters_, input);
}

Result<FastrakEvent> FastrakParser::finish() { return scan_.finish(*this, counters_); }

}  // namespace twister::tracker
