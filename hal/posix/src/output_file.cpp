// Output paths: errno is translated here, at the boundary.
#include "twister/hal/output_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <string_view>

namespace twister::hal {
namespace {

bool starts_with(const std::array<char, 64>& head, std::size_t n, const char* prefix,
                 std::size_t len) {
  return n >= len && std::memcmp(head.data(), prefix, len) == 0;
}

std::size_t skip_blanks(const std::array<char, 64>& head, std::size_t n) {
  std::size_t i = 0;
  while (i < n && (head[i] == ' ' || head[i] == '\t' || head[i] == '\r' || head[i] == '\n')) ++i;
  return i;
}

// An OBJ is text that starts (after blanks) with a comment or one of its statements.
bool looks_like_obj(const std::array<char, 64>& head, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    const auto c = static_cast<unsigned char>(head[i]);
    if (c < 0x20 && c != '\t' && c != '\r' && c != '\n') return false;
  }
  const std::size_t i = skip_blanks(head, n);
  if (i == n || head[i] == '#') return true;
  std::size_t end = i;
  while (end < n && head[end] != ' ' && head[end] != '\t' && head[end] != '\r' &&
         head[end] != '\n') {
    ++end;
  }
  if (end == n) return false;  // no whole first word within the first bytes
  const std::string_view word(head.data() + i, end - i);
  constexpr std::string_view kStatements[] = {"v", "vt", "vn", "vp", "f",      "o",
                                              "g", "s",  "l",  "p",  "mtllib", "usemtl"};
  for (const std::string_view statement : kStatements) {
    if (word == statement) return true;
  }
  return false;
}

bool is_kind(OutputKind kind, const std::array<char, 64>& head, std::size_t n) {
  if (n == 0) return true;  // an empty file holds nothing to lose
  switch (kind) {
    case OutputKind::obj:
      return looks_like_obj(head, n);
    case OutputKind::ply:
      return starts_with(head, n, "ply\n", 4) || starts_with(head, n, "ply\r\n", 5);
    case OutputKind::glb:
      return starts_with(head, n, "glTF", 4);
    case OutputKind::gltf: {
      const std::size_t i = skip_blanks(head, n);
      return i < n && head[i] == '{';
    }
    case OutputKind::png:
      return starts_with(head, n, "\x89PNG\r\n\x1a\n", 8);
    case OutputKind::svg:
      return starts_with(head, n, "<?xml", 5) || starts_with(head, n, "<svg", 4);
    case OutputKind::stl:
      return starts_with(head, n, "solid", 5) ||
             starts_with(head, n, kStlHeaderPrefix, sizeof kStlHeaderPrefix - 1);
  }
  return false;
}

// The PID of a lock holder: the classic lock the station keeps on its far byte, or
// what F_OFD_GETLK / F_GETLK reports (0 when unknown).
int lock_holder(int fd, const struct flock& found) {
  struct flock probe {};
  probe.l_type = F_WRLCK;
  probe.l_whence = SEEK_SET;
  probe.l_start = off_t{1} << 62;
  probe.l_len = 1;
  if (::fcntl(fd, F_GETLK, &probe) == 0 && probe.l_type != F_UNLCK && probe.l_pid > 0) {
    return probe.l_pid;
  }
  return found.l_pid > 0 ? found.l_pid : 0;
}

// Is any part of the file locked by anyone (OFD or classic, shared or exclusive)?
bool locked(int fd, int& pid) {
  struct flock probe {};
  probe.l_type = F_WRLCK;
  probe.l_whence = SEEK_SET;
  probe.l_start = 0;
  probe.l_len = 0;  // to the end, however far
  if (::fcntl(fd, F_OFD_GETLK, &probe) != 0 || probe.l_type == F_UNLCK) return false;
  pid = lock_holder(fd, probe);
  return true;
}

Status refuse(char* message, std::size_t size, const char* path, const char* why) {
  std::snprintf(message, size, "%s %s; it is not replaced", path, why);
  return StatusCode::failed_precondition;
}

// The checks on an open regular file: locks, our own formats, the kind.
Status inspect_open(int fd, const char* path, OutputRule rule, char* message, std::size_t size) {
  int pid = 0;
  if (locked(fd, pid)) {
    char why[96];
    if (pid > 0) {
      std::snprintf(why, sizeof why, "is in use (locked by PID %d: a running twister-station?)",
                    pid);
    } else {
      std::snprintf(why, sizeof why, "is in use (locked: a running twister-station?)");
    }
    return refuse(message, size, path, why);
  }
  std::array<char, 64> head{};
  ssize_t n = -1;
  do {
    n = ::read(fd, head.data(), head.size());
  } while (n < 0 && errno == EINTR);
  if (n < 0) {
    std::snprintf(message, size, "cannot read %s: %s", path, std::strerror(errno));
    return StatusCode::io_error;
  }
  const auto got = static_cast<std::size_t>(n);
  if (starts_with(head, got, kJournalMagic, 4)) return refuse(message, size, path, "is a journal");
  if (starts_with(head, got, kCheckpointMagic, 4)) {
    return refuse(message, size, path, "is a station checkpoint");
  }
  if (!rule.force) {
    return refuse(message, size, path,
                  "exists (--force replaces a file of the same kind, never anything else)");
  }
  if (!is_kind(rule.kind, head, got)) {
    char why[64];
    std::snprintf(why, sizeof why, "exists and its first bytes are not %s",
                  output_kind_name(rule.kind));
    return refuse(message, size, path, why);
  }
  return ok_status();
}

}  // namespace

