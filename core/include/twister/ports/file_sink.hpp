// FileSink port: writes one new file in one go and puts it in place atomically, for
// what the station writes besides the journal (mesh checkpoints, the bytes of a cut
// torn journal tail). begin() starts a temporary file, write() appends to it,
// commit() makes it durable and gives it its final name (a crash before commit()
// leaves no half file under that name), abort() drops it. The POSIX backend never
// replaces a file the program did not create. One file at a time; not thread-safe.
#pragma once

#include <cstdint>
#include <span>

#include "twister/base/status.hpp"

namespace twister::ports {

class FileSink {
 public:
  virtual ~FileSink() = default;

  // Starts a new temporary file (dropping one not committed). io_error: cannot create.
  Status begin() { return do_begin(); }
  // Appends all of `bytes`. io_error: write failed (disk full, ...);
  // failed_precondition: no begin().
  Status write(std::span<const std::byte> bytes) { return do_write(bytes); }
  // fsyncs the file, moves it to its final name and fsyncs the directory.
  // io_error: failed (the temporary is removed); failed_precondition: no begin();
  // already_exists-like refusals (the final name holds something the program did
  // not write) are failed_precondition too.
  Status commit() { return do_commit(); }
  // Drops the temporary file, if any.
  void abort() { do_abort(); }

 private:
  virtual Status do_begin() = 0;
  virtual Status do_write(std::span<const std::byte> bytes) = 0;
  virtual Status do_commit() = 0;
  virtual void do_abort() = 0;
};

}  // namespace twister::ports
