// The journal lock and the atomic file sink (issue 11, items 1 and 3): a second
// opener of a locked journal is refused and told the holder's PID, the lock dies with
// its process, and PosixFileSink never replaces a file it must not (never mode picks
// a new name; regular mode refuses FIFOs, directories and symlinks; own_magic refuses
// files it did not write) and leaves no temporary behind.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "twister/hal/posix_file_sink.hpp"
#include "twister/hal/posix_file_storage.hpp"

namespace twister::hal {
namespace {

namespace fs = std::filesystem;

class PosixFileIntegrity : public ::testing::Test {
 protected:
  void SetUp() override { fs::create_directories(dir_); }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const char* name) const { return (dir_ / name).string(); }
  static std::string read(const std::string& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }
  std::size_t entries() const {
    std::size_t n = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir_)) ++n;
    return n;
  }
  Status sink_write(PosixFileSink& sink, const std::string& text) {
    TWISTER_TRY(sink.begin());
    TWISTER_TRY(sink.write(std::as_bytes(std::span(text.data(), text.size()))));
    return sink.commit();
  }
  static PosixFileSinkConfig config(const std::string& p, PosixFileSinkConfig::Replace replace) {
    PosixFileSinkConfig c;
    c.path = p;
    c.replace = replace;
    return c;
  }
  fs::path dir_ = fs::temp_directory_path() / ("posix_integrity_" + std::to_string(::getpid()));
};

TEST_F(PosixFileIntegrity, ASecondStationIsRefusedAndToldTheHoldersPid) {
  const std::string journal = path("j.twj");
  int ready[2];
  int done[2];
  ASSERT_EQ(::pipe(ready), 0);
  ASSERT_EQ(::pipe(done), 0);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {  // the first station: holds the lock until told to go
    PosixFileStorage first;
    const bool locked = first.open({.path = journal, .lock = true}).ok();
    char c = locked ? 'y' : 'n';
    (void)!::write(ready[1], &c, 1);
    (void)!::read(done[0], &c, 1);
    ::_exit(0);
  }
  char c = 0;
  ASSERT_EQ(::read(ready[0], &c, 1), 1);
  ASSERT_EQ(c, 'y');
  PosixFileStorage second;
  EXPECT_EQ(second.open({.path = journal, .lock = true}).code(), StatusCode::failed_precondition);
  EXPECT_EQ(second.lock_holder_pid(), child);
  EXPECT_FALSE(second.is_open());
  // Without a lock request (tools that only read) the file still opens.
  PosixFileStorage reader;
  EXPECT_TRUE(reader.open({.path = journal, .create_if_missing = false, .read_only = true}).ok());
  // The holder dies (however it ends): the lock goes with it.
  ::kill(child, SIGKILL);
  int status = 0;
  ::waitpid(child, &status, 0);
  EXPECT_TRUE(second.open({.path = journal, .lock = true}).ok());
  // Another description in this very process is refused too (OFD locks).
  PosixFileStorage third;
  EXPECT_EQ(third.open({.path = journal, .lock = true}).code(), StatusCode::failed_precondition);
  ::close(ready[0]);
  ::close(ready[1]);
  ::close(done[0]);
  ::close(done[1]);
}

TEST_F(PosixFileIntegrity, NeverModeNeverReplacesAndPicksANewName) {
  const std::string base = path("j.twj.torn-tail");
  std::ofstream(base) << "older tail";
  PosixFileSink sink(config(base, PosixFileSinkConfig::Replace::never));
  ASSERT_TRUE(sink_write(sink, "new tail").ok()) << sink.last_error();
  EXPECT_EQ(std::string(sink.committed_path()), base + ".1");
  EXPECT_EQ(read(base), "older tail");
  EXPECT_EQ(read(base + ".1"), "new tail");
  ASSERT_TRUE(sink_write(sink, "third").ok());
  EXPECT_EQ(std::string(sink.committed_path()), base + ".2");
  EXPECT_EQ(entries(), 3u);
}

TEST_F(PosixFileIntegrity, RegularModeRefusesEverythingButARegularFile) {
  const std::string fifo = path("fifo");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const std::string subdir = path("dir");
  fs::create_directory(subdir);
  const std::string link = path("link");
  std::ofstream(path("target")) << "target";
  fs::create_symlink(path("target"), link);
  for (const std::string& p : {fifo, subdir, link}) {
    PosixFileSink sink(config(p, PosixFileSinkConfig::Replace::regular));
    EXPECT_EQ(sink_write(sink, "x").code(), StatusCode::failed_precondition) << p;
    EXPECT_NE(std::string(sink.last_error()).find("it is not replaced"), std::string::npos);
  }
  EXPECT_TRUE(fs::is_fifo(fifo));
  EXPECT_TRUE(fs::is_directory(subdir));
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_EQ(read(path("target")), "target");
  PosixFileSink sink(config(path("target"), PosixFileSinkConfig::Replace::regular));
  ASSERT_TRUE(sink_write(sink, "replaced").ok());
  EXPECT_EQ(read(path("target")), "replaced");
  EXPECT_EQ(entries(), 4u);  // no temporary file left
}

TEST_F(PosixFileIntegrity, OwnMagicModeReplacesOnlyItsOwnFiles) {
  const std::string ckpt = path("j.twj.ckpt");
  std::ofstream(ckpt) << "somebody else's file";
  PosixFileSinkConfig own = config(ckpt, PosixFileSinkConfig::Replace::own_magic);
  for (const char ch : std::string("TWCK")) own.magic.push_back(static_cast<std::byte>(ch));
  PosixFileSink sink(own);
  EXPECT_EQ(sink_write(sink, "TWCK new").code(), StatusCode::failed_precondition);
  EXPECT_EQ(read(ckpt), "somebody else's file");
  fs::remove(ckpt);
  ASSERT_TRUE(sink_write(sink, "TWCK first").ok());
  ASSERT_TRUE(sink_write(sink, "TWCK second").ok());
  EXPECT_EQ(read(ckpt), "TWCK second");
  // An aborted write leaves the old file and nothing else.
  ASSERT_TRUE(sink.begin().ok());
  ASSERT_TRUE(sink.write(std::as_bytes(std::span("TWCK half", 9))).ok());
  sink.abort();
  EXPECT_EQ(read(ckpt), "TWCK second");
  EXPECT_EQ(entries(), 1u);
}

}  // namespace
}  // namespace twister::hal
