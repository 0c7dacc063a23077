#include "export_file.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <mutex>
#include <utility>
#include <vector>

#include "twister/hal/posix_file_sink.hpp"

namespace twister::meshio::internal {
namespace {

using FileId = std::pair<dev_t, ino_t>;

struct OwnFiles {
  std::mutex mutex;
  std::vector<FileId> ids;
};

OwnFiles& own_files() {
  static OwnFiles files;
  return files;
}

bool file_id(const std::string& path, FileId& id) {
  struct stat st {};
  if (::lstat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) return false;
  id = {st.st_dev, st.st_ino};
  return true;
}

void remember(const std::string& path) {
  FileId id;
  if (!file_id(path, id)) return;
  OwnFiles& files = own_files();
  const std::lock_guard<std::mutex> lock(files.mutex);
  if (std::find(files.ids.begin(), files.ids.end(), id) == files.ids.end()) files.ids.push_back(id);
}

}  // namespace

bool written_by_this_process(const std::string& path) {
  FileId id;
  if (!file_id(path, id)) return false;
  OwnFiles& files = own_files();
  const std::lock_guard<std::mutex> lock(files.mutex);
  return std::find(files.ids.begin(), files.ids.end(), id) != files.ids.end();
}

hal::Expected<void> write_export_file(const std::string& path, std::string_view bytes,
                                      hal::OutputKind kind, bool force) {
  // A file this process wrote is of `kind` and ours to replace; anything else falls
  // under the output rule (refused unless `force` and of the same kind).
  const hal::OutputRule rule{kind, force || written_by_this_process(path)};
  if (auto written = hal::write_output_file(path, bytes, rule); !written) return written;
  remember(path);
  return {};
}

}  // namespace twister::meshio::internal
