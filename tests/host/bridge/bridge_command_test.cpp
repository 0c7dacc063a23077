// Keyboard commands of the display (undo, redo, method) over the link: the bridge
// sends them only once its handshake is done, the station takes them only from
// the admitted display, in order; a stranger's command is dropped and counted.
#include <gtest/gtest.h>

#include <array>

#include "bridge_link_rig.hpp"
#include "twister/link/link_codec.hpp"

namespace twister::bridge::test_support {
namespace {

std::vector<std::byte> command_frame(link::CommandKind kind) {
  link::LinkMessage m;
  m.type = link::MessageType::command;
  m.command.kind = kind;
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
  link::Command got;
  EXPECT_FALSE(rig.link->take_command(got));
  EXPECT_EQ(rig.link->counters().commands_refused, 1u);
  EXPECT_FALSE(rig.bridge.send_command({link::CommandKind::undo, 0}))
      << "sent before the handshake";

  rig.run();
  ASSERT_TRUE(rig.bridge.ready());
  ASSERT_TRUE(rig.link->admitted());
  EXPECT_TRUE(rig.bridge.send_command({link::CommandKind::redo, 0}));
  EXPECT_TRUE(rig.bridge.send_command({link::CommandKind::set_method, 1}));
  rig.run(2);
  ASSERT_TRUE(rig.link->take_command(got));
  EXPECT_EQ(got.kind, link::CommandKind::redo);
  ASSERT_TRUE(rig.link->take_command(got));
  EXPECT_EQ(got.kind, link::CommandKind::set_method);
  EXPECT_EQ(got.method, 1u);
  EXPECT_FALSE(rig.link->take_command(got));
  EXPECT_EQ(rig.link->counters().commands, 2u);
  EXPECT_EQ(rig.link->counters().commands_refused, 1u);
}

}  // namespace
}  // namespace twister::bridge::test_support
