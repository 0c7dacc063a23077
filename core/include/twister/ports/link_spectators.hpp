// LinkSpectators: the third capability of a listening LinkPort (issue 25): read-only
// displays. A newcomer the station admitted as a spectator moves from the newcomer
// channel into one of a fixed number of spectator slots, each its own byte channel
// beside the LinkPort's peer (the one display that may send commands). A spectator
// never replaces the peer nor another spectator; the station closes a slot when the
// spectator leaves or stops reading (docs/link-protocol.md "Spectators").
// Transports with one fixed far end (serial, pipes) do not offer it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "twister/base/result.hpp"

namespace twister::ports {

class LinkSpectators {
 public:
  virtual ~LinkSpectators() = default;

  // How many spectator slots the transport has (slots are 0 .. capacity - 1).
  std::size_t spectator_capacity() const { return do_spectator_capacity(); }
  // The waiting newcomer becomes the spectator in `slot` (which must be free).
  // unavailable: no newcomer waiting; out_of_range: no such slot.
  Status admit_spectator(std::size_t slot) { return do_admit_spectator(slot); }
  // Bytes to / from the spectator in `slot`, never blocking. unavailable: the slot is
  // empty or its spectator hung up.
  Result<std::size_t> send_spectator(std::size_t slot, std::span<const std::byte> src) {
    return do_send_spectator(slot, src);
  }
  Result<std::size_t> receive_spectator(std::size_t slot, std::span<std::byte> dest) {
    return do_receive_spectator(slot, dest);
  }
  // Closes the spectator in `slot` (nothing when it is empty).
  void close_spectator(std::size_t slot) { do_close_spectator(slot); }

 private:
  virtual std::size_t do_spectator_capacity() const = 0;
  virtual Status do_admit_spectator(std::size_t slot) = 0;
  virtual Result<std::size_t> do_send_spectator(std::size_t slot,
                                                std::span<const std::byte> src) = 0;
  virtual Result<std::size_t> do_receive_spectator(std::size_t slot, std::span<std::byte> dest) = 0;
  virtual void do_close_spectator(std::size_t slot) = 0;
};

}  // namespace twister::ports
