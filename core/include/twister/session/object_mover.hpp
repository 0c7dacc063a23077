// ObjectMover: the rigid move of the whole object with one hand. begin() notes the
// hand's and the object's poses; while the move is open the object follows the
// hand's motion since then (only the object pose in SessionPoses changes, never the
// mesh); commit() keeps the pose the hand's last valid pose gives, cancel() puts the
// object back where it was. Poses in the world frame. Recording the move (undo entry,
// journal record) is the caller's: see SessionHistory::commit_move.
// No allocation; not thread-safe.
#pragma once

#include <cstdint>

#include "twister/base/result.hpp"
#include "twister/math/frame.hpp"
#include "twister/session/session_poses.hpp"

namespace twister::session {

// A finished move: the object pose before and after (world).
struct ObjectMove {
  std::uint8_t hand = 0;
  math::Frame before{};
  math::Frame after{};
};

class ObjectMover {
 public:
  // `poses` must outlive the mover.
  explicit ObjectMover(SessionPoses& poses) : poses_(poses) {}

  // Starts moving the object with `hand` (< kHandCount) from its current poses.
  void begin(std::uint8_t hand);
  // Per step: the object follows the hand while the move is open and the hand is
  // tracked (a lost hand holds the object where it was last seen).
  void follow();
  // Ends the move at the hand's last valid pose.
  // failed_precondition: no move open.
  Result<ObjectMove> commit();
  // Ends the move and puts the object back. False: no move was open.
  bool cancel();

  bool moving() const { return moving_; }
  std::uint8_t hand() const { return hand_; }

 private:
  math::Frame moved_object() const;

  SessionPoses& poses_;
  bool moving_ = false;
  std::uint8_t hand_ = 0;
  math::Frame hand_start_{};    // world
  math::Frame object_start_{};  // world
};

}  // namespace twister::session
