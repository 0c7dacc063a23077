// PosixFileStorage: errno is translated to StatusCode here, at the boundary.
#include "twister/hal/posix_file_storage.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <climits>

namespace twister::hal {
namespace {

// Durability of a new file needs its directory entry on disk as well.
void sync_parent_directory(const std::string& path) {
  const auto slash = path.rfind('/');
  const std::string dir =
      slash == std::string::npos ? "." : (slash == 0 ? "/" : path.substr(0, slash));
  const int dfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dfd >= 0) {
    ::fsync(dfd);
    ::close(dfd);
  }
}

}  // namespace

PosixFileStorage::~PosixFileStorage() { close(); }

Status PosixFileStorage::fail(int err) {
  last_errno_ = err;
  return StatusCode::io_error;
}

Status PosixFileStorage::open(const PosixFileStorageConfig& config) {
  close();
  if (config.path.empty()) return StatusCode::invalid_argument;
  struct stat st {};
  const bool existed = ::stat(config.path.c_str(), &st) == 0;
  if (!existed && !config.create_if_missing) {
    last_errno_ = ENOENT;
    return StatusCode::unavailable;
  }
  const int access = config.read_only ? O_RDONLY : O_RDWR | O_APPEND;
  // O_NONBLOCK: a FIFO or device at the path never blocks the open; only a regular
  // file is used (a journal or checkpoint is nothing else).
  const int flags = access | O_CLOEXEC | O_NONBLOCK | (config.create_if_missing ? O_CREAT : 0);
  const int fd = ::open(config.path.c_str(), flags, 0644);
  if (fd < 0 && errno == EISDIR) {
    last_errno_ = EISDIR;
    return StatusCode::invalid_argument;
  }
  if (fd < 0) return fail(errno);
  struct stat opened {};
  if (::fstat(fd, &opened) != 0 || !S_ISREG(opened.st_mode)) {
    const int err = S_ISDIR(opened.st_mode) ? EISDIR : EINVAL;
    ::close(fd);
    last_errno_ = err;
    return StatusCode::invalid_argument;
  }
  ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);
  fd_ = fd;
  last_errno_ = 0;
  lock_holder_pid_ = 0;
  if (config.lock) {
    if (const Status locked = take_lock(); !locked.ok()) {
      close();
      return locked;
    }
  }
  if (!existed) sync_parent_directory(config.path);
  return ok_status();
}

Status PosixFileStorage::take_lock() {
  // The advertising byte: far past any journal, so it never overlaps the OFD lock.
  constexpr off_t kPidByte = off_t{1} << 62;
  struct flock ofd {};
  ofd.l_type = F_WRLCK;
  ofd.l_whence = SEEK_SET;
  ofd.l_start = 0;
  ofd.l_len = kPidByte;
  if (::fcntl(fd_, F_OFD_SETLK, &ofd) != 0) {
    const int err = errno;
    if (err != EAGAIN && err != EACCES) return fail(err);
    struct flock probe {};
    probe.l_type = F_WRLCK;
    probe.l_whence = SEEK_SET;
    probe.l_start = kPidByte;
    probe.l_len = 1;
    if (::fcntl(fd_, F_GETLK, &probe) == 0 && probe.l_type != F_UNLCK) {
      lock_holder_pid_ = probe.l_pid;
    }
    last_errno_ = err;
    return StatusCode::failed_precondition;
  }
  struct flock pid {};
  pid.l_type = F_WRLCK;
  pid.l_whence = SEEK_SET;
  pid.l_start = kPidByte;
  pid.l_len = 1;
  ::fcntl(fd_, F_SETLK, &pid);  // best effort: only names us to the next one
  return ok_status();
}

void PosixFileStorage::close() {
  if (fd_ >= 0) {
    ::close(fd_);
    fd_ = -1;
  }
}

Result<std::uint64_t> PosixFileStorage::do_size() {
  if (fd_ < 0) return StatusCode::failed_precondition;
  struct stat st {};
  if (::fstat(fd_, &st) != 0) return fail(errno);
  return static_cast<std::uint64_t>(st.st_size);
}

Result<std::size_t> PosixFileStorage::do_read_at(std::uint64_t offset, std::span<std::byte> dest) {
  if (fd_ < 0) return StatusCode::failed_precondition;
  if (offset > static_cast<std::uint64_t>(LLONG_MAX)) return StatusCode::out_of_range;
  std::size_t done = 0;
  while (done < dest.size()) {
    const ssize_t n =
        ::pread(fd_, dest.data() + done, dest.size() - done, static_cast<off_t>(offset + done));
    if (n < 0) {
      if (errno == EINTR) continue;
      return fail(errno);
    }
    if (n == 0) break;  // end of file
    done += static_cast<std::size_t>(n);
  }
  return done;
}

Status PosixFileStorage::do_append(std::span<const std::byte> src) {
  if (fd_ < 0) return StatusCode::failed_precondition;
  std::size_t done = 0;
  while (done < src.size()) {
    const ssize_t n = ::write(fd_, src.data() + done, src.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      return fail(errno);
    }
    done += static_cast<std::size_t>(n);
  }
  return ok_status();
}

Status PosixFileStorage::do_sync() {
  if (fd_ < 0) return StatusCode::failed_precondition;
  if (::fsync(fd_) != 0) return fail(errno);
  return ok_status();
}

Status PosixFileStorage::do_truncate(std::uint64_t length) {
  if (fd_ < 0) return StatusCode::failed_precondition;
  if (length > static_cast<std::uint64_t>(LLONG_MAX)) return StatusCode::out_of_range;
  if (::ftruncate(fd_, static_cast<off_t>(length)) != 0) return fail(errno);
  return ok_status();
}

}  // namespace twister::hal
