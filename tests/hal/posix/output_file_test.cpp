// The programs' output rule (issue 21 item 1), the sink's checkpoint replacement and
// stale temporaries (item 7), and non-blocking opens by type (item 4).
#include "twister/hal/output_file.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "twister/checkpoint/session_checkpoint.hpp"
#include "twister/hal/posix_file_sink.hpp"
#include "twister/hal/posix_file_storage.hpp"
#include "twister/journal/journal_record.hpp"

namespace twister::hal {
namespace {

namespace fs = std::filesystem;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void put(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

class OutputFile : public ::testing::Test {
 protected:
  void SetUp() override { fs::create_directories(dir_); }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  // Refused with a message containing `why`, and the file is byte-identical.
  void expect_refused(const std::string& p, OutputRule rule, const std::string& why) {
    const std::string before = fs::is_regular_file(p) ? slurp(p) : "";
    const auto checked = check_output_path(p, rule);
    ASSERT_FALSE(checked) << p;
    EXPECT_NE(checked.error().message.find(why), std::string::npos) << checked.error().message;
    const auto written = write_output_file(p, "v 0 0 0\n", rule);
    ASSERT_FALSE(written) << p;
    EXPECT_EQ(written.error().status.code(), StatusCode::failed_precondition);
    if (fs::is_regular_file(fs::symlink_status(p))) {
      EXPECT_EQ(slurp(p), before) << p;
    }
  }
  fs::path dir_ = fs::temp_directory_path() / ("output_file_" + std::to_string(::getpid()));
};

TEST_F(OutputFile, MagicsAreTheJournalsAndTheCheckpoints) {
  EXPECT_EQ(std::memcmp(kJournalMagic, journal::kFileMagic.data(), 4), 0);
  EXPECT_EQ(std::memcmp(kCheckpointMagic, checkpoint::kCheckpointMagic.data(), 4), 0);
}

TEST_F(OutputFile, NeverAJournalCheckpointLockedFileOrAnotherKindForceOnlyTheSameKind) {
  const OutputRule obj{OutputKind::obj, false};
  const OutputRule forced{OutputKind::obj, true};
  // Nothing there: written.
  ASSERT_TRUE(write_output_file(path("new.obj"), "v 0 0 0\n", obj));
  // An OBJ: only with force.
  expect_refused(path("new.obj"), obj, "--force replaces");
  ASSERT_TRUE(write_output_file(path("new.obj"), "# again\nv 1 0 0\n", forced));
  EXPECT_EQ(slurp(path("new.obj")), "# again\nv 1 0 0\n");
  // A journal and a checkpoint: never, even forced, whatever the name.
  put(path("j.obj"), std::string("TWJL\x01\0\0\0", 8) + "records");
  expect_refused(path("j.obj"), forced, "is a journal");
  put(path("c.obj"), "TWCK\x02" + std::string(300, '\0'));
  expect_refused(path("c.obj"), forced, "is a station checkpoint");
  // Another kind: text that is no OBJ, a PLY asked to be an OBJ, a PNG for an SVG.
  put(path("notes.obj"), "precious notes\n");
  expect_refused(path("notes.obj"), forced, "first bytes are not OBJ");
  put(path("mesh.obj"), "ply\nformat binary_little_endian 1.0\n");
  expect_refused(path("mesh.obj"), forced, "first bytes are not OBJ");
  put(path("p.svg"), "\x89PNG\r\n\x1a\n....");
  expect_refused(path("p.svg"), {OutputKind::svg, true}, "first bytes are not SVG");
  ASSERT_TRUE(write_output_file(path("p.png"), "\x89PNG\r\n\x1a\nnew", {OutputKind::png, false}));
  EXPECT_TRUE(write_output_file(path("p.png"), "\x89PNG\r\n\x1a\nnewer", {OutputKind::png, true}));
  // An empty file holds nothing: replaced when forced.
  put(path("empty.obj"), "");
  EXPECT_TRUE(write_output_file(path("empty.obj"), "v 0 0 0\n", forced));
  // FIFOs, directories and symbolic links: never (the FIFO never blocks the check).
  ASSERT_EQ(::mkfifo(path("fifo.obj").c_str(), 0600), 0);
  expect_refused(path("fifo.obj"), forced, "is a FIFO");
  fs::create_directories(path("dir.obj"));
  expect_refused(path("dir.obj"), forced, "is a directory");
  fs::create_symlink(path("new.obj"), path("link.obj"));
  expect_refused(path("link.obj"), forced, "is a symbolic link");
  // No temporary file is ever left behind.
  for (const auto& e : fs::directory_iterator(dir_)) {
    EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos) << e.path();
  }
}

TEST_F(OutputFile, ALockedFileIsRefused) {
  // The station's journal lock (exclusive) and its base model's (shared).
  put(path("journal.obj"), "v 0 0 0\n");
  PosixFileStorage journal;
  ASSERT_TRUE(journal.open({.path = path("journal.obj"), .lock = true}).ok());
  // (In this process the holder's PID cannot be seen: classic locks never conflict
  // within a process; the station test sees it from another process.)
  expect_refused(path("journal.obj"), {OutputKind::obj, true}, "is in use (locked");
  put(path("base.obj"), "v 0 0 0\n");
  {
    auto held = FileReadLock::hold(path("base.obj"));
    ASSERT_TRUE(held) << held.error().message;
    auto second = FileReadLock::hold(path("base.obj"));  // readers share it
    ASSERT_TRUE(second) << second.error().message;
    expect_refused(path("base.obj"), {OutputKind::obj, true}, "is in use");
  }
  EXPECT_TRUE(check_output_path(path("base.obj"), {OutputKind::obj, true}));  // released
  EXPECT_TRUE(same_file(path("base.obj"), (dir_ / "." / "base.obj").string()));
  EXPECT_FALSE(same_file(path("base.obj"), path("journal.obj")));
}

TEST_F(OutputFile, AnEmptyCheckpointIsReplacedAForeignFileNever) {
  PosixFileSinkConfig config;
  config.path = path("j.twj.ckpt");
  config.replace = PosixFileSinkConfig::Replace::own_magic;
  config.magic.assign(checkpoint::kCheckpointMagic.begin(), checkpoint::kCheckpointMagic.end());
  const std::string checkpoint = "TWCK" + std::string(16, 'x');
  auto write = [&config, &checkpoint] {
    PosixFileSink sink(config);
    Status s = sink.begin();
    if (s.ok()) s = sink.write(std::as_bytes(std::span(checkpoint.data(), checkpoint.size())));
    if (s.ok()) s = sink.commit();
    return s;
  };
  put(config.path, "");  // a writer that died before it wrote anything
  ASSERT_TRUE(write().ok());
  EXPECT_EQ(slurp(config.path), checkpoint);
  put(config.path, "someone's notes");
  EXPECT_EQ(write().code(), StatusCode::failed_precondition);
  EXPECT_EQ(slurp(config.path), "someone's notes");
}

TEST_F(OutputFile, StaleTemporariesOfOurOwnPatternAloneAreRemoved) {
  const std::string ckpt = path("j.twj.ckpt");
  for (const char* name :
       {"j.twj.ckpt.tmp-123-0", "j.twj.ckpt.tmp-9-17", "j.twj.ckpt.tmp-abc", "j.twj.ckpt.tmp-1-2-3",
        "j.twj.ckpt.tmp-12", "k.twj.ckpt.tmp-1-1", "j.twj.ckpt", "j.twj.ckpt.tmp-5-5x"}) {
    put(path(name), "x");
  }
  fs::create_directories(path("j.twj.ckpt.tmp-7-7"));  // not a regular file: kept
  EXPECT_EQ(PosixFileSink::remove_stale_temporaries(ckpt), 2);
  EXPECT_FALSE(fs::exists(path("j.twj.ckpt.tmp-123-0")));
  EXPECT_FALSE(fs::exists(path("j.twj.ckpt.tmp-9-17")));
  for (const char* kept :
       {"j.twj.ckpt.tmp-abc", "j.twj.ckpt.tmp-1-2-3", "j.twj.ckpt.tmp-12", "k.twj.ckpt.tmp-1-1",
        "j.twj.ckpt", "j.twj.ckpt.tmp-5-5x", "j.twj.ckpt.tmp-7-7"}) {
    EXPECT_TRUE(fs::exists(path(kept))) << kept;
  }
}

TEST_F(OutputFile, StorageOpensAFifoOrDeviceWithoutBlockingAndRefusesIt) {
  ASSERT_EQ(::mkfifo(path("fifo").c_str(), 0600), 0);
  const auto start = std::chrono::steady_clock::now();
  PosixFileStorage storage;
  EXPECT_EQ(
      storage.open({.path = path("fifo"), .create_if_missing = false, .read_only = true}).code(),
      StatusCode::invalid_argument);
  EXPECT_EQ(storage.open({.path = path("fifo"), .lock = true}).code(),
            StatusCode::invalid_argument);
  EXPECT_EQ(storage.open({.path = "/dev/zero", .read_only = true}).code(),
            StatusCode::invalid_argument);
  EXPECT_EQ(storage.open({.path = dir_.string(), .read_only = true}).code(),
            StatusCode::invalid_argument);
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(1));
  EXPECT_FALSE(storage.is_open());
}

}  // namespace
}  // namespace twister::hal
