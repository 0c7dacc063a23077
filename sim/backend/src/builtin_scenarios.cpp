#include "twister/sim/builtin_scenarios.hpp"

namespace twister::sim {
namespace {

// Scenario text format: docs/fastrak.md (sim/). Positions in inches, angles in degrees.
constexpr std::string_view kStroke = R"(seed 1
receivers 2
duration 7.5
key 0 1 10 -8 5 0 0 0 0
key 4 1 10 -8 5 0 0 0 1
key 4.5 1 10 -8 5 0 0 0 1
key 5.5 1 14 -6 5 20 0 0 1
key 6 1 14 -6 5 20 0 0 0
key 7.5 1 14 -6 5 20 0 0 0
key 0 2 10 8 5 0 0 0
key 7.5 2 10 8 5 0 0 0
)";

constexpr std::string_view kIdle = R"(seed 1
receivers 2
duration 3
key 0 1 10 -8 5 0 0 0
key 0 2 10 8 5 0 0 0
)";

constexpr std::string_view kUnplug = R"(seed 1
receivers 2
duration 16
key 0 1 10 -8 5 0 0 0 0
key 4 1 10 -8 5 0 0 0 1
key 4.5 1 10 -8 5 0 0 0 1
key 5.5 1 14 -6 5 20 0 0 1
key 6 1 14 -6 5 20 0 0 0
key 6.8 1 14 -6 5 20 0 0 1
key 7.5 1 30 30 30 20 0 0 1
key 7.51 1 14 -6 5 20 0 0 0
key 12.5 1 14 -6 5 20 0 0 1
key 13 1 14 -6 5 20 0 0 1
key 14 1 18 -4 5 40 0 0 1
key 14.5 1 18 -4 5 40 0 0 0
key 16 1 18 -4 5 40 0 0 0
key 0 2 10 8 5 0 0 0
key 16 2 10 8 5 0 0 0
fault 7 hangup 1.5
)";

}  // namespace

std::string_view builtin_scenario_text(std::string_view name) {
  if (name == "stroke") return kStroke;
  if (name == "idle") return kIdle;
  if (name == "unplug") return kUnplug;
  return {};
}

hal::Expected<Scenario> load_builtin_scenario(std::string_view name) {
  const std::string_view text = builtin_scenario_text(name);
  if (text.empty()) {
    return hal::make_error(StatusCode::invalid_argument,
                           "unknown built-in scenario '" + std::string(name) + "'");
  }
  Scenario out;
  if (std::string error; !parse_scenario(text, out, error)) {
    return hal::make_error(StatusCode::invalid_argument, error);
  }
  return out;
}

}  // namespace twister::sim
