// Keyboard commands of the display (undo, redo, method) over the link: the bridge
// sends them only once its handshake is done, the station's link takes them only
// from the admitted display and hands them, in order, to the session's command
// path itself (issue 20: no round trip through the program); a stranger's command
// is dropped and counted.
#include <gtest/gtest.h>

#include <array>

#include "bridge_link_rig.hpp"
#include "twister/link/link_codec.hpp"
#include "window_input.hpp"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

namespace twister::bridge::test_support {
namespace {

std::vector<std::byte> command_frame(link::CommandKind kind) {
  link::Command m;
  m.kind = kind;
  std::vector<std::byte> frame(link::kMaxFrameBytes);
  frame.resize(*link::encode_frame(m, frame));
  return frame;
}

TEST(BridgeCommand, OnlyTheAdmittedDisplaysCommandsReachTheStation) {
  ports::NullLogSink log;
  BridgeLinkRig rig(log);
  // Before any hello: a command on the wire is not from an admitted display.
  const auto stranger = command_frame(link::CommandKind::undo);
  ASSERT_TRUE(rig.bridge_end.send(stranger).ok());
  rig.link->poll(*rig.station.session, rig.station.now_us);
  EXPECT_EQ(rig.link->counters().commands, 0u);
  EXPECT_EQ(rig.link->counters().commands_refused, 1u);
  EXPECT_FALSE(rig.bridge.send_command({link::CommandKind::undo, 0}))
      << "sent before the handshake";

  rig.run();
  ASSERT_TRUE(rig.bridge.ready());
  ASSERT_TRUE(rig.link->admitted());
  EXPECT_TRUE(rig.bridge.send_command({link::CommandKind::redo, 0}));
  EXPECT_TRUE(rig.bridge.send_command({link::CommandKind::set_method, 1}));
  rig.run(2);
  EXPECT_EQ(rig.link->counters().commands, 2u);
  EXPECT_EQ(rig.link->counters().commands_refused, 1u);
  // Queued in the session by the link; its next step runs them (redo: nothing to
  // redo; set_method 1: rottran).
  EXPECT_EQ(rig.station.session->method(), math::WarpMethod::twister);
  (void)rig.station.tick();
  EXPECT_EQ(rig.station.session->method(), math::WarpMethod::rottran);
}

TEST(BridgeCommand, UndoKeyUndoesTheStrokeOnTheStationAndTheDisplayFollows) {
  ports::NullLogSink log;
  BridgeLinkRig rig(log);
  rig.run();
  const std::uint64_t before = rig.station.session->mesh().checksum();
  rig.stroke(0.05);
  for (int i = 0; i < 4; ++i) {
    (void)rig.station.tick();
    rig.run(4);
  }
  ASSERT_NE(rig.station.session->mesh().checksum(), before);
  ASSERT_EQ(rig.bridge.replica().checksum(), rig.station.session->mesh().checksum());
  ASSERT_TRUE(rig.bridge.send_command({link::CommandKind::undo, 0}));
  rig.run(2);  // the link queues the undo in the session's command path
  EXPECT_EQ(rig.link->counters().commands, 1u);
  (void)rig.station.tick();
  EXPECT_EQ(rig.station.session->mesh().checksum(), before) << "not undone";
  rig.run(10);
  EXPECT_EQ(rig.bridge.replica().checksum(), before) << "the display did not follow";
}

TEST(BridgeCommand, EachLinkCommandMapsToItsSessionCommand) {
  using session::SessionCommandKind;
  EXPECT_EQ(station::session_command({link::CommandKind::undo, 0}).kind, SessionCommandKind::undo);
  EXPECT_EQ(station::session_command({link::CommandKind::redo, 0}).kind, SessionCommandKind::redo);
  EXPECT_EQ(station::session_command({link::CommandKind::next_method, 0}).kind,
            SessionCommandKind::next_method);
  const session::SessionCommand set = station::session_command({link::CommandKind::set_method, 2});
  EXPECT_EQ(set.kind, SessionCommandKind::set_method);
  EXPECT_EQ(set.method, math::WarpMethod::scodef);
}

// Issue 26: key S sends cycle_symmetry; the station steps its configured cycle and the
// display's status shows the next stroke's group.
TEST(BridgeCommand, SymmetryKeyCyclesTheStationsGroupAndTheStatusFollows) {
  EXPECT_EQ(key_action(GLFW_KEY_S), KeyAction::cycle_symmetry);
  EXPECT_EQ(station::session_command({link::CommandKind::cycle_symmetry, 0}).kind,
            session::SessionCommandKind::cycle_symmetry);
  session::SculptSessionConfig config = session::test_support::test_config();
  const math::SymmetrySpec rot6{math::SymmetryKind::rotation, 0, 2, 6};
  ASSERT_TRUE(config.symmetry_cycle.push({}).ok());
  ASSERT_TRUE(config.symmetry_cycle.push(rot6).ok());
  ports::NullLogSink log;
  BridgeLinkRig rig(log, config);
  rig.run();
  ASSERT_TRUE(rig.bridge.ready());
  ASSERT_TRUE(rig.bridge.replica().has_status());
  EXPECT_EQ(rig.bridge.replica().station_status().symmetry, (std::array<std::uint8_t, 4>{}));
  ASSERT_TRUE(rig.bridge.send_command({link::CommandKind::cycle_symmetry, 0}));
  rig.run(2);
  (void)rig.station.tick();
  rig.run(4);
  EXPECT_EQ(rig.bridge.replica().station_status().symmetry,
            (std::array<std::uint8_t, 4>{2, 0, 2, 6}));  // rotation about z, 6-fold
}

}  // namespace
}  // namespace twister::bridge::test_support
