// GpiodLineOutput: GPIO output lines through libgpiod (v1 API, as GpiodButtonSource
// reads its inputs): the driving end of a rig's button wiring. twister-sim --buttons
// uses it to press the station's buttons on the scenario's clock (docs/hil.md).
// All lines are requested in one request (one line handle), every line starting
// inactive; set() writes the whole set of values in one ioctl (a v1 handle sets all
// its lines at once, so the others keep their levels); stage() changes lines without
// writing and flush() writes them together, so edges scripted for the same instant
// leave in one ioctl. active_low: an active
// (pressed) line is driven low, as a switch to GND with a pull-up would pull it (the
// station's default `active_low = true`); open_drain: the line is only ever pulled
// low or let go (safe against a second driver; needs the station's pull-up).
// close() (and the destructor) sets every line inactive before releasing it.
// Errors: open() -> unavailable (no such chip), io_error (a line busy, no permission:
// last_errno()), invalid_argument (no lines, too many, a repeated offset, an offset
// beyond the chip); set() -> failed_precondition (not open), invalid_argument (index
// beyond the lines), io_error (the ioctl failed, e.g. the chip is gone).
// Only the owning thread may call it.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "twister/base/status.hpp"

struct gpiod_chip;
struct gpiod_line;

namespace twister::hal {

struct GpiodOutputConfig {
  std::string chip = "gpiochip0";        // name, number or /dev path (gpiod_chip_open_lookup)
  std::vector<std::uint32_t> lines;      // output i = lines[i]; at most kMaxLines, each once
  bool active_low = true;                // active drives the line low
  bool open_drain = false;               // drive low or let go (never drive high)
  std::string consumer = "twister-sim";  // what `gpioinfo` shows as the lines' user
};

class GpiodLineOutput {
 public:
  static constexpr std::size_t kMaxLines = 16;

  GpiodLineOutput() = default;
  ~GpiodLineOutput();
  GpiodLineOutput(const GpiodLineOutput&) = delete;
  GpiodLineOutput& operator=(const GpiodLineOutput&) = delete;

  Status open(const GpiodOutputConfig& config);
  // Line `index` (lines[index]) active or inactive, written at once.
  Status set(std::size_t index, bool active);
  // The same without writing (same errors as set(), never io_error) ...
  Status stage(std::size_t index, bool active);
  // ... and every staged change written in one ioctl (nothing to do: ok).
  Status flush();
  void close();

  bool is_open() const { return count_ > 0; }
  std::size_t line_count() const { return count_; }
  bool active(std::size_t index) const { return index < count_ && values_[index] != 0; }
  // errno of the last failure, for the caller's message.
  int last_errno() const { return last_errno_; }

 private:
  Status write_values();

  gpiod_chip* chip_ = nullptr;
  std::array<gpiod_line*, kMaxLines> lines_{};
  std::array<int, kMaxLines> values_{};  // logical: 1 = active
  std::size_t count_ = 0;
  bool dirty_ = false;  // staged values not written yet
  int last_errno_ = 0;
};

}  // namespace twister::hal
