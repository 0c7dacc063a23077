// Output paths: the one rule every program that writes a file follows (twister
// replay / mesh / figure8, twister-bridge --export and snapshots), so no tool can
// destroy what it did not make. At `path` there may be
//   - nothing: written;
//   - a regular file of the kind the program writes (an OBJ over an OBJ, a PNG over
//     a PNG), only with `force` (the programs' --force; snapshots always force);
//   - never: a Twister journal or checkpoint (their magic), a file any process holds
//     a lock on (the running station's journal, and its base model, which the
//     station holds a shared lock on while it runs: hold_read_lock()), a FIFO,
//     device, socket, directory or symbolic link, or a file of another kind.
// The file is opened O_NONBLOCK after lstat(2) said it is regular, and fstat(2) must
// name the same inode, so the check never blocks and never follows a swapped link.
// check_output_path() is for start-up (it allocates its message);
// inspect_output_target() is the same check into a fixed buffer (PosixFileSink runs
// it again right before it renames its file into place).
#pragma once

#include <sys/types.h>

#include <cstddef>
#include <cstdint>
#include <string>

#include "twister/base/status.hpp"
#include "twister/hal/expected.hpp"

namespace twister::hal {

enum class OutputKind : std::uint8_t { obj, ply, glb, gltf, png, svg, stl };

struct OutputRule {
  OutputKind kind = OutputKind::obj;
  bool force = false;  // replace a regular file of `kind` (never anything else)
};

// The kind a file name asks for (.obj .ply .glb .gltf .png .svg .stl); false: none.
// An STL is recognised by an ASCII "solid" or the header our writer gives a binary
// one ("twister-station export"); any other binary STL is another kind.
bool output_kind_of(const std::string& path, OutputKind& kind);
const char* output_kind_name(OutputKind kind);

// ok: `path` may be written under `rule`. failed_precondition: refused, `message`
// says what is there and why; io_error: it could not be inspected.
Status inspect_output_target(const char* path, OutputRule rule, char* message,
                             std::size_t message_size);
Expected<void> check_output_path(const std::string& path, OutputRule rule);

// Are `a` and `b` the same file (same device and inode; false when either is missing)?
bool same_file(const std::string& a, const std::string& b);

// A shared (read) OFD lock held on a file for this object's lifetime: other readers
// may lock it too, check_output_path() refuses it. The station holds one on its base
// model while it runs.
class FileReadLock {
 public:
  FileReadLock() = default;
  ~FileReadLock();
  FileReadLock(FileReadLock&& other) noexcept;
  FileReadLock& operator=(FileReadLock&& other) noexcept;
  FileReadLock(const FileReadLock&) = delete;
  FileReadLock& operator=(const FileReadLock&) = delete;
  bool held() const { return fd_ >= 0; }

  // Opens `path` (a regular file, O_NONBLOCK) and takes the lock.
  static Expected<FileReadLock> hold(const std::string& path);

 private:
  int fd_ = -1;
};

// What a file that is not a regular one is, for messages: "a directory", "a FIFO",
// "a device", "a socket", "a symbolic link" ("not a regular file" otherwise).
const char* file_type_name(mode_t mode);

// The journal's and the checkpoint's magic ("TWJL", "TWCK"; hal cannot include the
// journal's headers: tests check they equal journal::kFileMagic and
// checkpoint::kCheckpointMagic).
inline constexpr char kJournalMagic[4] = {'T', 'W', 'J', 'L'};
inline constexpr char kCheckpointMagic[4] = {'T', 'W', 'C', 'K'};
// The first bytes of the 80-byte header of a binary STL twister writes (meshio).
inline constexpr char kStlHeaderPrefix[] = "twister-station export";

}  // namespace twister::hal
