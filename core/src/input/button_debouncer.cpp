#include "twister/input/button_debouncer.hpp"

#include <algorithm>

namespace twister::input {

ButtonDebouncer::ButtonDebouncer(const ButtonDebouncerConfig& config) : config_(config) {
  lines_.resize(std::min<std::size_t>(config.line_count, kMaxButtonLines));
}

Status ButtonDebouncer::feed(const ports::ButtonEdge& edge) {
  if (edge.line >= lines_.size()) return StatusCode::out_of_range;
  Line& line = lines_[edge.line];
  // Every edge restarts the stability wait, even a repeat of the same level: a
  // bounce that went down and up between two polls is still a bounce.
  line.raw = edge.pressed;
  line.raw_since_us = edge.time_us;
  return ok_status();
}

Result<ButtonEvent> ButtonDebouncer::poll(ports::TimestampUs now_us) {
  for (std::uint8_t i = 0; i < lines_.size(); ++i) {
    Line& line = lines_[i];
    if (line.raw == line.stable) continue;
    const ports::TimestampUs due_us = line.raw_since_us + config_.interval_us[i];
    if (now_us < due_us) continue;
    line.stable = line.raw;
    return ButtonEvent{i, line.stable, due_us};
  }
  return StatusCode::unavailable;
}

void ButtonDebouncer::reset() {
  for (Line& line : lines_) line = Line{};
}

bool ButtonDebouncer::pressed(std::uint8_t line) const {
  return line < lines_.size() && lines_[line].stable;
}

}  // namespace twister::input
