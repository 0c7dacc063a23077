// Issue 11 items 5 and 6 in core (label integrity): StationLink's admission on a
// port with a newcomer channel (a fake listening transport over in-memory wires).
//   - peer swap: the old display left a partial frame; the new display's hello is
//     admitted and its next request is understood (a fresh decoder per
//     connection); the old display is told "displaced" at a frame boundary;
//   - the same on a plain port: reconnect after a torn frame;
//   - a displaced display's yielding hello is told "busy" while another display
//     holds the link and is admitted once the link is free (issue 21 item 5);
//   - a protocol 1 peer is refused with a clear count, a silent one times out,
//     and neither disturbs the connected display.
#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "fakes/fake_link_listener.hpp"
#include "fakes/memory_wire.hpp"
#include "session_harness.hpp"
#include "twister/base/checksum.hpp"
#include "twister/ports/link_newcomers.hpp"
#include "twister/station/station_link.hpp"

namespace twister::link {
namespace {

using session::test_support::Station;

using test::FakeListener;

template <LinkBody M>
std::vector<std::byte> frame(const M& m) {
  std::vector<std::byte> f(kMaxFrameBytes);
  const auto n = encode_frame(m, f);
  EXPECT_TRUE(n.ok());
  f.resize(n.ok() ? *n : 0);
  return f;
}

Hello hello(std::uint32_t version = 0, std::uint64_t checksum = 0) {
  return Hello{Role::bridge, 0, version, checksum, {}};
}

ResendRequest resend() { return ResendRequest{}; }

// The display's end of a wire: what it sends, what it decodes.
struct Far {
  explicit Far(test::MemoryWire& w) : end(w, false) {}
  void send(const std::vector<std::byte>& bytes) { ASSERT_EQ(*end.send(bytes), bytes.size()); }
  std::vector<LinkMessage> receive() {
    std::vector<LinkMessage> got;
    std::vector<std::byte> buf(1 << 16);
    for (;;) {
      const auto n = end.receive(buf);
      if (!n.ok() || *n == 0) break;
      for (std::size_t i = 0; i < *n; ++i) {
        if (const auto m = decoder.process(buf[i]); m.ok()) got.push_back(**m);
      }
    }
    return got;
  }
  test::MemoryLinkEnd end;
  LinkDecoder decoder;
};

struct Rig {
  Rig() {
    const std::size_t n = station.mesh.vertex_capacity();
    x.resize(n);
    y.resize(n);
    z.resize(n);
    idx.resize(3 * station.mesh.triangle_capacity());
    out.resize(64 * kMaxFrameBytes);
    station::StationLinkOptions options;
    options.newcomers = &listener;
    link = std::make_unique<station::StationLink>(listener,
                                                  station::StationLinkStorage{x, y, z, idx, out},
                                                  station::StationLinkConfig{}, options);
    EXPECT_TRUE(link->start(*station.session).ok());
  }
  void poll(int rounds = 20) {
    for (int i = 0; i < rounds; ++i) {
      station.now_us += 1000;
      link->poll(*station.session, station.now_us);
    }
  }
  // A display connects on `wire` (its end `far`) and says `h`.
  void arrives(test::MemoryWire& wire, Far& far, const Hello& h) {
    listener.connect(wire);
    far.send(frame(h));
    poll();
  }
  Station station;
  FakeListener listener;
  std::vector<float> x, y, z;
  std::vector<std::uint32_t> idx;
  std::vector<std::byte> out;
  std::unique_ptr<station::StationLink> link;
};

std::size_t count(const std::vector<LinkMessage>& ms, MessageType t) {
  std::size_t n = 0;
  for (const auto& m : ms) n += type_of(m) == t ? 1 : 0;
  return n;
}

TEST(LinkPeerSwap, NewDisplaysHelloIsNotSwallowedByTheOldOnesPartialFrame) {
  Rig r;
  test::MemoryWire wa;
  Far a(wa);
  r.arrives(wa, a, hello());
  ASSERT_TRUE(r.link->peer_synced());
  EXPECT_EQ(count(a.receive(), MessageType::mesh_end), 1u);
  // The old display dies in the middle of a frame.
  const auto torn = frame(resend());
  a.send(std::vector<std::byte>(torn.begin(), torn.begin() + 5));
  r.poll(2);
  test::MemoryWire wb;
  Far b(wb);
  r.arrives(wb, b, hello(1, r.station.mesh.checksum()));  // holds our mesh already
  EXPECT_EQ(r.listener.peer(), &wb);
  const auto told = a.receive();
  ASSERT_FALSE(told.empty());
  EXPECT_EQ(type_of(told.back()), MessageType::bye);
  EXPECT_EQ(std::get<Bye>(told.back()).reason, ByeReason::displaced);
  EXPECT_EQ(count(b.receive(), MessageType::hello), 1u);
  // The new display's next request is understood on the display channel.
  b.send(frame(resend()));
  r.poll();
  EXPECT_EQ(r.link->counters().resend_requests, 1u);
  EXPECT_EQ(count(b.receive(), MessageType::mesh_end), 1u);
  EXPECT_EQ(r.link->counters().displaced, 1u);
}

TEST(LinkPeerSwap, AYieldingDisplayWaitsWhileAnotherHoldsTheLinkAndComesBackWhenItIsFree) {
  Rig r;
  test::MemoryWire wa;
  Far a(wa);
  r.arrives(wa, a, hello());
  ASSERT_EQ(r.listener.peer(), &wa);
  (void)a.receive();
  // A displaced display tries again, yielding: busy, and the display stays.
  Hello yielding = hello();
  yielding.flags = kHelloYield;
  test::MemoryWire wb;
  Far b(wb);
  r.arrives(wb, b, yielding);
  EXPECT_EQ(r.listener.peer(), &wa);
  EXPECT_FALSE(wb.up);  // refused and closed; read what was sent before it closed
  wb.up = true;
  const auto told = b.receive();
  ASSERT_EQ(told.size(), 1u);  // no station hello: only the bye
  EXPECT_EQ(std::get<Bye>(told[0]).reason, ByeReason::busy);
  EXPECT_EQ(count(a.receive(), MessageType::bye), 0u);
  EXPECT_EQ(r.link->counters().refused.busy, 1u);
  EXPECT_EQ(r.link->counters().displaced, 0u);
  // The display leaves; the next yielding try is admitted, displacing nobody.
  wa.up = false;
  r.poll();
  ASSERT_FALSE(r.link->connected());
  test::MemoryWire wc;
  Far c(wc);
  r.arrives(wc, c, yielding);
  EXPECT_EQ(r.listener.peer(), &wc);
  const auto welcome = c.receive();
  EXPECT_EQ(count(welcome, MessageType::hello), 1u);
  EXPECT_EQ(count(welcome, MessageType::mesh_end), 1u);
  EXPECT_EQ(count(welcome, MessageType::bye), 0u);
  EXPECT_EQ(r.link->counters().refused.busy, 1u);
  EXPECT_EQ(r.link->counters().displaced, 0u);
  EXPECT_EQ(r.link->counters().connects, 2u);
}

TEST(LinkPeerSwap, ReconnectAfterATornFrameOnAPlainPort) {
  Station station;
  test::MemoryWire wire;
  test::MemoryLinkEnd station_end(wire, true);
  Far far(wire);
  std::vector<float> x(station.mesh.vertex_capacity()), y(x.size()), z(x.size());
  std::vector<std::uint32_t> idx(3 * station.mesh.triangle_capacity());
  std::vector<std::byte> out(64 * kMaxFrameBytes);
  station::StationLink link(station_end, {x, y, z, idx, out}, {});
  ASSERT_TRUE(link.start(*station.session).ok());
  const auto h = frame(hello());
  far.send(std::vector<std::byte>(h.begin(), h.begin() + 7));  // torn
  link.poll(*station.session, 1000);
  wire.cut();
  link.poll(*station.session, 2000);
  wire.up = true;
  far.send(h);
  for (int i = 0; i < 20; ++i) link.poll(*station.session, 3000 + 1000 * i);
  EXPECT_TRUE(link.peer_synced());
  EXPECT_EQ(count(far.receive(), MessageType::mesh_end), 1u);
}

// COBS + CRC by hand: a frame of another protocol version.
std::vector<std::byte> frame_of_version(std::uint8_t version) {
  std::vector<std::byte> payload{std::byte{version}, std::byte{1}, std::byte{2}};
  payload.resize(15, std::byte{0});
  const std::uint32_t crc = crc32(payload);
  for (int i = 0; i < 4; ++i) payload.push_back(static_cast<std::byte>((crc >> (8 * i)) & 0xff));
  std::vector<std::byte> out{std::byte{0}};
  std::size_t code_pos = 0;
  for (const std::byte b : payload) {
    if (b == std::byte{0}) {
      out[code_pos] = static_cast<std::byte>(out.size() - code_pos);
      code_pos = out.size();
      out.push_back(std::byte{0});
    } else {
      out.push_back(b);
    }
  }
  out[code_pos] = static_cast<std::byte>(out.size() - code_pos);
  out.push_back(std::byte{0});
  return out;
}

TEST(LinkAdmission, OldProtocolAndSilentPeersAreRefusedAndTheDisplayStays) {
  Rig r;
  test::MemoryWire wa;
  Far a(wa);
  r.arrives(wa, a, hello());
  ASSERT_TRUE(r.link->peer_synced());
  (void)a.receive();
  test::MemoryWire old_wire;
  Far old(old_wire);
  r.listener.connect(old_wire);
  old.send(frame_of_version(1));
  r.poll();
  EXPECT_EQ(r.link->counters().refused.version, 1u);
  EXPECT_EQ(r.link->refused_version(), 1u);
  EXPECT_FALSE(old_wire.up);
  test::MemoryWire silent_wire;
  r.listener.connect(silent_wire);
  r.poll(2100);  // 2.1 s of station time
  EXPECT_EQ(r.link->counters().refused.timeout, 1u);
  EXPECT_EQ(r.listener.peer(), &wa);
  EXPECT_TRUE(r.link->admitted());
  EXPECT_EQ(r.link->counters().displaced, 0u);
  for (const auto& m : a.receive()) EXPECT_NE(type_of(m), MessageType::bye);
}

}  // namespace
}  // namespace twister::link
