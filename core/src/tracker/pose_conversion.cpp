// Orientation from each item (docs/fastrak-protocol.md §4) and the station-frame conversion.
#include "twister/tracker/pose_conversion.hpp"

#include <cmath>

namespace twister::tracker {
namespace {

constexpr double kDegToRad = 3.14159265358979323846 / 180.0;
constexpr double kInchToMetre = 0.0254;
constexpr double kCentimetreToMetre = 0.01;

}  // namespace

glm::dmat3 rotation_from_euler_deg(double azimuth, double elevation, double roll) {
  const double cp = std::cos(azimuth * kDegToRad), sp = std::sin(azimuth * kDegToRad);
  const double ct = std::cos(elevation * kDegToRad), st = std::sin(elevation * kDegToRad);
  const double cf = std::cos(roll * kDegToRad), sf = std::sin(roll * kDegToRad);
  // glm is column-major: each dvec3 below is a column of R = Rz*Ry*Rx.
  return glm::dmat3(glm::dvec3(cp * ct, sp * ct, -st),
                    glm::dvec3(cp * st * sf - sp * cf, sp * st * sf + cp * cf, ct * sf),
                    glm::dvec3(cp * st * cf + sp * sf, sp * st * cf - cp * sf, ct * cf));
}

glm::dvec3 euler_deg_from_rotation(const glm::dmat3& r) {
  // r[c][row]: R(2,0) = -sin(el), R(1,0)/R(0,0) = tan(az), R(2,1)/R(2,2) = tan(roll).
  const double el = std::asin(std::fmax(-1.0, std::fmin(1.0, -r[0][2])));
  const double az = std::atan2(r[0][1], r[0][0]);
  const double roll = std::atan2(r[1][2], r[2][2]);
  return glm::dvec3(az, el, roll) / kDegToRad;
}

Result<glm::dmat3> rotation_from_quaternion(const std::array<float, 4>& qf) {
  double q0 = qf[0], q1 = qf[1], q2 = qf[2], q3 = qf[3];
  const double n = std::sqrt(q0 * q0 + q1 * q1 + q2 * q2 + q3 * q3);
  if (!(n > 1e-6) || !std::isfinite(n)) return StatusCode::out_of_range;
  q0 /= n;
  q1 /= n;
  q2 /= n;
  q3 /= n;
  return glm::dmat3(
      glm::dvec3(1 - 2 * (q2 * q2 + q3 * q3), 2 * (q1 * q2 + q0 * q3), 2 * (q1 * q3 - q0 * q2)),
      glm::dvec3(2 * (q1 * q2 - q0 * q3), 1 - 2 * (q1 * q1 + q3 * q3), 2 * (q2 * q3 + q0 * q1)),
      glm::dvec3(2 * (q1 * q3 + q0 * q2), 2 * (q2 * q3 - q0 * q1), 1 - 2 * (q1 * q1 + q2 * q2)));
}

Result<glm::dmat3> rotation_from_dcm(const std::array<float, 9>& rows, double tolerance) {
  // Columns of R are the receiver axes: U = (5a, 6a, 7a), and so on.
  glm::dvec3 u(rows[0], rows[3], rows[6]);
  glm::dvec3 v(rows[1], rows[4], rows[7]);
  glm::dvec3 w(rows[2], rows[5], rows[8]);
  for (const auto& a : {u, v, w}) {
    if (!std::isfinite(a.x) || !std::isfinite(a.y) || !std::isfinite(a.z)) {
      return StatusCode::data_loss;
    }
  }
  const double det = glm::determinant(glm::dmat3(u, v, w));
  if (std::fabs(det - 1.0) > tolerance || std::fabs(glm::dot(u, v)) > tolerance ||
      std::fabs(glm::dot(u, w)) > tolerance || std::fabs(glm::dot(v, w)) > tolerance) {
    return StatusCode::data_loss;
  }
  // ASCII cosines carry 4 decimals: Gram-Schmidt makes the frame exactly orthonormal.
  u = glm::normalize(u);
  v = glm::normalize(v - glm::dot(v, u) * u);
  w = glm::cross(u, v);
  return glm::dmat3(u, v, w);
}

Result<glm::dmat3> tracker_rotation(const FastrakPose& pose, Format format) {
  if (pose.has.dcm) {
    return rotation_from_dcm(pose.dcm, orthonormal_tolerance(format));
  }
  if (pose.has.quaternion) return rotation_from_quaternion(pose.quaternion);
  if (pose.has.euler) {
    return rotation_from_euler_deg(pose.euler_deg[0], pose.euler_deg[1], pose.euler_deg[2]);
  }
  return StatusCode::failed_precondition;
}

Result<Pose> to_station_frame(const FastrakPose& pose, const PoseConversion& conv) {
  if (pose.station < 1 || pose.station > kMaxStations) return StatusCode::invalid_argument;
  if (!pose.has_position) return StatusCode::failed_precondition;
  const std::size_t s = pose.station - 1u;
  TWISTER_TRY_ASSIGN(glm::dmat3 r, tracker_rotation(pose, conv.format));
  const double scale = conv.units == Units::inches ? kInchToMetre : kCentimetreToMetre;
  glm::dvec3 p = glm::dvec3(pose.position[0], pose.position[1], pose.position[2]) * scale;
  const glm::dvec3& h = conv.hemisphere[s];
  if (glm::dot(h, h) > 0.0 && glm::dot(p, h) < 0.0) p = -p;
  // The tool point along the receiver's true axes: a boresight changes how the
  // orientation reads, not where the tip is.
  const glm::dvec3 tool = p + r * conv.tool_offset_m[s];
  if (conv.boresight[s]) {
    const glm::dvec3& ref = conv.boresight_reference_deg[s];
    r = rotation_from_euler_deg(ref.x, ref.y, ref.z) * glm::transpose(conv.boresight_rotation[s]) *
        r;
  }
  const glm::dmat3 world_r = conv.world_rotation * r;
  Pose f;
  f.origin = conv.world_rotation * tool + conv.world_translation_m;
  f.u = world_r[0];
  f.v = world_r[1];
  f.w = world_r[2];
  return f;
}

}  // namespace twister::tracker
