// The case file of `twister warp` (docs/math.md §10): parsing and validation, no warping.
// Host code (std::string/vector allowed); errors name the offending line.
#pragma once

#include <glm/vec3.hpp>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "twister/math/frame.hpp"
#include "twister/math/symmetry.hpp"
#include "twister/math/warp_method.hpp"

namespace twister::cli {

struct WarpCase {
  double radius = 0.0;
  math::WarpMethod method = math::WarpMethod::twister;
  math::SymmetryGroup symmetry;    // `symmetry` line (docs/math.md §10, §11); trivial if none
  std::vector<math::Frame> start;  // one per `hand` line, W = U x V
  std::vector<math::Frame> end;
  std::vector<int> hand_lines;  // line number of each hand, for later errors
  std::vector<glm::dvec3> points;
};

struct WarpCaseError {
  int line = 0;  // 1-based; the last line for "missing" errors
  std::string message;
};

// Parses and validates a whole case: keywords radius/method/symmetry/hand/point, comments
// after '#', finite numbers, orthonormal frames (1e-6), one or two hands, R > 0,
// two hands not grabbing the same point (or, under a symmetry, an image of it).
std::variant<WarpCase, WarpCaseError> parse_warp_case(std::string_view text);

}  // namespace twister::cli