const char* file_type_name(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode) || S_ISBLK(mode)) return "a device";
  if (S_ISSOCK(mode)) return "a socket";
  if (S_ISLNK(mode)) return "a symbolic link";
  return "not a regular file";
}

bool output_kind_of(const std::string& path, OutputKind& kind) {
  struct Ending {
    const char* ending;
    OutputKind kind;
  };
  constexpr Ending kEndings[] = {{".obj", OutputKind::obj}, {".ply", OutputKind::ply},
                                 {".glb", OutputKind::glb}, {".gltf", OutputKind::gltf},
                                 {".png", OutputKind::png}, {".svg", OutputKind::svg},
                                 {".stl", OutputKind::stl}};
  for (const Ending& e : kEndings) {
    if (path.ends_with(e.ending)) {
      kind = e.kind;
      return true;
    }
  }
  return false;
}

const char* output_kind_name(OutputKind kind) {
  switch (kind) {
    case OutputKind::obj:
      return "OBJ";
    case OutputKind::ply:
      return "PLY";
    case OutputKind::glb:
      return "binary glTF";
    case OutputKind::gltf:
      return "glTF";
    case OutputKind::png:
      return "PNG";
    case OutputKind::svg:
      return "SVG";
    case OutputKind::stl:
      return "STL";
  }
  return "unknown";
}

Status inspect_output_target(const char* path, OutputRule rule, char* message, std::size_t size) {
  message[0] = '\0';
  struct stat before {};
  if (::lstat(path, &before) != 0) {
    if (errno == ENOENT) return ok_status();
    std::snprintf(message, size, "cannot inspect %s: %s", path, std::strerror(errno));
    return StatusCode::io_error;
  }
  if (!S_ISREG(before.st_mode)) {
    char why[64];
    std::snprintf(why, sizeof why, "is %s", file_type_name(before.st_mode));
    return refuse(message, size, path, why);
  }
  const int fd = ::open(path, O_RDONLY | O_NONBLOCK | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0) {
    std::snprintf(message, size, "cannot open %s to check it: %s", path, std::strerror(errno));
    return StatusCode::io_error;
  }
  struct stat now {};
  Status s = ok_status();
  if (::fstat(fd, &now) != 0 || now.st_dev != before.st_dev || now.st_ino != before.st_ino ||
      !S_ISREG(now.st_mode)) {
    s = refuse(message, size, path, "changed while it was checked");
  } else {
    s = inspect_open(fd, path, rule, message, size);
  }
  ::close(fd);
  return s;
}

Expected<void> check_output_path(const std::string& path, OutputRule rule) {
  std::array<char, 4096 + 256> message{};
  const Status s = inspect_output_target(path.c_str(), rule, message.data(), message.size());
  if (s.ok()) return {};
  return Error{s, message.data()};
}

bool same_file(const std::string& a, const std::string& b) {
  struct stat sa {};
  struct stat sb {};
  return ::stat(a.c_str(), &sa) == 0 && ::stat(b.c_str(), &sb) == 0 && sa.st_dev == sb.st_dev &&
         sa.st_ino == sb.st_ino;
}

FileReadLock::~FileReadLock() {
  if (fd_ >= 0) ::close(fd_);
}

FileReadLock::FileReadLock(FileReadLock&& other) noexcept : fd_(other.fd_) { other.fd_ = -1; }

FileReadLock& FileReadLock::operator=(FileReadLock&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = other.fd_;
    other.fd_ = -1;
  }
  return *this;
}

Expected<FileReadLock> FileReadLock::hold(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    return make_error(StatusCode::io_error, "cannot open " + path + ": " + std::strerror(errno));
  }
  FileReadLock lock;
  lock.fd_ = fd;
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    return make_error(StatusCode::failed_precondition, path + " is not a regular file");
  }
  struct flock shared {};
  shared.l_type = F_RDLCK;
  shared.l_whence = SEEK_SET;
  shared.l_start = 0;
  shared.l_len = 0;
  if (::fcntl(fd, F_OFD_SETLK, &shared) != 0) {
    return make_error(
        StatusCode::failed_precondition,
        path + " is being written by another process (locked): " + std::strerror(errno));
  }
  return lock;
}

}  // namespace twister::hal
