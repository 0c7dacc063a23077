// GpiodButtonSource: the ButtonSource port over GPIO lines via libgpiod v1.
// Lines are requested for both-edge events with the consumer name "twister-station";
// active_low makes the kernel invert the level, so a rising event is always "pressed".
// Edge times are the kernel's event timestamps (CLOCK_MONOTONIC on Linux >= 5.7, the
// same base as MonotonicClock). poll() never blocks; as a PollSource it asks to
// wait for POLLIN on each line's event fd, and reopen() requests the lines again
// with the config of the last open().
// Errors: open() -> unavailable (chip missing), io_error (line busy, no permission,
// bias not supported by the kernel), invalid_argument (bad offsets);
// poll() -> unavailable (no edge pending), io_error (chip gone: the lines are released
// and the source is closed, connected() false, until reopen() finds the chip again),
// failed_precondition (not open).
// Only the owning thread may call it.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "twister/base/inline_vector.hpp"
#include "twister/hal/poll_source.hpp"
#include "twister/ports/button_source.hpp"

struct gpiod_chip;
struct gpiod_line;

namespace twister::hal {

struct GpiodButtonConfig {
  std::string chip = "gpiochip0";    // name, number or /dev path (gpiod_chip_open_lookup)
  std::vector<std::uint32_t> lines;  // button i = lines[i]; at most kMaxLines
  bool active_low = true;
  enum class Bias : std::uint8_t { as_is, disable, pull_up, pull_down } bias = Bias::as_is;
};

class GpiodButtonSource final : public ports::ButtonSource, public PollSource {
 public:
  static constexpr std::size_t kMaxLines = PollSource::kMaxFds;

  GpiodButtonSource() = default;
  ~GpiodButtonSource() override;
  GpiodButtonSource(const GpiodButtonSource&) = delete;
  GpiodButtonSource& operator=(const GpiodButtonSource&) = delete;

  Status open(const GpiodButtonConfig& config);
  void close();
  // errno of the last failure, for the log at the composition root.
  int last_errno() const { return last_errno_; }

 private:
  Result<ports::ButtonEdge> do_poll() override;
  std::uint8_t do_line_count() const override { return static_cast<std::uint8_t>(lines_.size()); }
  bool do_connected() const override { return !lines_.empty(); }
  std::size_t do_poll_fds(std::span<pollfd> out) const override;
  Status do_reopen() override;

  GpiodButtonConfig config_;  // of the last open(), for reopen()
  bool configured_ = false;
  gpiod_chip* chip_ = nullptr;
  struct RequestedLine {
    gpiod_line* line = nullptr;
    int fd = -1;  // its event fd
  };
  InlineVector<RequestedLine, kMaxLines> lines_;  // button line i = lines_[i]
  std::size_t next_line_ = 0;  // round-robin start so one chatty line cannot starve others
  int last_errno_ = 0;
};

}  // namespace twister::hal
