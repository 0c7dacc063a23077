// LinkPort: the byte link from the station to twister-bridge (serial/USB CDC, TCP
// loopback, Unix socket, pipe). Framing lives in core/link; this only moves bytes.
#pragma once

#include <cstddef>
#include <span>

#include "twister/base/result.hpp"

namespace twister::ports {

class LinkPort {
 public:
  virtual ~LinkPort() = default;

  // Sends bytes without blocking; returns how many were taken (0 when the peer is
  // slow). unavailable: no peer connected (the station keeps working).
  Result<std::size_t> send(std::span<const std::byte> src) { return do_send(src); }

  // Receives pending bytes (0 when none). unavailable: no peer connected.
  Result<std::size_t> receive(std::span<std::byte> dest) { return do_receive(dest); }

 private:
  virtual Result<std::size_t> do_send(std::span<const std::byte> src) = 0;
  virtual Result<std::size_t> do_receive(std::span<std::byte> dest) = 0;
};

}  // namespace twister::ports
