// SocketLink: ports::LinkPort over a stream socket, non-blocking throughout.
// Address: "unix:/path/to/socket" or "tcp:127.0.0.1:PORT" (any IPv4 host).
// Server (station): listens, accepts one peer inside send()/receive(); a newer
// peer replaces the old one (a restarted bridge is taken at once). Client
// (bridge): connects on use and, after a loss, retries at most every
// reconnect_interval_ms. No peer -> unavailable (the station keeps working).
// Errors from the OS become io_error (errno kept in last_errno()). The address is
// parsed once, at construction: reconnecting and accepting never allocate.
// PollSource: the peer's descriptor and, on the server, the listening one (POLLIN);
// reopen() closes everything and opens again (server: binds anew).
#pragma once

#include <sys/socket.h>

#include <cstdint>
#include <string>

#include "twister/hal/poll_source.hpp"
#include "twister/ports/link_port.hpp"

namespace twister::hal {

struct SocketLinkConfig {
  std::string address;  // unix:PATH | tcp:HOST:PORT
  bool server = false;
  std::uint32_t reconnect_interval_ms = 200;
};

class SocketLink final : public ports::LinkPort, public PollSource {
 public:
  explicit SocketLink(SocketLinkConfig config);
  ~SocketLink() override;
  SocketLink(const SocketLink&) = delete;
  SocketLink& operator=(const SocketLink&) = delete;

  // Server: binds and listens (a stale Unix socket file is replaced).
  // invalid_argument: bad address; io_error: bind/listen failed.
  // Client: nothing to do until the first send/receive (returns ok).
  Status open();
  bool connected() const { return peer_fd_ >= 0; }
  // File descriptor to poll(2) for input (peer, else listener; -1 when none).
  // Kept for twister-bridge's loop; the station uses poll_fds().
  int poll_fd() const { return peer_fd_ >= 0 ? peer_fd_ : listen_fd_; }
  std::uint64_t connects() const { return connects_; }
  int last_errno() const { return last_errno_; }

 private:
  Result<std::size_t> do_send(std::span<const std::byte> src) override;
  Result<std::size_t> do_receive(std::span<std::byte> dest) override;
  std::size_t do_poll_fds(std::span<pollfd> out) const override;
  Status do_reopen() override;
  bool ensure_peer();
  void drop_peer();

  SocketLinkConfig config_;
  sockaddr_storage address_{};  // config_.address, parsed
  socklen_t address_length_ = 0;
  bool address_ok_ = false;
  int listen_fd_ = -1;
  int peer_fd_ = -1;
  std::uint64_t connects_ = 0;
  std::int64_t next_attempt_ms_ = 0;
  int last_errno_ = 0;
};

}  // namespace twister::hal
