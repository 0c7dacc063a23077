// Conversion of a parsed Fastrak pose to the station's frame (O, U, V, W) (docs/fastrak-protocol.md
// §4; docs/math.md §1): O in metres, U, V, W = the receiver's x, y, z axes as unit vectors, all in
// world coordinates. Pure functions; no heap.
#pragma once

#include <array>
#include <glm/glm.hpp>

#include "twister/base/pose.hpp"
#include "twister/base/result.hpp"
#include "twister/tracker/fastrak_event.hpp"
#include "twister/tracker/fastrak_wire.hpp"

namespace twister::tracker {

// Per-receiver and world settings applied after decoding.
struct PoseConversion {
  Units units = Units::inches;
  Format format = Format::ascii;  // picks the orthonormality tolerance (orthonormal_tolerance)
  // Tool offset per station (index = station - 1), metres, in receiver coordinates:
  // the tool point is position + R * offset (R before any boresight).
  std::array<glm::dvec3, kMaxStations> tool_offset_m{};
  // Hemisphere per station (tracker frame, §2 `H`): a pose whose position points
  // into the other half-space is mirrored through the origin, as the unit does when
  // it reports in the configured hemisphere. Zero = no correction.
  std::array<glm::dvec3, kMaxStations> hemisphere{};
  // Host-side boresight per station (§2 `B`/`G`): when set, orientations are
  // reported relative to boresight_rotation (the receiver's R captured at boresight
  // time), i.e. R' = R_ref * B^T * R with R_ref from the reference angles.
  std::array<bool, kMaxStations> boresight{};
  std::array<glm::dmat3, kMaxStations> boresight_rotation{};
  std::array<glm::dvec3, kMaxStations> boresight_reference_deg{};  // az, el, roll
  // World alignment: world = world_rotation * tracker + world_translation_m.
  glm::dmat3 world_rotation{1.0};
  glm::dvec3 world_translation_m{0.0};
};

// R = Rz(az) * Ry(el) * Rx(roll) from degrees (§4); columns = receiver axes.
glm::dmat3 rotation_from_euler_deg(double azimuth, double elevation, double roll);
// R(q) of q0 (scalar), q1, q2, q3 after normalisation. out_of_range: |q| ~ 0.
Result<glm::dmat3> rotation_from_quaternion(const std::array<float, 4>& q);
// R from items 5,6,7 (row-major), re-orthonormalised by Gram-Schmidt on the columns.
// data_loss: the frame is off orthonormal by more than `tolerance`.
Result<glm::dmat3> rotation_from_dcm(const std::array<float, 9>& rows, double tolerance);
// Inverse of rotation_from_euler_deg (az, el, roll in degrees).
glm::dvec3 euler_deg_from_rotation(const glm::dmat3& r);

// Orientation of the pose in the tracker frame: direction cosines if all three rows
// are present, else the quaternion, else the Euler angles.
// failed_precondition: the pose carries no orientation item; data_loss/out_of_range
// as the rotation_from_* functions.
Result<glm::dmat3> tracker_rotation(const FastrakPose& pose, Format format);

// The full conversion: the hand's pose (twister::Pose: origin in metres, U, V, W the
// receiver's axes, world frame). The station, time and validity stay with the caller
// (the pose's station is pose.station). failed_precondition: no position or no orientation item;
// invalid_argument: station out of 1..4; data_loss: orientation not orthonormal.
Result<Pose> to_station_frame(const FastrakPose& pose, const PoseConversion& conv);

}  // namespace twister::tracker
