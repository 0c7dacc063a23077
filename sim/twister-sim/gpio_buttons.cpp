#include "gpio_buttons.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace twister::sim {
namespace {

hal::Error bad(const std::string& spec, const std::string& why) {
  return hal::make_error(StatusCode::invalid_argument,
                         "--buttons " + spec + ": " + why +
                             " (expected gpiod:CHIP:OFFSET,OFFSET,...[:active-low|:active-high]"
                             "[:open-drain])");
}

std::vector<std::string> split(const std::string& text, char sep) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  for (;;) {
    const std::size_t at = text.find(sep, start);
    parts.push_back(text.substr(start, at - start));
    if (at == std::string::npos) return parts;
    start = at + 1;
  }
}

}  // namespace

hal::Expected<GpioButtonsSpec> parse_gpio_buttons(const std::string& spec) {
  // The chip may be a /dev path (no ':' in it); fields are split at ':'.
  const std::vector<std::string> fields = split(spec, ':');
  if (fields.size() < 3 || fields[0] != "gpiod") return bad(spec, "not a gpiod spec");
  GpioButtonsSpec out;
  out.chip = fields[1];
  if (out.chip.empty()) return bad(spec, "no chip");
  for (const std::string& item : split(fields[2], ',')) {
    char* end = nullptr;
    const unsigned long offset = std::strtoul(item.c_str(), &end, 10);
    if (item.empty() || *end != '\0' || item[0] == '-' || offset > 1023) {
      return bad(spec, "line offset '" + item + "' is not a number from 0 to 1023");
    }
    if (std::find(out.lines.begin(), out.lines.end(), offset) != out.lines.end()) {
      return bad(spec, "line offset " + item + " given twice");
    }
    out.lines.push_back(static_cast<std::uint32_t>(offset));
  }
  if (out.lines.size() > kMaxGpioButtonLines) {
    return bad(spec, "more than " + std::to_string(kMaxGpioButtonLines) + " lines");
  }
  for (std::size_t i = 3; i < fields.size(); ++i) {
    if (fields[i] == "active-low") {
      out.active_low = true;
    } else if (fields[i] == "active-high") {
      out.active_low = false;
    } else if (fields[i] == "open-drain") {
      out.open_drain = true;
    } else {
      return bad(spec, "unknown option '" + fields[i] + "'");
    }
  }
  return out;
}

ButtonPlayer::ButtonPlayer(std::vector<ButtonEvent> events) : events_(std::move(events)) {}

hal::Expected<void> ButtonPlayer::check_lines(std::size_t line_count) const {
  for (const ButtonEvent& e : events_) {
    if (e.line < 0 || static_cast<std::size_t>(e.line) >= line_count) {
      return hal::make_error(StatusCode::invalid_argument,
                             "the scenario presses button line " + std::to_string(e.line) +
                                 " but --buttons wires " + std::to_string(line_count) +
                                 " lines (button line i is the i-th offset)");
    }
  }
  return {};
}

Status ButtonPlayer::advance(std::int64_t now_us, const SetLine& set) {
  while (next_ < events_.size()) {
    const ButtonEvent& e = events_[next_];
    if (std::llround(e.t_s * 1e6) > now_us) break;
    ++next_;
    if (e.line < 0 || e.line >= kMaxScenarioButtonLines) continue;
    const auto line = static_cast<std::size_t>(e.line);
    if (level_[line] == e.pressed) continue;  // no edge
    level_[line] = e.pressed;
    ++edges_;
    if (const Status s = set(line, e.pressed); !s.ok()) return s;
  }
  return ok_status();
}

}  // namespace twister::sim
