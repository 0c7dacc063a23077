// PosixFileSink: the FileSink port over POSIX files. begin() opens an unnamed file
// (O_TMPFILE) in the target's directory, or, where the file system has none, a new
// uniquely named temporary (O_CREAT | O_EXCL: never an existing file); commit()
// fsyncs it, gives it its final name and fsyncs the directory, so a crash leaves
// either the old file or the new one, never half a file. What may be at the final
// name is the config's `replace` rule, checked with lstat(2) right before:
//   never     - nothing is ever replaced: the file gets `path`, else `path.1`,
//               `path.2`, ... (link(2) fails on an existing name instead of replacing
//               it), so every committed file is new (the cut bytes of a torn journal tail);
//   regular   - a regular file may be replaced (not a FIFO, device, socket,
//               directory or symlink: refused with failed_precondition);
//   own_magic - only a regular file that starts with `magic` (one this program
//               wrote, e.g. the previous checkpoint), or an empty one, may be replaced;
//   output    - the programs' output rule (output_file.hpp: never a journal, a
//               checkpoint, a locked file or another kind; a file of `output.kind`
//               only with `output.force`).
// begin(), write() and commit() never allocate (names are built in fixed buffers),
// so the station may write a checkpoint from its loop. Not thread-safe; one file at
// a time.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "twister/hal/expected.hpp"
#include "twister/hal/output_file.hpp"
#include "twister/ports/file_sink.hpp"

namespace twister::hal {

struct PosixFileSinkConfig {
  enum class Replace : std::uint8_t { never, regular, own_magic, output };
  std::string path;  // final name
  Replace replace = Replace::regular;
  std::vector<std::byte> magic;  // own_magic: the first bytes of a file we wrote
  OutputRule output;             // output: what may be replaced
  unsigned mode = 0644;
  // Ask the kernel to start writing back every this many bytes (sync_file_range), so
  // commit()'s fsync waits less (0: never).
  std::size_t writeback_bytes = 0;
};

class PosixFileSink final : public ports::FileSink {
 public:
  explicit PosixFileSink(PosixFileSinkConfig config);
  ~PosixFileSink() override;
  PosixFileSink(const PosixFileSink&) = delete;
  PosixFileSink& operator=(const PosixFileSink&) = delete;

  // Removes what a killed writer of `path` left: regular files named exactly
  // `path.tmp-PID-N` (this sink's temporary names; nothing else is touched). Only for
  // a caller that owns `path` (the station, holding its journal's lock). Returns how
  // many were removed.
  static int remove_stale_temporaries(const std::string& path);

  const std::string& path() const { return config_.path; }
  // The name the last commit() gave its file (replace == never may add a suffix).
  const char* committed_path() const { return committed_path_.data(); }
  // errno of the last failure (0 if none) and what failed or was refused, for the log.
  int last_errno() const { return last_errno_; }
  const char* last_error() const { return last_error_.data(); }

 private:
  Status do_begin() override;
  Status do_write(std::span<const std::byte> bytes) override;
  Status do_commit() override;
  void do_abort() override;

  Status fail(int err, const char* what);
  // May `config_.path` be replaced? ok, or failed_precondition naming what is there.
  Status check_target();
  // Puts the synced file at its final name (per the replace rule).
  Status place();
  Status link_new_name();

  PosixFileSinkConfig config_;
  std::string directory_;
  int fd_ = -1;
  std::array<char, 4096> temp_path_{};  // empty with O_TMPFILE
  std::array<char, 4096> committed_path_{};
  std::uint64_t written_ = 0;
  std::uint64_t written_back_ = 0;
  std::uint64_t temp_counter_ = 0;
  int last_errno_ = 0;
  std::array<char, 256> last_error_{};
};

// Writes `bytes` to `path` atomically under the output rule (Replace::output): what
// the programs' writers of whole files in memory use. Error naming the path.
Expected<void> write_output_file(const std::string& path, std::string_view bytes, OutputRule rule);

}  // namespace twister::hal
