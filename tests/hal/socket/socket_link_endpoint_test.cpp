// Issue 11 items 4 and 5 at the transport: link endpoints never destroy files
// (a path holding a regular file is refused and left byte-identical; a stale
// socket is replaced; a live station's socket is refused; the socket file is
// removed at exit, and only if it is still ours), the Unix socket's mode is
// explicit whatever the umask (0660 by default, also at umask 0) with an optional
// group, and TCP listens on loopback unless allowed otherwise. Label integrity.
#include <grp.h>
#include <gtest/gtest.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include "twister/hal/socket_link.hpp"

namespace twister::hal {
namespace {

std::string temp_path(const char* name) {
  return "/tmp/twister_endpoint_" + std::to_string(::getpid()) + "_" + name;
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

mode_t mode_of(const std::string& path) {
  struct stat st {};
  EXPECT_EQ(::lstat(path.c_str(), &st), 0) << path;
  return st.st_mode & 07777;
}

// Restores the umask at scope exit.
struct Umask {
  explicit Umask(mode_t m) : old(::umask(m)) {}
  ~Umask() { ::umask(old); }
  mode_t old;
};

TEST(LinkEndpoint, PathHoldingARegularFileIsRefusedAndLeftUntouched) {
  const std::string path = temp_path("journal.bin");
  {
    std::ofstream out(path, std::ios::binary);
    out << "TWJ1 a journal the station must never lose\n";
  }
  const std::string before = read_file(path);
  SocketLink server({"unix:" + path, true, 0});
  const auto opened = server.open();
  ASSERT_FALSE(opened);
  EXPECT_EQ(opened.error().status.code(), StatusCode::failed_precondition);
  EXPECT_NE(opened.error().message.find("is not a socket; left untouched"), std::string::npos)
      << opened.error().message;
  server.close();
  EXPECT_EQ(read_file(path), before);
  EXPECT_TRUE(S_ISREG([&] {
    struct stat st {};
    ::lstat(path.c_str(), &st);
    return st.st_mode;
  }()));
  ::unlink(path.c_str());
}

TEST(LinkEndpoint, StaleSocketIsReplacedLiveOneRefusedAndOursRemovedAtExit) {
  const std::string path = temp_path("link.sock");
  ::unlink(path.c_str());
  {
    // A stale socket: bound, never listened on, its process gone.
    const int fd = ::socket(AF_UNIX, SOCK_STREAM, 0);
    sockaddr_un un{};
    un.sun_family = AF_UNIX;
    std::snprintf(un.sun_path, sizeof un.sun_path, "%s", path.c_str());
    ASSERT_EQ(::bind(fd, reinterpret_cast<sockaddr*>(&un), sizeof un), 0);
    ::close(fd);
  }
  SocketLink first({"unix:" + path, true, 0});
  const auto opened = first.open();
  ASSERT_TRUE(opened) << opened.error().message;
  // A second station on the same path is refused; the first keeps its socket.
  SocketLink second({"unix:" + path, true, 0});
  const auto refused = second.open();
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.error().message.find("listens on it"), std::string::npos)
      << refused.error().message;
  second.close();
  struct stat st {};
  ASSERT_EQ(::lstat(path.c_str(), &st), 0);
  EXPECT_TRUE(S_ISSOCK(st.st_mode));
  first.close();
  EXPECT_NE(::lstat(path.c_str(), &st), 0);  // removed at exit
}

TEST(LinkEndpoint, SocketReplacedByAnotherFileIsNotRemovedAtExit) {
  const std::string path = temp_path("moved.sock");
  ::unlink(path.c_str());
  SocketLink server({"unix:" + path, true, 0});
  ASSERT_TRUE(server.open());
  ASSERT_EQ(::unlink(path.c_str()), 0);
  { std::ofstream(path) << "someone else's file\n"; }
  server.close();
  EXPECT_EQ(read_file(path), "someone else's file\n");
  ::unlink(path.c_str());
}

TEST(LinkEndpoint, SocketModeIsExplicitAtUmaskZeroAndGroupIsSet) {
  const Umask open_umask(0);
  const std::string path = temp_path("mode.sock");
  ::unlink(path.c_str());
  {
    SocketLink server({"unix:" + path, true, 0});
    ASSERT_TRUE(server.open());
    EXPECT_EQ(mode_of(path), 0660u);  // not 0777 from umask 0
  }
  const group* own = ::getgrgid(::getgid());
  ASSERT_NE(own, nullptr);
  SocketLinkConfig config("unix:" + path, true, 0);
  config.socket_mode = 0600;
  config.socket_group = own->gr_name;
  SocketLink server(config);
  const auto opened = server.open();
  ASSERT_TRUE(opened) << opened.error().message;
  EXPECT_EQ(mode_of(path), 0600u);
  struct stat st {};
  ::lstat(path.c_str(), &st);
  EXPECT_EQ(st.st_gid, own->gr_gid);
  server.close();
  config.socket_group = "no-such-group-twister";
  SocketLink unknown(config);
  const auto bad = unknown.open();
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().status.code(), StatusCode::invalid_argument);
  EXPECT_NE(::access(path.c_str(), F_OK), 0);  // nothing left behind
}

TEST(LinkEndpoint, TcpListensOnLoopbackUnlessNetworkIsAllowed) {
  const std::string any = "tcp:0.0.0.0:" + std::to_string(21000 + ::getpid() % 20000);
  SocketLink open_to_all({any, true, 0});
  const auto refused = open_to_all.open();
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.error().status.code(), StatusCode::invalid_argument);
  EXPECT_NE(refused.error().message.find("beyond loopback"), std::string::npos);
  SocketLinkConfig config(any, true, 0);
  config.allow_network = true;
  SocketLink allowed(config);
  EXPECT_TRUE(allowed.open());
  SocketLink loopback({"tcp:127.0.0.1:" + std::to_string(41000 + ::getpid() % 20000), true, 0});
  EXPECT_TRUE(loopback.open());
}

}  // namespace
}  // namespace twister::hal
