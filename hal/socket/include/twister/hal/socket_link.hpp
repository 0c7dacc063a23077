// SocketLink: ports::LinkPort over a stream socket, non-blocking throughout.
// Address: "unix:/path/to/socket" or "tcp:A.B.C.D:PORT".
// Server (station): listens; every peer that connects waits as the newcomer
// (ports::LinkNewcomers) until the station's handshake admits it as the peer or
// refuses it: the connected peer is never replaced behind the station's back
// (a stranger cannot displace the display). Admission cannot be starved: accepted
// connections wait in a bounded pending set (kMaxPending, arrival order) and only
// one that has spoken becomes the newcomer, oldest first, once the station is done
// with the previous one; a connection silent for pending_timeout_ms is closed, and
// when the set is full the oldest silent one makes room (a flood of silent
// connects never pushes out a display that says hello). Client (bridge): connects on use and,
// after a loss, retries at most every reconnect_interval_ms. No peer ->
// unavailable (the station keeps working). Errors from the OS become io_error
// (errno kept in last_errno()). The address is parsed once, at construction:
// reconnecting and accepting never allocate.
// Endpoints never destroy files (docs/link-protocol.md "Endpoints"): a Unix
// socket path is replaced only when it is a socket nobody listens on; a regular
// file or anything else there is refused, and so is a socket a live station
// listens on. The socket file gets socket_mode (default 0660) and socket_group
// whatever the umask, and the server removes it when it closes (if it is still
// the file it created). A TCP server listens on a loopback address unless
// allow_network is set (the station then requires a pre-shared key).
// Spectators (issue 25, ports::LinkSpectators): the station may move its newcomer
// into one of kSpectatorSlots read-only slots instead of making it the peer; a
// spectator never replaces the peer, and close() closes them too.
// PollSource: the peer's, the newcomer's, the listening and (room permitting: at
// most PollSource::kMaxFds) the spectators' and the pending descriptors (POLLIN);
// those left out are still served on every pass of the station's loop;
// reopen() closes everything and opens again (server: binds anew).
#pragma once

#include <sys/socket.h>
#include <sys/types.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>

#include "twister/base/inline_vector.hpp"
#include "twister/hal/expected.hpp"
#include "twister/hal/poll_source.hpp"
#include "twister/ports/link_newcomers.hpp"
#include "twister/ports/link_port.hpp"
#include "twister/ports/link_spectators.hpp"

namespace twister::hal {

struct SocketLinkConfig {
  SocketLinkConfig() = default;
  SocketLinkConfig(std::string address_, bool server_, std::uint32_t reconnect_interval_ms_)
      : address(std::move(address_)),
        server(server_),
        reconnect_interval_ms(reconnect_interval_ms_) {}

  std::string address;  // unix:PATH | tcp:HOST:PORT
  bool server = false;
  std::uint32_t reconnect_interval_ms = 200;
  // Server only.
  std::uint32_t socket_mode = 0660;         // the Unix socket file's mode, whatever the umask
  std::string socket_group;                 // its group ("" = the process's)
  bool allow_network = false;               // a TCP listener on a non-loopback address
  std::uint32_t pending_timeout_ms = 1000;  // a silent accepted connection is closed after
};

class SocketLink final : public ports::LinkPort,
                         public ports::LinkNewcomers,
                         public ports::LinkSpectators,
                         public PollSource {
 public:
  static constexpr std::size_t kSpectatorSlots = 8;

  explicit SocketLink(SocketLinkConfig config);
  ~SocketLink() override;
  SocketLink(const SocketLink&) = delete;
  SocketLink& operator=(const SocketLink&) = delete;

  // Server: binds and listens. Errors (message names the path/address):
  // invalid_argument: bad address, or a non-loopback TCP address without
  // allow_network, or an unknown group; failed_precondition: the Unix path exists
  // and is not a socket, or a live process listens on it (left untouched);
  // io_error: bind/listen/chmod/chown failed.
  // Client: only checks the address (connects on first send/receive).
  Expected<void> open();
  // Server: closes peer, newcomer and listener and removes the socket file it made.
  void close();
  bool connected() const { return peer_fd_ >= 0; }
  // File descriptor to poll(2) for input (peer, else listener; -1 when none).
  // Kept for twister-bridge's loop; the station uses poll_fds().
  int poll_fd() const { return peer_fd_ >= 0 ? peer_fd_ : listen_fd_; }
  std::uint64_t connects() const { return connects_; }
  std::uint64_t accepted() const { return accepted_; }  // server: connections accepted
  int last_errno() const { return last_errno_; }

 private:
  Result<std::size_t> do_send(std::span<const std::byte> src) override;
  Result<std::size_t> do_receive(std::span<std::byte> dest) override;
  std::uint64_t do_newcomer_id() override;
  Result<std::size_t> do_send_newcomer(std::span<const std::byte> src) override;
  Result<std::size_t> do_receive_newcomer(std::span<std::byte> dest) override;
  void do_admit_newcomer() override;
  void do_refuse_newcomer() override;
  std::size_t do_spectator_capacity() const override;
  Status do_admit_spectator(std::size_t slot) override;
  Result<std::size_t> do_send_spectator(std::size_t slot, std::span<const std::byte> src) override;
  Result<std::size_t> do_receive_spectator(std::size_t slot, std::span<std::byte> dest) override;
  void do_close_spectator(std::size_t slot) override;
  std::size_t do_poll_fds(std::span<pollfd> out) const override;
  Status do_reopen() override;
  Expected<void> prepare_unix_path();
  Expected<void> listen_now();
  void accept_newcomers();
  // The pending set (server): silent ones expire, the oldest speaker is promoted.
  void add_pending(int fd, std::int64_t now_ms);
  void drop_pending(std::size_t index);
  void expire_pending(std::int64_t now_ms);
  void promote_newcomer();
  bool ensure_client();
  // connect(2) on a non-blocking socket, waiting at most timeout_ms for a TCP one.
  bool connect_within(int fd, int timeout_ms);
  static constexpr int kConnectTimeoutMs = 500;
  Result<std::size_t> send_on(int& fd, std::span<const std::byte> src);
  Result<std::size_t> receive_on(int& fd, std::span<std::byte> dest);
  static void close_fd(int& fd);

  SocketLinkConfig config_;
  sockaddr_storage address_{};  // config_.address, parsed
  socklen_t address_length_ = 0;
  bool address_ok_ = false;
  bool loopback_ = false;  // a TCP address on 127.0.0.0/8
  int listen_fd_ = -1;
  int peer_fd_ = -1;
  int newcomer_fd_ = -1;
  std::array<int, kSpectatorSlots> spectator_fds_{-1, -1, -1, -1, -1, -1, -1, -1};
  struct Pending {
    int fd = -1;
    std::int64_t since_ms = 0;
  };
  static constexpr std::size_t kMaxPending = 16;
  InlineVector<Pending, kMaxPending> pending_;  // [0] arrived first
  std::uint64_t newcomer_id_ = 0;
  std::uint64_t connects_ = 0;
  std::uint64_t accepted_ = 0;
  std::int64_t next_attempt_ms_ = 0;
  int last_errno_ = 0;
  // The socket file this server made (removed at close if it is still that file).
  bool made_file_ = false;
  dev_t made_dev_ = 0;
  ino_t made_ino_ = 0;
};

}  // namespace twister::hal
