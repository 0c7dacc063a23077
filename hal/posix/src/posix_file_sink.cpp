// PosixFileSink: errno is translated to StatusCode here, at the boundary.
#include "twister/hal/posix_file_sink.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <utility>

#include "twister/hal/output_file.hpp"

namespace twister::hal {
namespace {

std::string directory_of(const std::string& path) {
  const auto slash = path.rfind('/');
  if (slash == std::string::npos) return ".";
  return slash == 0 ? "/" : path.substr(0, slash);
}

void sync_directory(const char* dir) {
  const int dfd = ::open(dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dfd >= 0) {
    ::fsync(dfd);
    ::close(dfd);
  }
}

}  // namespace

namespace {

// "DIGITS-DIGITS" and nothing else.
bool is_temp_suffix(const char* s) {
  int groups = 0;
  for (;;) {
    if (*s < '0' || *s > '9') return false;
    while (*s >= '0' && *s <= '9') ++s;
    ++groups;
    if (*s == '\0') return groups == 2;
    if (*s != '-' || groups == 2) return false;
    ++s;
  }
}

}  // namespace

int PosixFileSink::remove_stale_temporaries(const std::string& path) {
  const std::string dir = directory_of(path);
  const auto slash = path.rfind('/');
  const std::string prefix = (slash == std::string::npos ? path : path.substr(slash + 1)) + ".tmp-";
  DIR* d = ::opendir(dir.c_str());
  if (d == nullptr) return 0;
  int removed = 0;
  while (const dirent* e = ::readdir(d)) {
    if (std::strncmp(e->d_name, prefix.c_str(), prefix.size()) != 0 ||
        !is_temp_suffix(e->d_name + prefix.size())) {
      continue;
    }
    struct stat st {};
    if (::fstatat(::dirfd(d), e->d_name, &st, AT_SYMLINK_NOFOLLOW) != 0 || !S_ISREG(st.st_mode)) {
      continue;
    }
    if (::unlinkat(::dirfd(d), e->d_name, 0) == 0) ++removed;
  }
  ::closedir(d);
  if (removed > 0) sync_directory(dir.c_str());
  return removed;
}

PosixFileSink::PosixFileSink(PosixFileSinkConfig config)
    : config_(std::move(config)), directory_(directory_of(config_.path)) {}

PosixFileSink::~PosixFileSink() { do_abort(); }

Status PosixFileSink::fail(int err, const char* what) {
  last_errno_ = err;
  std::snprintf(last_error_.data(), last_error_.size(), "%s: %s", what,
                err != 0 ? std::strerror(err) : "refused");
  return err != 0 ? StatusCode::io_error : StatusCode::failed_precondition;
}

Status PosixFileSink::do_begin() {
  do_abort();
  last_errno_ = 0;
  last_error_[0] = '\0';
  written_ = 0;
  written_back_ = 0;
  temp_path_[0] = '\0';
  // An unnamed file first: a crash before commit() leaves nothing behind.
  fd_ = ::open(directory_.c_str(), O_TMPFILE | O_WRONLY | O_CLOEXEC, config_.mode);
  if (fd_ >= 0) return ok_status();
  if (errno != EOPNOTSUPP && errno != EISDIR && errno != EINVAL) {
    return fail(errno, "cannot create a temporary file");
  }
  // No O_TMPFILE here: a new name that nothing else holds (O_EXCL never opens an
  // existing file).
  for (int attempt = 0; attempt < 100; ++attempt) {
    std::snprintf(temp_path_.data(), temp_path_.size(), "%s.tmp-%ld-%llu", config_.path.c_str(),
                  static_cast<long>(::getpid()), static_cast<unsigned long long>(temp_counter_++));
    fd_ = ::open(temp_path_.data(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, config_.mode);
    if (fd_ >= 0) return ok_status();
    if (errno != EEXIST) break;
  }
  temp_path_[0] = '\0';
  return fail(errno, "cannot create a temporary file");
}

Status PosixFileSink::do_write(std::span<const std::byte> bytes) {
  if (fd_ < 0) return StatusCode::failed_precondition;
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd_, bytes.data() + done, bytes.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      return fail(errno, "write failed");
    }
    done += static_cast<std::size_t>(n);
  }
  written_ += bytes.size();
  if (config_.writeback_bytes > 0 && written_ - written_back_ >= config_.writeback_bytes) {
    // Start writeback now, without waiting: commit()'s fsync then has less to do.
    ::sync_file_range(fd_, static_cast<off_t>(written_back_),
                      static_cast<off_t>(written_ - written_back_), SYNC_FILE_RANGE_WRITE);
    written_back_ = written_;
  }
  return ok_status();
}

