// StationSolver: the simulated unit's solutions, one per station: the scenario's hand
// sample reported in the station's hemisphere and passed through the station's
// adaptive position and attitude filters, then moved to the `N` tip offset and turned
// by the `B`/`G` boresight. One job: the numbers a record carries. No heap.
#pragma once

#include <array>
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "twister/sim/adaptive_filter.hpp"
#include "twister/sim/scenario.hpp"
#include "twister/sim/unit_settings.hpp"

namespace twister::sim {

class StationSolver {
 public:
  struct Solution {
    bool valid = false;
    glm::dvec3 position_in{0.0};
    glm::dquat attitude{1.0, 0.0, 0.0, 0.0};
    bool button = false;
  };

  // Power-up: no solutions, filters restart.
  void reset();
  // Solves `station` (1..4) from its sample `h` under `settings` (updates the filters).
  void solve(int station, const HandSample& h, const UnitSettings& settings);
  const Solution& solution(int station) const {
    return solution_[static_cast<std::size_t>(station - 1)];
  }

 private:
  std::array<Solution, 4> solution_{};
  std::array<std::array<AdaptiveFilter, 2>, 4> filter_{};  // [station][position, attitude]
  std::array<glm::dmat3, 4> boresight_{glm::dmat3(1.0), glm::dmat3(1.0), glm::dmat3(1.0),
                                       glm::dmat3(1.0)};  // the attitude captured by `B`
  std::array<unsigned, 4> boresight_taken_{};             // the requests already captured
};

}  // namespace twister::sim
