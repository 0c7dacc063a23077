// PosixFileStorage: the Storage port over one append-only file (the stroke journal).
// append() writes all bytes (retrying short writes and EINTR); sync() is fsync(2).
// A newly created file also gets its directory fsynced, so the file survives power
// loss. With `lock`, open() takes an exclusive lock on the file for as long as it is
// open: an open file description (OFD) fcntl lock, so no other process (and no other
// PosixFileStorage in this one) can lock it meanwhile; the kernel drops it when the
// process ends, however it ends. Because OFD locks do not tell who holds them, the
// owner also holds a classic POSIX lock on one byte far past any real data, which
// F_GETLK reports with the holder's PID. Not thread-safe: one owner (the station loop).
#pragma once

#include <cstdint>
#include <string>

#include "twister/ports/storage.hpp"

namespace twister::hal {

struct PosixFileStorageConfig {
  std::string path;  // journal file; created (mode 0644) when missing
  bool create_if_missing = true;
  bool lock = false;       // exclusive lock while open (see above)
  bool read_only = false;  // O_RDONLY: size/read only (append/sync/truncate fail)
};

class PosixFileStorage final : public ports::Storage {
 public:
  PosixFileStorage() = default;
  ~PosixFileStorage() override;
  PosixFileStorage(const PosixFileStorage&) = delete;
  PosixFileStorage& operator=(const PosixFileStorage&) = delete;

  // Opens (or creates) the file, without blocking (O_NONBLOCK, then fstat(2)).
  // invalid_argument: the path holds something other than a regular file (a FIFO,
  // device, socket or directory: closed again, never read); io_error: open/create
  // failed (errno() tells why);
  // unavailable: missing and create_if_missing is false; failed_precondition: `lock`
  // and another process holds the lock (lock_holder_pid() names it; the file was not
  // changed).
  Status open(const PosixFileStorageConfig& config);
  void close();
  bool is_open() const { return fd_ >= 0; }
  // errno of the last failed call (0 if none), for the log at the composition root.
  int last_errno() const { return last_errno_; }
  // After open() refused a locked file: the PID holding the lock (0 when unknown).
  int lock_holder_pid() const { return lock_holder_pid_; }

 private:
  Result<std::uint64_t> do_size() override;
  Result<std::size_t> do_read_at(std::uint64_t offset, std::span<std::byte> dest) override;
  Status do_append(std::span<const std::byte> src) override;
  Status do_sync() override;
  Status do_truncate(std::uint64_t length) override;
  Status fail(int err);
  Status take_lock();

  int fd_ = -1;
  int last_errno_ = 0;
  int lock_holder_pid_ = 0;
};

}  // namespace twister::hal
