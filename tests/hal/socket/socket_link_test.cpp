// SocketLink (hal/socket), the transport twister-station and twister-bridge use:
// Unix and TCP loopback, non-blocking, client reconnect; on the server every peer
// arrives as the newcomer and becomes the peer only when admitted (protocol 2:
// a newcomer never replaces the connected peer by itself).
#include "twister/hal/socket_link.hpp"

#include <gtest/gtest.h>
#include <poll.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <string>
#include <vector>

namespace twister::hal {
namespace {

std::vector<std::byte> bytes(const std::string& s) {
  std::vector<std::byte> b;
  for (const char c : s) b.push_back(static_cast<std::byte>(c));
  return b;
}

// Waits (at most 20 ms) until the link's descriptors are ready: bytes, a peer, a hang-up.
void wait_ready(SocketLink& link) {
  std::array<pollfd, 3> fds{};
  ::poll(fds.data(), link.poll_fds(fds), 20);
}

// Receives until `want` bytes arrived (bounded wait, on readiness).
std::string receive_all(SocketLink& link, std::size_t want, bool newcomer = false) {
  std::string got;
  std::vector<std::byte> buf(256);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(2);
  while (got.size() < want && std::chrono::steady_clock::now() < deadline) {
    const auto n = newcomer ? link.receive_newcomer(buf) : link.receive(buf);
    if (n.ok()) {
      for (std::size_t k = 0; k < *n; ++k) got.push_back(static_cast<char>(buf[k]));
    }
    if (got.size() < want) wait_ready(link);
  }
  return got;
}

// Waits until the server sees a new newcomer (id changes).
bool newcomer_arrives(SocketLink& server, std::uint64_t before) {
  for (int i = 0; i < 100; ++i) {
    if (server.newcomer_id() != before) return true;
    wait_ready(server);
  }
  return false;
}

void exchange(const std::string& address) {
  SocketLink client({address, false, 0});
  ASSERT_TRUE(client.open());
  EXPECT_EQ(client.send(bytes("x")).status().code(), StatusCode::unavailable);  // no server yet
  SocketLink server({address, true, 0});
  const auto opened = server.open();
  ASSERT_TRUE(opened) << opened.error().message;
  std::vector<std::byte> scratch(8);
  EXPECT_EQ(server.receive(scratch).status().code(), StatusCode::unavailable);
  ASSERT_EQ(*client.send(bytes("hello")), 5u);
  ASSERT_TRUE(newcomer_arrives(server, 0));
  EXPECT_EQ(server.receive(scratch).status().code(), StatusCode::unavailable);  // not admitted
  EXPECT_EQ(receive_all(server, 5, true), "hello");
  server.admit_newcomer();
  ASSERT_EQ(*server.send(bytes("mesh")), 4u);
  EXPECT_EQ(receive_all(client, 4), "mesh");
  // A second client waits as the newcomer; the peer keeps the link.
  SocketLink again({address, false, 0});
  ASSERT_TRUE(again.open());
  ASSERT_EQ(*again.send(bytes("v2")), 2u);
  ASSERT_TRUE(newcomer_arrives(server, 1));
  EXPECT_EQ(receive_all(server, 2, true), "v2");
  ASSERT_EQ(*client.send(bytes("still")), 5u);
  EXPECT_EQ(receive_all(server, 5), "still");
  // Admitted, it replaces the first peer, which sees the hang-up.
  server.admit_newcomer();
  EXPECT_EQ(server.connects(), 2u);
  std::vector<std::byte> buf(8);
  Result<std::size_t> r = std::size_t{0};
  for (int i = 0; i < 100 && r.ok(); ++i) {
    r = client.receive(buf);
    if (r.ok()) wait_ready(client);
  }
  EXPECT_EQ(r.status().code(), StatusCode::unavailable);
  ASSERT_EQ(*server.send(bytes("ok")), 2u);
  EXPECT_EQ(receive_all(again, 2), "ok");
}

TEST(BridgeSocketLink, UnixSocketExchangeAndNewcomersWaitForAdmission) {
  exchange("unix:/tmp/twister-bridge-test-" + std::to_string(::getpid()) + ".sock");
}

TEST(BridgeSocketLink, TcpLoopbackExchangeAndNewcomersWaitForAdmission) {
  exchange("tcp:127.0.0.1:" + std::to_string(20000 + ::getpid() % 30000));
}

// PollSource: the server offers its listener, then the newcomer or peer too; the
// client its connection. reopen() binds again; the client then reconnects on use.
TEST(BridgeSocketLink, PollFdsNameListenerAndPeerAndReopenRebinds) {
  const std::string address =
      "unix:/tmp/twister-bridge-poll-" + std::to_string(::getpid()) + ".sock";
  SocketLink server({address, true, 0});
  std::array<pollfd, 4> fds{};
  EXPECT_EQ(server.poll_fds(fds), 0u);  // not open
  ASSERT_TRUE(server.open());
  ASSERT_EQ(server.poll_fds(fds), 1u);
  EXPECT_EQ(fds[0].events, POLLIN);
  SocketLink client({address, false, 0});
  ASSERT_TRUE(client.open());
  ASSERT_EQ(*client.send(bytes("hi")), 2u);
  ASSERT_EQ(client.poll_fds(fds), 1u);
  ASSERT_TRUE(newcomer_arrives(server, 0));
  EXPECT_EQ(server.poll_fds(fds), 2u);  // newcomer and listener
  server.admit_newcomer();
  EXPECT_EQ(receive_all(server, 2), "hi");
  EXPECT_EQ(server.poll_fds(fds), 2u);  // peer and listener (a newcomer wakes it)
  ASSERT_TRUE(static_cast<PollSource&>(server).reopen().ok());
  EXPECT_EQ(server.poll_fds(fds), 1u);  // listening again, no peer
  std::vector<std::byte> buf(8);
  Result<std::size_t> r = std::size_t{0};
  for (int i = 0; i < 100 && r.ok(); ++i) {
    r = client.receive(buf);  // the client sees its connection go
    if (r.ok()) wait_ready(client);
  }
  EXPECT_EQ(r.status().code(), StatusCode::unavailable);
  ASSERT_EQ(*client.send(bytes("again")), 5u);
  ASSERT_TRUE(newcomer_arrives(server, 1));
  EXPECT_EQ(receive_all(server, 5, true), "again");
}

// Issue 25: the newcomer moves into a spectator slot beside the peer (never replacing
// it); each slot is its own channel, polled with the others, and closing it hangs up
// that spectator only. A client has no slots.
TEST(BridgeSocketLink, SpectatorSlotsSitBesideThePeer) {
  const std::string address =
      "unix:/tmp/twister-bridge-spect-" + std::to_string(::getpid()) + ".sock";
  SocketLink server({address, true, 0});
  ASSERT_TRUE(server.open());
  EXPECT_EQ(server.spectator_capacity(), SocketLink::kSpectatorSlots);
  EXPECT_EQ(SocketLink({address, false, 0}).spectator_capacity(), 0u);
  EXPECT_EQ(server.admit_spectator(0).code(), StatusCode::unavailable);  // no newcomer
  SocketLink main({address, false, 0});
  ASSERT_TRUE(main.open());
  ASSERT_EQ(*main.send(bytes("m")), 1u);
  ASSERT_TRUE(newcomer_arrives(server, 0));
  EXPECT_EQ(receive_all(server, 1, true), "m");
  server.admit_newcomer();
  SocketLink watcher({address, false, 0});
  ASSERT_TRUE(watcher.open());
  ASSERT_EQ(*watcher.send(bytes("s")), 1u);
  ASSERT_TRUE(newcomer_arrives(server, 1));
  EXPECT_EQ(receive_all(server, 1, true), "s");
  EXPECT_EQ(server.admit_spectator(SocketLink::kSpectatorSlots).code(), StatusCode::out_of_range);
  ASSERT_TRUE(server.admit_spectator(3).ok());
  EXPECT_EQ(server.connects(), 1u);  // the peer is still the first client
  std::array<pollfd, 8> fds{};
  EXPECT_EQ(server.poll_fds(fds), 3u);  // peer, listener, spectator
  ASSERT_EQ(*server.send_spectator(3, bytes("mesh")), 4u);
  EXPECT_EQ(receive_all(watcher, 4), "mesh");
  ASSERT_EQ(*server.send(bytes("live")), 4u);
  EXPECT_EQ(receive_all(main, 4), "live");
  ASSERT_EQ(*watcher.send(bytes("cmd")), 3u);
  std::vector<std::byte> buf(8);
  std::size_t got = 0;
  for (int i = 0; i < 100 && got < 3; ++i) {
    const auto n = server.receive_spectator(3, buf);
    ASSERT_TRUE(n.ok());
    got += *n;
    if (got < 3) wait_ready(server);
  }
  EXPECT_EQ(got, 3u);
  EXPECT_EQ(server.send_spectator(2, bytes("x")).status().code(), StatusCode::unavailable);
  server.close_spectator(3);
  EXPECT_EQ(server.send_spectator(3, bytes("x")).status().code(), StatusCode::unavailable);
  Result<std::size_t> r = std::size_t{0};
  for (int i = 0; i < 100 && r.ok(); ++i) {
    r = watcher.receive(buf);  // the spectator sees its connection go
    if (r.ok()) wait_ready(watcher);
  }
  EXPECT_EQ(r.status().code(), StatusCode::unavailable);
  ASSERT_EQ(*server.send(bytes("ok")), 2u);  // the peer is untouched
  EXPECT_EQ(receive_all(main, 2), "ok");
}

TEST(BridgeSocketLink, BadAddressesAreRefused) {
  for (const char* a :
       {"", "unix:", "tcp:127.0.0.1", "tcp:localhost:80", "tcp:127.0.0.1:0", "serial:/dev/ttyS0"}) {
    SocketLink link({a, true, 0});
    const auto opened = link.open();
    ASSERT_FALSE(opened) << a;
    EXPECT_EQ(opened.error().status.code(), StatusCode::invalid_argument) << a;
  }
}

}  // namespace
}  // namespace twister::hal
