// Events the Fastrak parser produces (docs/fastrak-protocol.md §3.8): validated poses, plausibility
// errors of framed records, one resync per run of dropped bytes, status replies and
// other '2'-led replies. Values are as sent: tracker frame, tracker units (inches or
// cm per the configuration), degrees; conversion happens in pose_conversion.hpp.
#pragma once

#include <array>
#include <cstdint>

namespace twister::tracker {

// Which orientation items a pose carries (a list may carry several).
struct OrientationItems {
  bool euler = false;       // item 4 / 54
  bool dcm = false;         // all three of items 5, 6, 7 (or 55, 56, 57)
  bool quaternion = false;  // item 11 / 61

  friend bool operator==(const OrientationItems&, const OrientationItems&) = default;
};

// A framed record whose values passed every plausibility check.
struct FastrakPose {
  std::uint8_t station = 0;  // 1..4
  char status = ' ';         // header byte 2: ' ' or a letter (a warning; pose still used)
  bool has_position = false;
  std::array<float, 3> position{};  // x, y, z in tracker units
  OrientationItems has{};
  std::array<float, 3> euler_deg{};   // azimuth, elevation, roll
  std::array<float, 9> dcm{};         // R row-major: items 5, 6, 7 in wire order
  std::array<float, 4> quaternion{};  // q0 (scalar), q1, q2, q3 as sent
  bool has_button = false;
  bool button = false;  // stylus switch (item 16), station 1 only

  friend bool operator==(const FastrakPose&, const FastrakPose&) = default;
};

// Why a framed record was rejected, in the order the checks run (§3.8).
enum class PoseError : std::uint8_t {
  nonfinite,
  position_range,
  angle_range,
  bad_dcm,
  bad_quaternion,
};
const char* pose_error_name(PoseError e);

// The 55-byte status reply to `S` (§3.6).
struct FastrakStatus {
  std::uint8_t station = 0;  // digit in byte 2 (0 if it was not a digit)
  std::uint16_t flags = 0;   // the three hex digits
  bool binary = false;       // flag bit 0
  bool centimetres = false;  // flag bit 1
  bool continuous = false;   // flag bit 3
};

// Any other '2'-led reply line (read-backs, command errors).
struct FastrakReply {
  char station = ' ';       // byte 1 as sent
  char command = ' ';       // byte 2: 'O', 'l', 'X', 'E', ...
  std::uint8_t length = 0;  // bytes including CR LF
  bool is_error = false;    // a command-error record ("2 E*ERROR*...")
  int error_code = 0;       // the EC value of a command error (-1, -2, -3, -4, -5, -99)
};

enum class EventKind : std::uint8_t { pose, error, resync, status, reply };

struct FastrakEvent {
  EventKind kind = EventKind::resync;
  FastrakPose pose{};                      // kind == pose
  std::uint8_t station = 0;                // kind == error: station of the rejected record
  PoseError error = PoseError::nonfinite;  // kind == error
  std::uint32_t dropped = 0;               // kind == resync: bytes in the dropped run
  FastrakStatus status{};                  // kind == status
  FastrakReply reply{};                    // kind == reply
};

}  // namespace twister::tracker
