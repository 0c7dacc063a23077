// Byte-wise hunting parser of Liberty-family frames (docs/liberty-protocol.md §4), built like
// the Fastrak parser: candidates are examined in place when they fit in the caller's buffer;
// only a candidate cut by the end of a read is copied into pending_. A candidate is rejected
// as early as its header allows (tag, station, command, size), so a bad frame costs one
// dropped byte and the hunt resumes at the next byte that can begin the model's tag.
#include "twister/tracker/liberty_parser.hpp"

#include <algorithm>
#include <bit>
#include <cstring>

#include "fastrak_plausibility.hpp"

namespace twister::tracker {
namespace {

char ch(std::byte b) { return static_cast<char>(b); }

std::uint32_t read_u32(const std::byte* p) {
  std::uint32_t v = 0;
  for (int i = 3; i >= 0; --i) v = (v << 8) | std::to_integer<std::uint32_t>(p[i]);
  return v;
}

float read_f32(const std::byte* p) { return std::bit_cast<float>(read_u32(p)); }

void read_floats(const std::byte* p, float* out, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) out[i] = read_f32(p + 4 * i);
}

}  // namespace

LibertyParser::LibertyParser(const LibertyConfig& config) { configure(config).ignore(); }

Status LibertyParser::configure(const LibertyConfig& config) {
  config_ = config;
  scan_.forget_pending();
  const Status s = validate(config);
  config_ok_ = s.ok();
  for (std::size_t i = 0; i < body_len_.size(); ++i) {
    const LibertyStationConfig& st = config.stations[i];
    body_len_[i] =
        (config_ok_ && st.enabled) ? static_cast<std::uint16_t>(liberty_body_length(st.list)) : 0;
  }
  return s;
}

void LibertyParser::reset() { scan_.reset(); }

bool LibertyParser::can_start(std::byte b) const { return ch(b) == frame_tag(config_.model)[0]; }

LibertyParser::Candidate LibertyParser::examine(const std::byte* p, std::size_t avail,
                                                FastrakEvent& out) const {
  const auto tag = frame_tag(config_.model);
  if (ch(p[0]) != tag[0]) return {Verdict::drop, 1};
  if (avail < 2) return {Verdict::need_more, 2};
  if (ch(p[1]) != tag[1]) return {Verdict::drop, 1};
  Candidate bad{Verdict::drop, 1, true, false};
  if (avail < 3) return {Verdict::need_more, 3};
  const unsigned station = std::to_integer<unsigned>(p[2]);
  if (station < 1 || station > static_cast<unsigned>(kLibertyMaxStations)) return bad;
  const std::size_t body = body_len_[station - 1];
  if (body == 0) return bad;
  if (avail < 4) return {Verdict::need_more, 4};
  const char command = ch(p[3]);
  if (command != kLibertyContinuous && command != kLibertyPoll) return bad;
  if (avail < kLibertyHeaderBytes) return {Verdict::need_more, kLibertyHeaderBytes};
  const std::size_t size = std::to_integer<std::size_t>(p[kLibertySizeOffset]) |
                           (std::to_integer<std::size_t>(p[kLibertySizeOffset + 1]) << 8);
  if (size > liberty_size_value(kLibertyMaxBodyBytes, config_.size_field)) {
    bad.oversize = true;
    return bad;
  }
  if (size != liberty_size_value(body, config_.size_field)) return bad;
  const std::size_t len = kLibertyHeaderBytes + body;
  if (avail < len) return {Verdict::need_more, len};
  return decode_body(p, station, len, out);
}

LibertyParser::Candidate LibertyParser::decode_body(const std::byte* frame, std::size_t station,
                                                    std::size_t len, FastrakEvent& out) const {
  const LibertyStationConfig& st = config_.stations[station - 1];
  FastrakPose pose{};
  pose.station = static_cast<std::uint8_t>(station);
  const auto err = std::to_integer<unsigned>(frame[4]);
  pose.status = (err == 0 || err == ' ') ? ' ' : static_cast<char>(err);
  unsigned dcm_rows = 0;
  const std::byte* q = frame + kLibertyHeaderBytes;
  for (std::size_t i = 0; i < st.list.count; ++i) {
    const LibertyItem item = st.list.items[i];
    switch (item) {
      case LibertyItem::space:
        if (ch(q[0]) != ' ') return {Verdict::drop, 1, true, false};
        break;
      case LibertyItem::crlf:
        if (ch(q[0]) != kCr || ch(q[1]) != kLf) return {Verdict::drop, 1, true, false};
        break;
      case LibertyItem::position:
      case LibertyItem::position_ext:
        pose.has_position = true;
        read_floats(q, pose.position.data(), 3);
        break;
      case LibertyItem::euler:
      case LibertyItem::euler_ext:
        pose.has.euler = true;
        read_floats(q, pose.euler_deg.data(), 3);
        break;
      case LibertyItem::dcm:
        dcm_rows = 7u;
        read_floats(q, pose.dcm.data(), 9);
        break;
      case LibertyItem::quaternion:
        pose.has.quaternion = true;
        read_floats(q, pose.quaternion.data(), 4);
        break;
      case LibertyItem::stylus:
        pose.has_button = true;
        pose.button = read_u32(q) != 0;
        break;
      case LibertyItem::timestamp:
      case LibertyItem::frame_count:
      case LibertyItem::distortion:
        break;
    }
    q += liberty_item_width(item);
  }
  pose.has.dcm = dcm_rows == 7u;
  // The Fastrak's value checks, with the tolerance of IEEE floats.
  FastrakConfig checks{};
  checks.format = Format::binary;
  checks.units = config_.units;
  if (const auto e = internal::check_plausibility(pose, dcm_rows, checks)) {
    out.kind = EventKind::error;
    out.station = pose.station;
    out.error = *e;
  } else {
    out.kind = EventKind::pose;
    out.pose = pose;
  }
  return {Verdict::accept, len};
}

void LibertyParser::reject(const Candidate& c) {
  if (!c.tagged) return;
  ++counters_.bad_frames;
  if (c.oversize) ++counters_.oversize;
}

void LibertyParser::count(const FastrakEvent& ev) {
  if (ev.kind == EventKind::pose) ++counters_.poses;
  if (ev.kind == EventKind::error) ++counters_.errors;
}

// A frame cut off by the end of the stream: its first byte is dropped, and it counts
// as a bad frame when it began with the model's tag.
LibertyParser::Candidate LibertyParser::at_end(const Candidate&, const std::byte* p,
                                               std::size_t n) const {
  const auto tag = frame_tag(config_.model);
  return {Verdict::drop, 1, n >= 2 && ch(p[1]) == tag[1], false};
}

Result<FastrakEvent> LibertyParser::next(std::span<const std::byte>& input) {
  return config_ok_ ? scan_.next(*this, counters_, input) : scan_.drop_all(counters_, input);
}

Result<FastrakEvent> LibertyParser::finish() { return scan_.finish(*this, counters_); }

}  // namespace twister::tracker
