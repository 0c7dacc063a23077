// twister-station, `twister replay` and `twister journal check|salvage` on journals that
// must prove their order (issue 21, items 2, 3 and the journal's part of 7), as processes:
// duplicated, spliced, missing and too-new records are refused with their offsets by all
// three (check exits 1), salvage keeps the longest ordered valid prefix; a torn tail is
// not cut when start-up then fails on the link; a NUL in the journal path fails --check;
// a new journal the file system cannot hold says why.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <unistd.h>

#include <filesystem>
#include <functional>

#include "station_test_support.hpp"
#include "twister/base/checksum.hpp"
#include "twister/journal/journal_format.hpp"
#include "twister/journal/journal_writer.hpp"

namespace twister::station_test {
namespace {

namespace fs = std::filesystem;

class StationOrderIntegrity : public ::testing::Test {
 protected:
  void SetUp() override { fs::create_directories(dir_); }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::string config_for(const std::string& journal) {
    const std::string scn = path("chains.scn");
    write_file(scn, chain_scenario(1, 0));
    const std::string cfg = path("station.toml");
    write_file(cfg, sim_config(journal, scn));
    return cfg;
  }
  RunResult station(const std::string& args) {
    return run_command(std::string(TWISTER_STATION_BIN) + " " + args);
  }
  RunResult cli(const std::string& args) {
    return run_command(std::string(TWISTER_CLI_BIN) + " " + args);
  }
  // Six one-hand strokes on the deploy sphere in a journal of identity `id`; returns
  // the record offsets (and the end).
  std::vector<std::size_t> write_strokes(const std::string& journal, std::uint32_t id) {
    hal::PosixFileStorage storage;
    EXPECT_TRUE(storage.open({.path = journal}).ok());
    journal::JournalWriter writer(storage);
    writer.set_new_journal_id(id);
    EXPECT_TRUE(writer.open().ok());
    std::vector<std::size_t> at;
    for (std::uint32_t k = 0; k < 6; ++k) {
      at.push_back(static_cast<std::size_t>(writer.size()));
      journal::JournalRecord r;
      r.sequence = k;
      r.stroke.hand_mask = 1;
      r.stroke.radius_m = 0.06;
      r.stroke.start[0].origin = {0.30, -0.18, 0.15};
      r.stroke.end[0].origin = {0.30 + 0.002 * k, -0.18, 0.16};
      EXPECT_TRUE(writer.append(r).ok());
    }
    at.push_back(static_cast<std::size_t>(writer.size()));
    return at;
  }
  fs::path dir_ = fs::temp_directory_path() / ("station_order_" + std::to_string(::getpid()));
};

std::string slice(const std::string& s, std::size_t from, std::size_t to) {
  return s.substr(from, to - from);
}

void reseal(std::string& record) {
  const std::size_t body = record.size() - 4;
  const std::uint32_t crc = crc32(std::as_bytes(std::span(record.data(), body)));
  for (std::size_t i = 0; i < 4; ++i)
    record[body + i] = static_cast<char>((crc >> (8 * i)) & 0xffu);
}

TEST_F(StationOrderIntegrity, DuplicateSplicedGapAndTooNewRecordsAreRefusedWithOffsets) {
  const std::string clean = path("clean.twj");
  const auto at = write_strokes(clean, 1);
  const std::string good = read_file(clean);
  const std::string other_file = path("other.twj");
  write_strokes(other_file, 2);
  const std::string other = read_file(other_file);
  std::string too_new = slice(good, at[5], at[6]);
  too_new[4] = 9;  // a record version from a newer station
  reseal(too_new);
  struct Case {
    const char* name;
    std::string file;
    std::size_t offset;
    const char* problem;
    int kept;  // by salvage
  };
  const std::vector<Case> cases{
      {"duplicate", slice(good, 0, at[3]) + slice(good, at[2], at[6]), at[3], "duplicate", 6},
      {"spliced", slice(good, 0, at[3]) + slice(other, at[3], at[4]) + slice(good, at[3], at[6]),
       at[3], "other_journal", 6},
      {"gap", slice(good, 0, at[2]) + slice(good, at[3], at[6]), at[2], "sequence_gap", 2},
      {"too_new", slice(good, 0, at[5]) + too_new, at[5], "unknown_version", 5},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const std::string journal = path(std::string(c.name) + ".twj");
    write_file(journal, c.file);
    const std::string where = "record at offset " + std::to_string(c.offset);
    const RunResult r = station("--config " + config_for(journal));
    EXPECT_EQ(r.exit_code, 1) << r.output;
    EXPECT_NE(r.output.find(where), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(c.problem), std::string::npos) << r.output;
    const RunResult replay =
        cli("replay " + journal + " --mesh " TWISTER_DEPLOY_DIR "/sim_sphere.obj --out " +
            path("o.obj"));
    EXPECT_EQ(replay.exit_code, 2) << replay.output;
    EXPECT_NE(replay.output.find(where), std::string::npos) << replay.output;
    const RunResult check = cli("journal check " + journal);
    EXPECT_EQ(check.exit_code, 1) << check.output;
    EXPECT_NE(check.output.find("refused: " + where), std::string::npos) << check.output;
    EXPECT_NE(check.output.find("verdict: corrupt"), std::string::npos) << check.output;
    const std::string saved = path(std::string(c.name) + ".saved");
    const RunResult salvage = cli("journal salvage " + journal + " " + saved);
    ASSERT_EQ(salvage.exit_code, 0) << salvage.output;
    EXPECT_EQ(read_file(saved), slice(good, 0, at[static_cast<std::size_t>(c.kept)]));
    EXPECT_EQ(read_file(journal), c.file);  // nobody changed it
    EXPECT_FALSE(fs::exists(journal + ".torn-tail"));
    EXPECT_EQ(cli("journal check " + saved).exit_code, 0);
  }
}

TEST_F(StationOrderIntegrity, ATornTailIsNotCutWhenStartUpFailsOnTheLink) {
  const std::string journal = path("j.twj");
  const auto at = write_strokes(journal, 1);
  const std::string good = read_file(journal);
  const std::string torn = good + slice(good, at[0], at[0] + 30);
  write_file(journal, torn);
  write_file(path("not-a-socket"), "a regular file");
  const RunResult r =
      station("--config " + config_for(journal) + " --link unix:" + path("not-a-socket"));
  EXPECT_NE(r.exit_code, 0) << r.output;
  EXPECT_EQ(read_file(journal), torn);
  EXPECT_FALSE(fs::exists(journal + ".torn-tail"));
  // A new journal is not even created... its header is not written either.
  const std::string fresh = path("fresh.twj");
  EXPECT_NE(
      station("--config " + config_for(fresh) + " --link unix:" + path("not-a-socket")).exit_code,
      0);
  EXPECT_TRUE(!fs::exists(fresh) || fs::file_size(fresh) == 0);
}

TEST_F(StationOrderIntegrity, ANulInTheJournalPathFailsCheck) {
  const std::string cfg = config_for(path("j.twj"));
  std::string text = read_file(cfg);
  const std::string key = "journal = \"" + path("j.twj");
  text.replace(text.find(key), key.size(), key + "\\u0000.evil");
  write_file(cfg, text);
  const RunResult r = station("--config " + cfg + " --check");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("station.journal"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("NUL"), std::string::npos) << r.output;
}

// A new journal whose header the file system refuses (RLIMIT_FSIZE below the header's
// 16 bytes: write(2) fails with EFBIG) says why, not just io_error, and leaves no byte.
TEST_F(StationOrderIntegrity, ANewJournalThatCannotBeWrittenSaysWhy) {
  const std::string journal = path("new.twj");
  const std::string cmd = std::string(TWISTER_STATION_BIN) + " --config " + config_for(journal);
  const RunResult r = run_command("ulimit -f 0 2>/dev/null; exec " + cmd);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("cannot write it: file size limit reached"), std::string::npos)
      << r.output;
  EXPECT_TRUE(!fs::exists(journal) || fs::file_size(journal) == 0);
}

}  // namespace
}  // namespace twister::station_test