Status PosixFileSink::check_target() {
  struct stat st {};
  if (::lstat(config_.path.c_str(), &st) != 0) {
    return errno == ENOENT ? ok_status() : fail(errno, "cannot inspect the target");
  }
  if (!S_ISREG(st.st_mode)) {
    std::snprintf(last_error_.data(), last_error_.size(), "%s is %s; it is not replaced",
                  config_.path.c_str(), file_type_name(st.st_mode));
    last_errno_ = 0;
    return StatusCode::failed_precondition;
  }
  if (config_.replace == PosixFileSinkConfig::Replace::output) {
    last_errno_ = 0;
    const Status s = inspect_output_target(config_.path.c_str(), config_.output, last_error_.data(),
                                           last_error_.size());
    if (s.code() == StatusCode::io_error) last_errno_ = errno;
    return s;
  }
  if (config_.replace != PosixFileSinkConfig::Replace::own_magic) return ok_status();
  // An empty file holds nothing (a checkpoint whose writer died before it wrote).
  if (st.st_size == 0) return ok_status();
  std::array<std::byte, 16> head{};
  const std::size_t want = std::min(head.size(), config_.magic.size());
  const int fd = ::open(config_.path.c_str(), O_RDONLY | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK);
  const ssize_t n = fd >= 0 ? ::read(fd, head.data(), want) : -1;
  if (fd >= 0) ::close(fd);
  if (n != static_cast<ssize_t>(want) ||
      std::memcmp(head.data(), config_.magic.data(), want) != 0) {
    std::snprintf(last_error_.data(), last_error_.size(),
                  "%s exists and was not written by this program; it is not replaced",
                  config_.path.c_str());
    last_errno_ = 0;
    return StatusCode::failed_precondition;
  }
  return ok_status();
}

Status PosixFileSink::link_new_name() {
  // link(2) never replaces: EEXIST sends us to the next name.
  std::array<char, 64> proc{};
  std::snprintf(proc.data(), proc.size(), "/proc/self/fd/%d", fd_);
  for (int suffix = 0; suffix < 1000000; ++suffix) {
    if (suffix == 0) {
      std::snprintf(committed_path_.data(), committed_path_.size(), "%s", config_.path.c_str());
    } else {
      std::snprintf(committed_path_.data(), committed_path_.size(), "%s.%d", config_.path.c_str(),
                    suffix);
    }
    const int rc = temp_path_[0] != '\0' ? ::link(temp_path_.data(), committed_path_.data())
                                         : ::linkat(AT_FDCWD, proc.data(), AT_FDCWD,
                                                    committed_path_.data(), AT_SYMLINK_FOLLOW);
    if (rc == 0) {
      if (temp_path_[0] != '\0') ::unlink(temp_path_.data());
      return ok_status();
    }
    if (errno != EEXIST) return fail(errno, "cannot name the file");
  }
  return fail(EEXIST, "no free name");
}

Status PosixFileSink::place() {
  if (config_.replace == PosixFileSinkConfig::Replace::never) return link_new_name();
  TWISTER_TRY(check_target());
  std::snprintf(committed_path_.data(), committed_path_.size(), "%s", config_.path.c_str());
  if (temp_path_[0] == '\0') {
    // Give the unnamed file a temporary name first; rename(2) then replaces atomically.
    std::array<char, 64> proc{};
    std::snprintf(proc.data(), proc.size(), "/proc/self/fd/%d", fd_);
    for (int attempt = 0; attempt < 100 && temp_path_[0] == '\0'; ++attempt) {
      std::snprintf(temp_path_.data(), temp_path_.size(), "%s.tmp-%ld-%llu", config_.path.c_str(),
                    static_cast<long>(::getpid()),
                    static_cast<unsigned long long>(temp_counter_++));
      if (::linkat(AT_FDCWD, proc.data(), AT_FDCWD, temp_path_.data(), AT_SYMLINK_FOLLOW) == 0)
        break;
      const int err = errno;
      temp_path_[0] = '\0';
      if (err != EEXIST) return fail(err, "cannot name the file");
    }
    if (temp_path_[0] == '\0') return fail(EEXIST, "no free temporary name");
  }
  if (::rename(temp_path_.data(), config_.path.c_str()) != 0) return fail(errno, "cannot rename");
  temp_path_[0] = '\0';
  return ok_status();
}

Status PosixFileSink::do_commit() {
  if (fd_ < 0) return StatusCode::failed_precondition;
  if (::fsync(fd_) != 0) {
    const Status s = fail(errno, "fsync failed");
    do_abort();
    return s;
  }
  if (const Status s = place(); !s.ok()) {
    do_abort();
    return s;
  }
  ::close(fd_);
  fd_ = -1;
  sync_directory(directory_.c_str());
  return ok_status();
}

void PosixFileSink::do_abort() {
  if (fd_ >= 0) {
    ::close(fd_);
    fd_ = -1;
  }
  // Only the temporary this sink created (O_EXCL) is ever removed.
  if (temp_path_[0] != '\0') {
    ::unlink(temp_path_.data());
    temp_path_[0] = '\0';
  }
}

Expected<void> write_output_file(const std::string& path, std::string_view bytes, OutputRule rule) {
  PosixFileSinkConfig config;
  config.path = path;
  config.replace = PosixFileSinkConfig::Replace::output;
  config.output = rule;
  PosixFileSink sink(config);
  Status s = sink.begin();
  if (s.ok()) s = sink.write(std::as_bytes(std::span(bytes.data(), bytes.size())));
  if (s.ok()) s = sink.commit();
  if (s.ok()) return {};
  sink.abort();
  return Error{s, "cannot write " + path + ": " + sink.last_error()};
}

}  // namespace twister::hal
