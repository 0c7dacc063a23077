#include "twister/sim/station_solver.hpp"

#include <algorithm>

#include "twister/tracker/pose_conversion.hpp"

namespace twister::sim {

void StationSolver::reset() {
  for (auto& f : filter_) {
    for (auto& one : f) one.reset();
  }
  solution_ = {};
  boresight_taken_ = {};
}

void StationSolver::solve(int station, const HandSample& h, const UnitSettings& settings) {
  const auto i = static_cast<std::size_t>(station - 1);
  glm::dvec3 p(h.position_in[0], h.position_in[1], h.position_in[2]);
  const auto& hem = settings.hemisphere[i];
  // The unit reports positions in the configured half-space.
  if (glm::dot(p, glm::dvec3(hem[0], hem[1], hem[2])) < 0.0) p = -p;
  const double el = std::clamp(h.euler_deg[1], -90.0, 90.0);
  const glm::dquat q =
      glm::quat_cast(tracker::rotation_from_euler_deg(h.euler_deg[0], el, h.euler_deg[2]));
  Solution& s = solution_[i];
  s.valid = true;
  s.position_in = filter_[i][0].position(p, settings.filter[0]);
  s.attitude = filter_[i][1].attitude(q, settings.filter[1]);
  // The tip offset, in the receiver's own (unboresighted) axes.
  const glm::dmat3 r = glm::mat3_cast(s.attitude);
  const auto& tip = settings.tip_offset_in[i];
  s.position_in += r * glm::dvec3(tip[0], tip[1], tip[2]);
  if (boresight_taken_[i] != settings.boresight_requests[i]) {  // `B`: this attitude
    boresight_[i] = r;
    boresight_taken_[i] = settings.boresight_requests[i];
  }
  if (settings.boresight_on[i]) {
    const auto& ref = settings.boresight_reference_deg[i];
    s.attitude =
        glm::normalize(glm::quat_cast(tracker::rotation_from_euler_deg(ref[0], ref[1], ref[2]) *
                                      glm::transpose(boresight_[i]) * r));
  }
  s.button = station == 1 && h.button;  // the stylus works on station 1 only
}

}  // namespace twister::sim
