// Issue 20: StationLink is a coordinator of four parts with one job each; each is
// tested here alone (label architecture):
//   FrameQueues    urgent frames overtake bulk ones at a frame boundary; a bulk
//                  mark/rewind drops a half commit; interrupt_with() ends a torn
//                  frame and says bye;
//   LinkAdmission  hello admits (no key), the admitted display's resend and
//                  command reach the listener, a stranger's command does not, a
//                  lost channel is reported;
//   MeshMirror     a full send from the shadow, then one change set per commit;
//   LiveStream     hands, object and status once, nothing while nothing changes,
//                  everything again after restart().
#include <gtest/gtest.h>

#include <vector>

#include "fakes/memory_wire.hpp"
#include "session_harness.hpp"
#include "twister/station/station_link_admission.hpp"
#include "twister/station/station_link_live.hpp"
#include "twister/station/station_link_mirror.hpp"
#include "twister/station/station_link_queues.hpp"

namespace twister::station {
namespace {

using link::MessageType;

// The display's end of a wire: sends frames, decodes what arrives.
struct Display {
  explicit Display(test::MemoryWire& w) : end(w, false) {}
  template <link::LinkBody M>
  void send(const M& m) {
    std::vector<std::byte> f(link::kMaxFrameBytes);
    const auto n = link::encode_frame(m, f);
    ASSERT_TRUE(n.ok());
    ASSERT_EQ(*end.send(std::span<const std::byte>(f).first(*n)), *n);
  }
  std::vector<link::LinkMessage> receive() {
    std::vector<link::LinkMessage> got;
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
  link::LinkDecoder decoder;
};

std::vector<MessageType> types(const std::vector<link::LinkMessage>& ms) {
  std::vector<MessageType> out;
  for (const auto& m : ms) out.push_back(link::type_of(m));
  return out;
}

// A port that takes at most `chunk` bytes per send (a slow line).
class SlowPort final : public ports::LinkPort {
 public:
  explicit SlowPort(ports::LinkPort& inner, std::size_t chunk) : inner_(inner), chunk_(chunk) {}

