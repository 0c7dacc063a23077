// The Fastrak's adaptive filter as the simulator models it (`x` position, `v`
// attitude; manual rev. G, "x"/"v" commands and appendix E). The manual gives the
// output equation <x>_k = a x_k + (1 - a) <x>_(k-1) and the roles of F, FLOW, FHIGH,
// FACTOR but not how the pole a adapts; the adaptation below is ours (assumed,
// docs/fastrak.md): the innovation e = |x_k - <x>_(k-1)| (inches, or degrees of the
// rotation between input and output) relative to a full-bandwidth step places a target
// between FLOW (e = 0) and FHIGH (e >= a full step); F is the share of that target in
// the new a; a falls by at most a factor FACTOR per update. FLOW = 1 disables the filter. One
// instance per station and quantity; fixed storage, no heap.
#pragma once

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace twister::sim {

struct FilterParams {
  double f = 0.2;        // sensitivity, 0 < F < 1
  double flow = 1.0;     // maximum filtering (smallest a); 1 = filter off
  double fhigh = 0.8;    // minimum filtering (largest a), FLOW < FHIGH < 1
  double factor = 0.95;  // largest step towards heavier filtering, 0 < FACTOR < 1
  bool enabled() const { return flow < 1.0; }
};

// Macro settings (`x n` / `v n`): 2 none, 3 low, 4 medium (the manual's values), 5
// heavy. Low and heavy are assumed.
inline constexpr FilterParams kFilterOff{0.2, 1.0, 0.8, 0.95};
inline constexpr FilterParams kFilterLow{0.2, 0.5, 0.9, 0.95};
inline constexpr FilterParams kFilterMedium{0.2, 0.2, 0.8, 0.95};
inline constexpr FilterParams kFilterHeavy{0.2, 0.05, 0.5, 0.95};

// Innovation that opens the filter fully (a = FHIGH): per update, assumed.
inline constexpr double kFullStepInches = 1.0;
inline constexpr double kFullStepDegrees = 5.0;

class AdaptiveFilter {
 public:
  // Next output for input `in`; the first input after reset() passes unchanged.
  glm::dvec3 position(const glm::dvec3& in, const FilterParams& p);
  glm::dquat attitude(const glm::dquat& in, const FilterParams& p);
  void reset() { primed_ = false; }
  double alpha() const { return alpha_; }

 private:
  // Adapts alpha_ to the innovation e (relative to a full step); false: filter off
  // or first input (the output is the input).
  bool adapt(double relative_step, const FilterParams& p);

  bool primed_ = false;
  double alpha_ = 1.0;
  glm::dvec3 position_{0.0};
  glm::dquat attitude_{1.0, 0.0, 0.0, 0.0};
};

}  // namespace twister::sim
