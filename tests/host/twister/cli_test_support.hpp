// Helpers for the tests that run host programs: a scratch directory removed at the
// end of the test, and a shell command run with its stdout and exit code captured.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstddef>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <span>
#include <string>

namespace twister::host_test {

// <temp>/<prefix>_<pid>, created; removed with everything in it on destruction.
class ScratchDir {
 public:
  explicit ScratchDir(const std::string& prefix)
      : path_(std::filesystem::temp_directory_path() /
              (prefix + "_" + std::to_string(::getpid()))) {
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() { std::filesystem::remove_all(path_); }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

struct CommandRun {
  int exit_code = -1;  // -1: not run or did not exit normally
  std::string out;     // stdout (add "2>&1" to the command for stderr too)
};

// Runs `command` with /bin/sh (redirections allowed).
inline CommandRun run_command(const std::string& command) {
  CommandRun r;
  FILE* p = popen(command.c_str(), "r");
  if (p == nullptr) return r;
  std::array<char, 512> buf{};
  while (fgets(buf.data(), buf.size(), p) != nullptr) r.out += buf.data();
  const int status = pclose(p);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

#ifdef TWISTER_CLI
// stdout and stderr of `twister ARGS` (the build's twister).
inline CommandRun run_twister(const std::string& args) {
  return run_command(std::string(TWISTER_CLI) + " " + args + " 2>&1");
}
#endif

// Writes `bytes` to `path` (a journal or a model a test made), replacing it.
inline void write_file(const std::filesystem::path& path, std::span<const std::byte> bytes) {
  std::ofstream f(path, std::ios::binary);
  f.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

}  // namespace twister::host_test
