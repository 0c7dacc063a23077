#include "twister/hal/logger.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <cstdlib>
#include <string>

#include "support/allocation_counter.hpp"

namespace twister::hal {
namespace {

std::string format(const char* fmt, std::initializer_list<ports::LogArg> args) {
  std::array<char, 256> out{};
  format_log_message(out, fmt, {args.begin(), args.size()});
  return out.data();
}

// Reads everything written to a pipe's write end so far.
struct Pipe {
  Pipe() { EXPECT_EQ(::pipe(fds.data()), 0); }
  ~Pipe() {
    ::close(fds[0]);
    ::close(fds[1]);
  }
  std::string drain() {
    ::close(fds[1]);
    fds[1] = -1;
    std::string text;
    std::array<char, 4096> buf{};
    for (ssize_t n; (n = ::read(fds[0], buf.data(), buf.size())) > 0;) text.append(buf.data(), n);
    return text;
  }
  std::array<int, 2> fds{};
};

TEST(LogFormat, ConversionsTakeTheArgumentsInOrder) {
  EXPECT_EQ(format("hand %u committed as record %u", {0u, 12u}), "hand 0 committed as record 12");
  EXPECT_EQ(format("%d %s %.3f %5.1f%%", {-4, "x", 0.5, 2.25}), "-4 x 0.500   2.2%");
  EXPECT_EQ(format("%016llx", {0xabcULL}), "0000000000000abc");
  EXPECT_EQ(format("%zu %lld", {std::size_t{7}, -8LL}), "7 -8");
}

TEST(LogFormat, MismatchedOrMissingArgumentsNeverCrash) {
  EXPECT_EQ(format("%d and %s", {1.9}), "1 and ?");
  EXPECT_EQ(format("%s", {3}), "?");
  EXPECT_EQ(format("trailing %", {}), "trailing %");
  EXPECT_EQ(format("no args", {1, 2}), "no args");
}

TEST(LogFormat, LongOutputIsCutAndTerminated) {
  std::array<char, 8> out{};
  EXPECT_EQ(format_log_message(out, "%s", std::initializer_list<ports::LogArg>{"abcdefghij"}), 7u);
  EXPECT_STREQ(out.data(), "abcdefg");
}

TEST(Logger, PlainLinesCarryProgramLevelAndComponent) {
  Pipe p;
  Logger log({"twister-station", LogLevel::info, false, p.fds[1]});
  log.notice("journal", "%u good records", 12u);
  log.warning("tracker", "lost");
  log.error("", "cannot open %s", "/x");
  log.debug("tracker", "hidden");
  EXPECT_EQ(p.drain(),
            "twister-station: journal: 12 good records\n"
            "twister-station: warning: tracker: lost\n"
            "twister-station: error: cannot open /x\n");
}

TEST(Logger, SystemdLinesCarryPriorityPrefixes) {
  Pipe p;
  Logger log({"twister-station", LogLevel::debug, true, p.fds[1]});
  log.error("journal", "bad");
  log.info("stroke", "hand %u", 1u);
  EXPECT_EQ(p.drain(), "<3>journal: bad\n<6>stroke: hand 1\n");
}

TEST(Logger, ThresholdFiltersAndCoreSinkSeesIt) {
  Pipe p;
  Logger log({"p", LogLevel::warning, false, p.fds[1]});
  ports::LogSink& sink = log;
  EXPECT_TRUE(sink.enabled(LogLevel::error));
  EXPECT_FALSE(sink.enabled(LogLevel::notice));
  sink.write(LogLevel::notice, "c", "dropped");
  log.set_threshold(LogLevel::notice);
  sink.write(LogLevel::notice, "c", "kept %d", {5});
  EXPECT_EQ(p.drain(), "p: c: kept 5\n");
}

TEST(Logger, WritingALineDoesNotAllocate) {
  Pipe p;
  Logger log({"twister-station", LogLevel::debug, false, p.fds[1]});
  EXPECT_NO_ALLOCATIONS(log.info("stroke", "hand %u committed as journal record %u", 0u, 42u));
}

TEST(LogLevelNames, ParseAndNameRoundTrip) {
  for (const LogLevel l :
       {LogLevel::error, LogLevel::warning, LogLevel::notice, LogLevel::info, LogLevel::debug}) {
    LogLevel parsed = LogLevel::error;
    ASSERT_TRUE(parse_log_level(log_level_name(l), parsed));
    EXPECT_EQ(parsed, l);
  }
  LogLevel unused = LogLevel::error;
  EXPECT_FALSE(parse_log_level("verbose", unused));
}

TEST(StderrIsJournal, MatchesOnlyTheDeviceAndInodeOfStderr) {
  ::unsetenv("JOURNAL_STREAM");
  EXPECT_FALSE(stderr_is_journal());
  struct stat st {};
  ASSERT_EQ(::fstat(2, &st), 0);
  const std::string mine = std::to_string(st.st_dev) + ":" + std::to_string(st.st_ino);
  ::setenv("JOURNAL_STREAM", mine.c_str(), 1);
  EXPECT_TRUE(stderr_is_journal());
  ::setenv("JOURNAL_STREAM", "1:2", 1);
  EXPECT_FALSE(stderr_is_journal());
  ::unsetenv("JOURNAL_STREAM");
}

}  // namespace
}  // namespace twister::hal
