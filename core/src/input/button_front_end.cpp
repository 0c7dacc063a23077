#include "twister/input/button_front_end.hpp"

namespace twister::input {

ButtonFrontEnd::ButtonFrontEnd(const ButtonDebouncerConfig& debounce, const ButtonMap& map)
    : debouncer_(debounce), map_(map) {}

Status ButtonFrontEnd::feed(const ports::ButtonEdge& edge) { return debouncer_.feed(edge); }

void ButtonFrontEnd::poll(ports::TimestampUs now_us) {
  for (auto e = debouncer_.poll(now_us); e.ok(); e = debouncer_.poll(now_us)) {
    map_.apply(*e, levels_);
  }
}

}  // namespace twister::input
