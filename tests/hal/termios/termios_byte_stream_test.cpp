// TermiosByteStream on a PTY pair: raw 8N1 both ways, non-blocking reads, config
// errors, and hang-up seen as io_error (never a bare read() == 0).
#include "twister/hal/termios_byte_stream.hpp"

#include <gtest/gtest.h>

#include <array>
#include <chrono>

#include "support/poll_wait.hpp"
#include "support/pty_pair.hpp"

namespace twister::hal {
namespace {

// Reads until `want` bytes arrived or `ms` passed (generous: the machine may be busy).
std::string read_for(TermiosByteStream& s, std::size_t want, int ms = 5000) {
  std::string out;
  const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(ms);
  std::array<std::byte, 256> buf{};
  while (out.size() < want) {
    auto n = s.read(buf);
    if (!n.ok()) break;
    out.append(reinterpret_cast<const char*>(buf.data()), *n);
    if (out.size() < want && !test::wait_ready(s, test::ms_until(end))) break;
  }
  return out;
}

TEST(TermiosByteStream, RawBytesBothWays) {
  test::PtyPair pty;
  ASSERT_GE(pty.master, 0);
  TermiosByteStream s({pty.slave, 115200, FlowControl::none});
  ASSERT_TRUE(s.reopen().ok());
  std::array<std::byte, 16> buf{};
  auto n = s.read(buf);  // nothing yet: 0, not an error, no wait
  ASSERT_TRUE(n.ok());
  EXPECT_EQ(*n, 0u);
  const std::string binary("0\x01 \xff\r\n\x13\x11\x00\x19", 10);
  pty.write(binary);
  EXPECT_EQ(read_for(s, binary.size()),
            binary);  // no CR/LF mapping, 0xFF not doubled, ^S/^Q passed
  const std::string cmd = "O1,2,11,1\r";
  auto w = s.write(std::as_bytes(std::span<const char>(cmd.data(), cmd.size())));
  ASSERT_TRUE(w.ok());
  EXPECT_EQ(*w, cmd.size());
  EXPECT_EQ(pty.read_all(), cmd);
}

TEST(TermiosByteStream, DiscardInputDropsPendingBytes) {
  test::PtyPair pty;
  TermiosByteStream s({pty.slave, 19200, FlowControl::rts_cts});
  ASSERT_TRUE(s.reopen().ok());
  pty.write("stale bytes");
  ASSERT_TRUE(pty.wait_slave_pending(11));
  s.discard_input();
  pty.write("fresh");
  EXPECT_EQ(read_for(s, 5), "fresh");
  EXPECT_EQ(read_for(s, 1, 50), "");  // nothing stale behind it
}

TEST(TermiosByteStream, ConfigurationErrors) {
  TermiosByteStream bad_baud({"/dev/null", 12345, FlowControl::none});
  EXPECT_EQ(bad_baud.reopen().code(), StatusCode::invalid_argument);
  TermiosByteStream missing({"/nonexistent/ttyFASTRAK", 115200, FlowControl::none});
  EXPECT_EQ(missing.reopen().code(), StatusCode::unavailable);
  std::array<std::byte, 4> buf{};
  EXPECT_EQ(missing.read(buf).status().code(), StatusCode::io_error);
  unsigned speed = 0;
  EXPECT_TRUE(baud_to_speed(9600, speed));
  EXPECT_FALSE(baud_to_speed(1000, speed));
}

TEST(TermiosByteStream, HangUpIsDisconnected) {
  auto pty = std::make_unique<test::PtyPair>();
  const std::string path = pty->slave;
  TermiosByteStream s({path, 115200, FlowControl::none});
  ASSERT_TRUE(s.reopen().ok());
  pty->write("last");
  EXPECT_EQ(read_for(s, 4), "last");
  pty.reset();  // the device side goes away
  std::array<std::byte, 16> buf{};
  auto n = s.read(buf);
  EXPECT_EQ(n.status().code(), StatusCode::io_error);
  EXPECT_FALSE(s.is_open());
  // Writing on a closed port is an error as well.
  const char c = 'S';
  EXPECT_EQ(s.write(std::as_bytes(std::span<const char>(&c, 1))).status().code(),
            StatusCode::io_error);
}

}  // namespace
}  // namespace twister::hal
