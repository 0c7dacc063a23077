// LinkNewcomers: the second capability of a LinkPort whose far end can change (a
// listening socket): a peer that connects while another is connected waits as the
// newcomer, with its own byte channel, until the station admits it (it becomes the
// LinkPort's peer and the previous peer is closed) or refuses it (closed). The
// connected peer is never replaced behind the station's back, so a stranger that
// connects cannot displace the display (docs/link-protocol.md "Admission").
// Transports with one fixed far end (serial, pipes) do not offer it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "twister/base/result.hpp"

namespace twister::ports {

class LinkNewcomers {
 public:
  virtual ~LinkNewcomers() = default;

  // Looks for newcomers; the value changes whenever a new one arrived (0: there
  // never was one). A newcomer that arrives while one is waiting replaces it (the
  // older one is closed).
  std::uint64_t newcomer_id() { return do_newcomer_id(); }
  // Bytes to / from the newcomer, never blocking. unavailable: no newcomer (none
  // waiting, or it hung up).
  Result<std::size_t> send_newcomer(std::span<const std::byte> src) {
    return do_send_newcomer(src);
  }
  Result<std::size_t> receive_newcomer(std::span<std::byte> dest) {
    return do_receive_newcomer(dest);
  }
  // The newcomer becomes the LinkPort's peer; the previous peer, if any, is closed.
  void admit_newcomer() { do_admit_newcomer(); }
  // Closes the newcomer.
  void refuse_newcomer() { do_refuse_newcomer(); }

 private:
  virtual std::uint64_t do_newcomer_id() = 0;
  virtual Result<std::size_t> do_send_newcomer(std::span<const std::byte> src) = 0;
  virtual Result<std::size_t> do_receive_newcomer(std::span<std::byte> dest) = 0;
  virtual void do_admit_newcomer() = 0;
  virtual void do_refuse_newcomer() = 0;
};

}  // namespace twister::ports
