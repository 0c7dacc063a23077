#include "twister/hal/posix_file_storage.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <cstring>
#include <string>

namespace twister::hal {
namespace {

class PosixFileStorageTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::array<char, 64> tmpl{};
    std::snprintf(tmpl.data(), tmpl.size(), "/tmp/twister_storage_XXXXXX");
    ASSERT_NE(::mkdtemp(tmpl.data()), nullptr);
    dir_ = tmpl.data();
    path_ = dir_ + "/journal.bin";
  }
  void TearDown() override {
    ::unlink(path_.c_str());
    ::rmdir(dir_.c_str());
  }
  static std::span<const std::byte> bytes(const char* s) {
    return std::as_bytes(std::span<const char>(s, std::strlen(s)));
  }
  std::string dir_;
  std::string path_;
};

TEST_F(PosixFileStorageTest, CreatesAppendsReadsAndSyncs) {
  PosixFileStorage storage;
  ASSERT_TRUE(storage.open({.path = path_}).ok());
  ASSERT_EQ(storage.size().value(), 0u);
  ASSERT_TRUE(storage.append(bytes("hello ")).ok());
  ASSERT_TRUE(storage.append(bytes("world")).ok());
  ASSERT_TRUE(storage.sync().ok());
  EXPECT_EQ(storage.size().value(), 11u);

  std::array<std::byte, 32> buf{};
  auto n = storage.read_at(6, buf);
  ASSERT_TRUE(n.ok());
  EXPECT_EQ(n.value(), 5u);
  EXPECT_EQ(std::memcmp(buf.data(), "world", 5), 0);
  EXPECT_EQ(storage.read_at(11, buf).value(), 0u);  // at end
}

TEST_F(PosixFileStorageTest, ReopenKeepsDataAndAppendsAtEnd) {
  {
    PosixFileStorage storage;
    ASSERT_TRUE(storage.open({.path = path_}).ok());
    ASSERT_TRUE(storage.append(bytes("abc")).ok());
  }
  PosixFileStorage storage;
  ASSERT_TRUE(storage.open({.path = path_}).ok());
  EXPECT_EQ(storage.size().value(), 3u);
  ASSERT_TRUE(storage.append(bytes("def")).ok());
  std::array<std::byte, 6> buf{};
  ASSERT_EQ(storage.read_at(0, buf).value(), 6u);
  EXPECT_EQ(std::memcmp(buf.data(), "abcdef", 6), 0);
}

TEST_F(PosixFileStorageTest, TruncateDropsTornTail) {
  PosixFileStorage storage;
  ASSERT_TRUE(storage.open({.path = path_}).ok());
  ASSERT_TRUE(storage.append(bytes("record1torn")).ok());
  ASSERT_TRUE(storage.truncate(7).ok());
  EXPECT_EQ(storage.size().value(), 7u);
  ASSERT_TRUE(storage.append(bytes("X")).ok());  // O_APPEND: lands after the cut
  std::array<std::byte, 8> buf{};
  ASSERT_EQ(storage.read_at(0, buf).value(), 8u);
  EXPECT_EQ(std::memcmp(buf.data(), "record1X", 8), 0);
}

TEST_F(PosixFileStorageTest, MissingFileWithoutCreateIsUnavailable) {
  PosixFileStorage storage;
  EXPECT_EQ(storage.open({.path = path_, .create_if_missing = false}).code(),
            StatusCode::unavailable);
  EXPECT_FALSE(storage.is_open());
}

TEST_F(PosixFileStorageTest, UnwritableDirectoryIsIoErrorWithErrno) {
  PosixFileStorage storage;
  EXPECT_EQ(storage.open({.path = "/nonexistent_dir_twister/j.bin"}).code(), StatusCode::io_error);
  EXPECT_EQ(storage.last_errno(), ENOENT);
}

TEST_F(PosixFileStorageTest, CallsBeforeOpenAreFailedPrecondition) {
  PosixFileStorage storage;
  EXPECT_EQ(storage.size().status().code(), StatusCode::failed_precondition);
  EXPECT_EQ(storage.append(bytes("x")).code(), StatusCode::failed_precondition);
  EXPECT_EQ(storage.sync().code(), StatusCode::failed_precondition);
}

}  // namespace
}  // namespace twister::hal
