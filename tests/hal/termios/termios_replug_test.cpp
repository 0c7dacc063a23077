// Fault recovery on a real PTY: the device hangs up, a new PTY appears behind the
// same symlink (moved with rename()), and reopen() on the unchanged path reconnects.
#include <gtest/gtest.h>
#include <stdio.h>
#include <unistd.h>

#include <array>
#include <chrono>

#include "support/poll_wait.hpp"
#include "support/pty_pair.hpp"
#include "twister/hal/termios_byte_stream.hpp"

namespace twister::hal {
namespace {

void link_to(const std::string& target, const std::string& link) {
  const std::string tmp = link + ".tmp";
  ::unlink(tmp.c_str());
  ASSERT_EQ(::symlink(target.c_str(), tmp.c_str()), 0);
  ASSERT_EQ(::rename(tmp.c_str(), link.c_str()), 0);
}

// Everything the stream delivers within `ms` ("<io_error>" appended on a hang-up).
std::string read_some(TermiosByteStream& s, int ms) {
  std::string out;
  std::array<std::byte, 64> buf{};
  const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(ms);
  for (;;) {
    auto n = s.read(buf);
    if (!n.ok()) return out + "<io_error>";
    out.append(reinterpret_cast<const char*>(buf.data()), *n);
    const int left = test::ms_until(end);
    if (left == 0) return out;
    // Input or a hang-up wakes the wait; a stream that closed itself has no fd and
    // its next read reports the hang-up.
    if (!test::wait_ready(s, left) && s.is_open()) return out;
  }
}

TEST(TermiosReplug, HangUpAndReturnBehindAStableSymlink) {
  const std::string link = ::testing::TempDir() + "fastrak_replug_" + std::to_string(::getpid());
  auto first = std::make_unique<test::PtyPair>();
  link_to(first->slave, link);
  TermiosByteStream s({link, 115200, FlowControl::none});
  ASSERT_TRUE(s.reopen().ok());
  first->write("A");
  EXPECT_EQ(read_some(s, 20), "A");

  // Unplug as twister-sim and udev do it: the link goes, then the line hangs up.
  // (A stale link is not tested: the /dev/pts number is reused by the next PTY that
  // any process opens.)
  ::unlink(link.c_str());
  first.reset();
  EXPECT_EQ(read_some(s, 5), "<io_error>");
  // Until the device returns, reopen() reports unavailable rather than failing hard.
  EXPECT_EQ(s.reopen().code(), StatusCode::unavailable);

  test::PtyPair second;
  link_to(second.slave, link);
  ASSERT_TRUE(s.reopen().ok());
  second.write("B");
  EXPECT_EQ(read_some(s, 20), "B");
  const char c = 'S';
  ASSERT_TRUE(s.write(std::as_bytes(std::span<const char>(&c, 1))).ok());
  EXPECT_EQ(second.read_all(), "S");
  ::unlink(link.c_str());
}

}  // namespace
}  // namespace twister::hal