 private:
  Result<std::size_t> do_send(std::span<const std::byte> src) override {
    return inner_.send(src.first(std::min(src.size(), chunk_)));
  }
  Result<std::size_t> do_receive(std::span<std::byte> dest) override {
    return inner_.receive(dest);
  }
  ports::LinkPort& inner_;
  std::size_t chunk_;
};

TEST(FrameQueues, UrgentFramesOvertakeBulkOnesAtAFrameBoundary) {
  test::MemoryWire wire;
  test::MemoryLinkEnd station_end(wire, true);
  SlowPort slow(station_end, 100);
  Display display(wire);
  std::vector<std::byte> bulk(8 * link::kMaxFrameBytes);
  FrameQueues q(slow, bulk);
  link::Vertices v;
  v.count = 50;  // 800 bytes: several sends each
  ASSERT_TRUE(q.bulk(v));
  ASSERT_TRUE(q.bulk(v));
  q.flush();  // the first vertices frame is under way
  ASSERT_TRUE(q.urgent(link::Hands{}));
  for (int i = 0; i < 100 && q.pending_bytes() > 0; ++i) q.flush();
  EXPECT_EQ(
      types(display.receive()),
      (std::vector<MessageType>{MessageType::vertices, MessageType::hands, MessageType::vertices}));
  // A half commit never stays queued.
  const std::size_t mark = q.bulk_mark();
  ASSERT_TRUE(q.bulk(link::MeshBegin{}));
  q.bulk_rewind(mark);
  EXPECT_EQ(q.pending_bytes(), 0u);
  // interrupt_with: 0x00 ends the display's half frame, then the bye; queues dropped.
  ASSERT_TRUE(q.bulk(v));
  q.flush();
  q.interrupt_with(link::Bye{link::ByeReason::displaced});
  EXPECT_EQ(q.pending_bytes(), 0u);
  const auto got = display.receive();
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(std::get<link::Bye>(got[0]).reason, link::ByeReason::displaced);
}

struct Recorder final : AdmissionListener {
  void on_admitted(const MeshIdentity& h) override {
    ++admitted;
    holds = h;
  }
  void on_display_lost() override { ++lost; }
  void on_resend_request() override { ++resends; }
  void on_command(const link::Command& c) override { commands.push_back(c); }
  MeshIdentity offered() override { return ours; }
  MeshIdentity ours{};  // what the station offers in its hello
  int admitted = 0;
  int lost = 0;
  int resends = 0;
  MeshIdentity holds{};
  std::vector<link::Command> commands;
};

TEST(LinkAdmission, HelloAdmitsAndOnlyTheAdmittedDisplaysRequestsReachTheListener) {
  test::MemoryWire wire;
  test::MemoryLinkEnd station_end(wire, true);
  Display display(wire);
  std::vector<std::byte> bulk(4 * link::kMaxFrameBytes);
  FrameQueues q(station_end, bulk);
  Recorder r;
  LinkAdmission a(station_end, q, r, StationLinkOptions{}, 2'000'000);
  r.ours = MeshIdentity{3, 0xabcdef};
  display.send(link::Command{link::CommandKind::undo, 0});  // before any hello
  a.poll(0);
  EXPECT_TRUE(a.connected());
  EXPECT_FALSE(a.admitted());
  EXPECT_EQ(a.counters().commands_refused, 1u);
  display.send(link::Hello{link::Role::bridge, 0, 2, 7, {}});
  a.poll(1000);
  ASSERT_TRUE(a.admitted());
  EXPECT_EQ(r.admitted, 1);
  EXPECT_EQ(r.holds.version, 2u);
  EXPECT_EQ(r.holds.checksum, 7u);
  q.flush();
  const auto reply = display.receive();
  ASSERT_EQ(reply.size(), 1u);
  EXPECT_EQ(std::get<link::Hello>(reply[0]).mesh_version, 3u);
  EXPECT_EQ(std::get<link::Hello>(reply[0]).mesh_checksum, 0xabcdefu);
  display.send(link::ResendRequest{});
  display.send(link::Command{link::CommandKind::set_method, 2});
  a.poll(2000);
  EXPECT_EQ(r.resends, 1);
  ASSERT_EQ(r.commands.size(), 1u);
  EXPECT_EQ(r.commands[0].method, 2u);
  display.send(link::Hands{});  // only the station sends hands
  a.poll(3000);
  EXPECT_EQ(a.counters().refused.protocol, 1u);
  wire.cut();
  a.poll(4000);
  EXPECT_FALSE(a.connected());
  EXPECT_EQ(r.lost, 1);
  EXPECT_EQ(a.counters().disconnects, 1u);
}

TEST(MeshMirror, FullSendFromTheShadowThenOneChangeSetPerCommit) {
  test::MemoryWire wire;
  test::MemoryLinkEnd station_end(wire, true);
  Display display(wire);
  std::vector<std::byte> bulk(16 * link::kMaxFrameBytes);
  FrameQueues q(station_end, bulk);
  session::test_support::TestMesh mesh;
  session::test_support::make_grid(mesh, 33);  // 1089 vertices, 2048 triangles
  std::vector<float> x(mesh.vertex_capacity()), y(x.size()), z(x.size());
  std::vector<std::uint32_t> idx(3 * mesh.triangle_capacity());
  MeshMirror mirror(q, MeshMirrorStorage{x, y, z, idx});
  ASSERT_TRUE(mirror.start(mesh).ok());
  EXPECT_EQ(mirror.offered().version, 1u);
  EXPECT_EQ(mirror.offered().checksum, mesh.checksum());
  mirror.resync(mirror.offered());  // holds ours: nothing to send
  EXPECT_TRUE(mirror.idle());
  mirror.resync(MeshIdentity{});
  for (int i = 0; i < 20 && !mirror.idle(); ++i) {
    mirror.send();
    q.flush();
  }
  auto got = display.receive();
  ASSERT_GE(got.size(), 4u);
  EXPECT_TRUE(std::get<link::MeshBegin>(got.front()).full);
  EXPECT_EQ(std::get<link::MeshEnd>(got.back()).checksum, mesh.checksum());
  EXPECT_EQ(mirror.counters().full_sends, 1u);
  mesh.set_position(5, {0.0F, 0.0F, 0.25F});
  mirror.track(mesh, true);
  q.flush();
  got = display.receive();
  EXPECT_EQ(types(got), (std::vector<MessageType>{MessageType::mesh_begin, MessageType::vertices,
                                                  MessageType::mesh_end}));
  EXPECT_EQ(std::get<link::Vertices>(got[1]).count, 1u);
  EXPECT_EQ(std::get<link::MeshEnd>(got[2]).version, 2u);
  EXPECT_EQ(std::get<link::MeshEnd>(got[2]).checksum, mesh.checksum());
  EXPECT_EQ(mirror.counters().commits_sent, 1u);
}

TEST(LiveStream, SendsWhatChangedAndEverythingAgainAfterRestart) {
  test::MemoryWire wire;
  test::MemoryLinkEnd station_end(wire, true);
  Display display(wire);
  std::vector<std::byte> bulk(4 * link::kMaxFrameBytes);
  FrameQueues q(station_end, bulk);
  LiveStreamConfig config;
  config.workspace.flags = link::kWorkspaceCalibrated;
  config.workspace.max = {0.3F, 0.3F, 0.4F};
  LiveStream live(q, config);
  session::test_support::Station s;
  live.poll(*s.session, StationStatus{}, LinkFacts{1, 0}, 0);
  q.flush();
  const auto first = display.receive();
  EXPECT_EQ(types(first), (std::vector<MessageType>{MessageType::workspace, MessageType::object,
                                                    MessageType::hands, MessageType::status}));
  ASSERT_FALSE(first.empty());
  ASSERT_TRUE(std::holds_alternative<link::Workspace>(first[0]));
  EXPECT_EQ(std::get<link::Workspace>(first[0]).flags, link::kWorkspaceCalibrated);
  EXPECT_EQ(std::get<link::Workspace>(first[0]).max, glm::vec3(0.3F, 0.3F, 0.4F));
  live.poll(*s.session, StationStatus{}, LinkFacts{1, 0}, 10'000);
  q.flush();
  EXPECT_TRUE(display.receive().empty()) << "nothing changed";
  s.hand(0, math::identity_frame({0.1, 0.0, 0.0}));
  (void)s.tick();
  live.poll(*s.session, StationStatus{}, LinkFacts{1, 0}, 20'000);
  q.flush();
  const auto got = display.receive();
  ASSERT_EQ(types(got), std::vector<MessageType>{MessageType::hands});
  EXPECT_EQ(std::get<link::Hands>(got[0]).sequence, 1u);
  EXPECT_EQ(live.counters().live_sent, 2u);
  live.restart();
  live.poll(*s.session, StationStatus{}, LinkFacts{1, 0}, 30'000);
  q.flush();
  EXPECT_EQ(display.receive().size(), 4u) << "the workspace, object, hands and status again";
}

}  // namespace
}  // namespace twister::station
