// PoseContinuity: the last plausibility check of a Fastrak pose, across records. A
// record carries no checksum (docs/fastrak-protocol.md §3.8, §6 pitfall 14): a flipped
// digit, sign or float bit that keeps the record's syntax and value ranges is only
// visible as a jump. A pose farther from its station's last accepted pose than the
// limits allow for the time between them is held back; when the following poses agree
// with it (a chain of `confirmations` more, each consistent with the one before) the
// hand really moved (e.g. a hemisphere flip) and the chain's last pose is accepted, so
// a corrupted record cannot lock a station out and a corrupted first record is replaced
// within a few records. Identical corruption in that many successive records would
// pass.
// Pure: time comes in with each pose. Fixed storage, no heap.
#pragma once

#include <array>
#include <glm/glm.hpp>

#include "twister/ports/clock.hpp"
#include "twister/tracker/fastrak_event.hpp"
#include "twister/tracker/fastrak_wire.hpp"

namespace twister::tracker {

struct ContinuityLimits {
  double max_speed_in_s = 150.0;               // 3.8 m/s; 0 turns the check off
  double position_slack_in = 1.0;              // on top of speed x time
  double max_turn_rate_deg_s = 1000.0;         // 0 turns the orientation check off
  double angle_slack_deg = 10.0;               // on top of rate x time
  ports::TimestampUs min_interval_us = 8'333;  // one 120 Hz cycle: records read in a burst
  int confirmations = 2;                       // agreeing poses that confirm a jump
};

class PoseContinuity {
 public:
  PoseContinuity(const ContinuityLimits& limits, Units units, Format format);

  // true: the pose is consistent with its station's track (or confirms a held-back
  // jump) and becomes the station's reference; false: held back as implausible.
  bool accept(const FastrakPose& pose, ports::TimestampUs now);
  // Forgets every station's track (new stream, after a fault).
  void reset();

 private:
  struct Sample {
    bool valid = false;
    ports::TimestampUs t = 0;
    glm::dvec3 position{0.0};
    bool has_rotation = false;
    glm::dmat3 rotation{1.0};
  };
  Sample sample_of(const FastrakPose& pose, ports::TimestampUs now) const;
  bool consistent(const Sample& from, const Sample& to) const;

  ContinuityLimits limits_;
  double scale_;  // tracker units per inch
  Format format_;
  std::array<Sample, kMaxStations> reference_{};
  std::array<Sample, kMaxStations> held_{};  // last pose of the chain held back
  std::array<int, kMaxStations> chain_{};    // poses in that chain after its first
};

}  // namespace twister::tracker
