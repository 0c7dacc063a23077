// ExhibitArchive: a directory per sculpture, built in a temporary directory, fsynced
// and renamed (see the header and docs/reliability.md "Exhibit mode").
#include "exhibit_archive.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cinttypes>
#include <cstdio>
#include <cstring>
#include <random>
#include <vector>

#include "twister/hal/posix_file_sink.hpp"
#include "twister/journal/journal_reader.hpp"

namespace twister::station_app {
namespace {

// The file names an archive directory holds: nothing else is ever removed.
constexpr std::array<const char*, 5> kArchiveFiles{"journal.twj", "model.stl", "model.glb",
                                                   "thumbnail.png", "record.json"};

bool is_full(int err) { return err == ENOSPC || err == EDQUOT || err == EFBIG; }

int fsync_path(const std::string& path, bool directory) {
  const int fd = ::open(path.c_str(), (directory ? O_DIRECTORY : 0) | O_RDONLY | O_CLOEXEC);
  if (fd < 0) return errno;
  const int rc = ::fsync(fd);
  const int err = rc == 0 ? 0 : errno;
  ::close(fd);
  return err;
}

// Writes all of `bytes` to `fd` (retrying short writes and EINTR); errno or 0.
int write_all(int fd, const void* bytes, std::size_t n) {
  const auto* p = static_cast<const char*>(bytes);
  while (n > 0) {
    const ssize_t w = ::write(fd, p, n);
    if (w < 0 && errno == EINTR) continue;
    if (w < 0) return errno;
    if (w == 0) return ENOSPC;
    p += w;
    n -= static_cast<std::size_t>(w);
  }
  return 0;
}

int write_new_file(const std::string& path, const std::string& text) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) return errno;
  int err = write_all(fd, text.data(), text.size());
  if (err == 0 && ::fsync(fd) != 0) err = errno;
  ::close(fd);
  return err;
}

std::string hex8(std::uint32_t v) {
  std::array<char, 12> b{};
  std::snprintf(b.data(), b.size(), "%08x", v);
  return b.data();
}

std::string utc(std::time_t t, const char* format) {
  std::tm tm{};
  gmtime_r(&t, &tm);
  std::array<char, 40> b{};
  std::strftime(b.data(), b.size(), format, &tm);
  return b.data();
}

// Removes our files from `dir`, then `dir` (left when it holds anything else). Our
// files include the writers' temporaries (`NAME.tmp-PID-N`, PosixFileSink's names) a
// crash inside a writer leaves behind.
bool remove_archive_dir(const std::string& dir) {
  for (const char* f : kArchiveFiles) {
    const std::string path = dir + "/" + f;
    (void)::unlink(path.c_str());
    (void)hal::PosixFileSink::remove_stale_temporaries(path);
  }
  return ::rmdir(dir.c_str()) == 0;
}

std::uint64_t dir_bytes(const std::string& dir) {
  std::uint64_t total = 0;
  for (const char* f : kArchiveFiles) {
    struct stat st {};
    if (::stat((dir + "/" + f).c_str(), &st) == 0) total += static_cast<std::uint64_t>(st.st_size);
  }
  return total;
}

struct JournalCounts {
  std::uint32_t records = 0, strokes = 0, moves = 0, undos = 0, redos = 0;
};

JournalCounts count_records(ports::Storage& journal) {
  JournalCounts c;
  journal::JournalReader reader(journal);
  if (!reader.open().ok()) return c;
  for (auto r = reader.next(); r.ok(); r = reader.next()) {
    ++c.records;
    switch (r->type) {
      case journal::RecordType::stroke:
        ++c.strokes;
        break;
      case journal::RecordType::object_move:
        ++c.moves;
        break;
      case journal::RecordType::undo:
        ++c.undos;
        break;
      case journal::RecordType::redo:
        ++c.redos;
        break;
    }
  }
  return c;
}

}  // namespace

bool parse_archive_name(const std::string& name, std::uint32_t* id, std::uint32_t* visitor,
                        std::string* day) {
  // YYYYMMDDTHHMMSSZ-vNNNN-IIIIIIII
  if (name.size() != 31 || name[8] != 'T' || name[15] != 'Z' || name[16] != '-' ||
      name[17] != 'v' || name[22] != '-') {
    return false;
  }
  for (std::size_t i :
       {0u, 1u, 2u, 3u, 4u, 5u, 6u, 7u, 9u, 10u, 11u, 12u, 13u, 14u, 18u, 19u, 20u, 21u}) {
    if (name[i] < '0' || name[i] > '9') return false;
  }
  for (std::size_t i = 23; i < 31; ++i) {
    if (std::strchr("0123456789abcdef", name[i]) == nullptr || name[i] == '\0') return false;
  }
  if (id != nullptr) *id = static_cast<std::uint32_t>(std::stoul(name.substr(23), nullptr, 16));
  if (visitor != nullptr) *visitor = static_cast<std::uint32_t>(std::stoul(name.substr(18, 4)));
  if (day != nullptr) *day = name.substr(0, 8);
  return true;
}

ExhibitArchive::ExhibitArchive(ExhibitArchiveConfig config,
                               std::unique_ptr<ArchiveModelWriter> writer)
    : config_(std::move(config)), writer_(std::move(writer)) {
  if (!config_.wall_clock) config_.wall_clock = [] { return std::time(nullptr); };
  if (config_.keep_count == 0) config_.keep_count = 1;
}

std::vector<std::string> ExhibitArchive::list() const {
  std::vector<std::string> names;
  DIR* d = ::opendir(config_.dir.c_str());
  if (d == nullptr) return names;
  while (const dirent* e = ::readdir(d)) {
    const std::string name = e->d_name;
    if (parse_archive_name(name, nullptr, nullptr, nullptr)) names.push_back(name);
  }
  ::closedir(d);
  std::sort(names.begin(), names.end());
  return names;
}

hal::Expected<ArchiveRecovery> ExhibitArchive::recover() {
  ArchiveRecovery out;
  if (::mkdir(config_.dir.c_str(), 0755) != 0 && errno != EEXIST) {
    return hal::Error{StatusCode::io_error,
                      "exhibit.archive_dir " + config_.dir + ": " + std::strerror(errno)};
  }
  struct stat st {};
  if (::stat(config_.dir.c_str(), &st) != 0 || !S_ISDIR(st.st_mode)) {
    return hal::Error{StatusCode::invalid_argument,
                      "exhibit.archive_dir " + config_.dir + ": not a directory"};
  }
  // 1. Temporaries of an archive a crash interrupted: rolled back (the journal still
  //    holds the sculpture).
  if (DIR* d = ::opendir(config_.dir.c_str())) {
    std::vector<std::string> tmps;
    while (const dirent* e = ::readdir(d)) {
      const std::string name = e->d_name;
      if (name.rfind(".tmp-", 0) == 0) tmps.push_back(name);
    }
    ::closedir(d);
    for (const std::string& t : tmps) {
      if (remove_archive_dir(config_.dir + "/" + t)) ++out.temporaries_removed;
    }
  }
  // 2. A rotation the crash interrupted after the archive was complete: the journal's
  //    bytes are an archive's journal.twj byte for byte, so it is cut (finished).
  std::vector<char> journal;
  if (std::FILE* f = std::fopen(config_.journal_path.c_str(), "rb")) {
    std::array<char, 65536> buf{};
    for (std::size_t n; (n = std::fread(buf.data(), 1, buf.size(), f)) > 0;) {
      journal.insert(journal.end(), buf.data(), buf.data() + n);
    }
    std::fclose(f);
  }
  const std::string today = utc(config_.wall_clock(), "%Y%m%d");
  for (const std::string& name : list()) {
    std::uint32_t visitor = 0;
    std::string day;
    (void)parse_archive_name(name, nullptr, &visitor, &day);
    if (day == today) out.visitors_today = std::max(out.visitors_today, visitor);
    if (journal.empty() || out.rotation_finished) continue;
    std::FILE* f = std::fopen((config_.dir + "/" + name + "/journal.twj").c_str(), "rb");
    if (f == nullptr) continue;
    std::vector<char> archived(journal.size() + 1);
    const std::size_t n = std::fread(archived.data(), 1, archived.size(), f);
    std::fclose(f);
    if (n == journal.size() && std::equal(journal.begin(), journal.end(), archived.begin())) {
      if (::truncate(config_.journal_path.c_str(), 0) != 0 ||
          fsync_path(config_.journal_path, false) != 0) {
        return hal::Error{StatusCode::io_error, "journal " + config_.journal_path +
                                                    ": archived as " + name +
                                                    " but cannot be cut: " + std::strerror(errno)};
      }
      out.rotation_finished = true;
      out.archive_of_journal = name;
    }
  }
  const std::vector<std::string> names = list();
  stats_.kept = static_cast<std::uint32_t>(names.size());
  stats_.kept_bytes = 0;
  for (const std::string& n : names) stats_.kept_bytes += dir_bytes(config_.dir + "/" + n);
  return out;
}

std::uint32_t ExhibitArchive::do_next_journal_id() {
  std::random_device rd;
  std::uint32_t id = 0;
  while (id == 0) id = rd();
  return id;
}

station::ArchiveOutcome ExhibitArchive::fail(int err, const std::string& what,
                                             const std::string& tmp) {
  if (!tmp.empty()) (void)remove_archive_dir(tmp);
  ++stats_.failed;
  if (is_full(err)) ++stats_.disk_full;
  stats_.last_errno = err;
  stats_.last_error = what + ": " + std::strerror(err);
  return {StatusCode::io_error, is_full(err)};
}

station::ArchiveOutcome ExhibitArchive::do_archive(const station::SculptureSummary& s,
                                                   ports::Storage& journal,
                                                   std::uint64_t journal_bytes,
                                                   const mesh::Mesh& mesh, const Pose& pose) {
  const std::string id = hex8(s.sculpture);
  // Reused: an archive of this sculpture holding exactly these journal bytes (the
  // rotation after it failed and is tried again).
  for (const std::string& name : list()) {
    if (name.compare(23, 8, id) != 0) continue;
    const std::string path = config_.dir + "/" + name + "/journal.twj";
    struct stat st {};
    if (::stat(path.c_str(), &st) == 0 && static_cast<std::uint64_t>(st.st_size) == journal_bytes) {
      return {};
    }
  }
  const std::time_t now = config_.wall_clock();
  char visitor[8];
  std::snprintf(visitor, sizeof visitor, "%04u", std::min<std::uint32_t>(s.visitor, 9999));
  const std::string name = utc(now, "%Y%m%dT%H%M%SZ") + "-v" + visitor + "-" + id;
  const std::string tmp = config_.dir + "/.tmp-" + id + "-" + std::to_string(::getpid());
  (void)remove_archive_dir(tmp);
  if (::mkdir(tmp.c_str(), 0755) != 0) return fail(errno, "archive " + tmp, "");
  step(ArchiveStep::temporary_made);
  // The journal, byte for byte.
  {
    const int fd =
        ::open((tmp + "/journal.twj").c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    if (fd < 0) return fail(errno, "archive journal", tmp);
    std::array<std::byte, 65536> buf{};
    int err = 0;
    for (std::uint64_t at = 0; at < journal_bytes && err == 0;) {
      const auto want =
          static_cast<std::size_t>(std::min<std::uint64_t>(buf.size(), journal_bytes - at));
      auto n = journal.read_at(at, std::span(buf).first(want));
      if (!n.ok() || *n == 0) {
        err = EIO;
        break;
      }
      err = write_all(fd, buf.data(), *n);
      at += *n;
    }
    if (err == 0 && ::fsync(fd) != 0) err = errno;
    ::close(fd);
    if (err != 0) return fail(err, "archive journal", tmp);
  }
  step(ArchiveStep::journal_copied);
  if (const int err = writer_->write_stl(tmp + "/model.stl", mesh, pose); err != 0) {
    return fail(err, "archive model.stl", tmp);
  }
  step(ArchiveStep::stl_written);
  if (const int err = writer_->write_glb(tmp + "/model.glb", mesh, pose); err != 0) {
    return fail(err, "archive model.glb", tmp);
  }
  step(ArchiveStep::glb_written);
  if (const int err = writer_->write_thumbnail(tmp + "/thumbnail.png", mesh, pose); err != 0) {
    return fail(err, "archive thumbnail.png", tmp);
  }
  step(ArchiveStep::thumbnail_written);
  for (const char* f : {"model.stl", "model.glb", "thumbnail.png"}) {
    if (const int err = fsync_path(tmp + "/" + f, false); err != 0) return fail(err, f, tmp);
  }
  // The record.
  const JournalCounts c = count_records(journal);
  const ports::TimestampUs mono = config_.mono_clock ? config_.mono_clock() : s.now_us;
  const auto ago = [&](ports::TimestampUs t) {
    return now - static_cast<std::time_t>((mono - t) / 1'000'000);
  };
  std::array<char, 1024> json{};
  std::snprintf(json.data(), json.size(),
                "{\n  \"format\": \"twister-sculpture-1\",\n  \"sculpture\": \"%s\",\n"
                "  \"visitor\": %u,\n  \"day\": \"%s\",\n  \"began_utc\": \"%s\",\n"
                "  \"ended_utc\": \"%s\",\n  \"archived_utc\": \"%s\",\n  \"sculpting_s\": %.1f,\n"
                "  \"end\": \"%s\",\n  \"journal_records\": %u,\n  \"strokes\": %u,\n"
                "  \"object_moves\": %u,\n  \"undos\": %u,\n  \"redos\": %u,\n"
                "  \"journal_bytes\": %" PRIu64
                ",\n  \"vertices\": %zu,\n  \"triangles\": %zu,\n"
                "  \"model_checksum\": \"%016" PRIx64 "\"\n}\n",
                id.c_str(), s.visitor, utc(now, "%Y-%m-%d").c_str(),
                utc(ago(s.began_us), "%Y-%m-%dT%H:%M:%SZ").c_str(),
                utc(ago(s.ended_us), "%Y-%m-%dT%H:%M:%SZ").c_str(),
                utc(now, "%Y-%m-%dT%H:%M:%SZ").c_str(),
                static_cast<double>(s.ended_us - s.began_us) / 1e6,
                session::sculpture_end_name(s.end), c.records, c.strokes, c.moves, c.undos, c.redos,
                journal_bytes, mesh.vertex_count(), mesh.triangle_count(), s.checksum);
  if (const int err = write_new_file(tmp + "/record.json", json.data()); err != 0) {
    return fail(err, "archive record.json", tmp);
  }
  step(ArchiveStep::record_written);
  // Durable under its final name, or not there at all.
  if (const int err = fsync_path(tmp, true); err != 0) return fail(err, "archive " + tmp, tmp);
  step(ArchiveStep::temporary_synced);
  const std::string final_path = config_.dir + "/" + name;
  struct stat st {};
  if (::lstat(final_path.c_str(), &st) == 0) return fail(EEXIST, "archive " + final_path, tmp);
  if (::rename(tmp.c_str(), final_path.c_str()) != 0) return fail(errno, "archive " + name, tmp);
  step(ArchiveStep::renamed);
  if (const int err = fsync_path(config_.dir, true); err != 0) {
    return fail(err, "archive " + config_.dir, "");
  }
  step(ArchiveStep::archive_synced);
  ++stats_.written;
  stats_.last_archive = name;
  prune(name);
  return {};
}

void ExhibitArchive::prune(const std::string& keep) {
  std::vector<std::string> names = list();
  std::vector<std::uint64_t> bytes;
  std::uint64_t total = 0;
  for (const std::string& n : names) {
    bytes.push_back(dir_bytes(config_.dir + "/" + n));
    total += bytes.back();
  }
  std::size_t count = names.size();
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (count <= config_.keep_count && total <= config_.keep_bytes) break;
    if (names[i] == keep || count <= 1) continue;  // never the current sculpture
    // Out of the archive's names first (atomic), so a crash mid-removal leaves a
    // temporary the next start removes, never a half archive under a final name.
    const std::string from = config_.dir + "/" + names[i];
    const std::string doomed = config_.dir + "/.tmp-prune-" + names[i];
    if (::rename(from.c_str(), doomed.c_str()) != 0) continue;
    step(ArchiveStep::prune_renamed);
    if (!remove_archive_dir(doomed)) {  // not only ours: put back, left alone
      (void)::rename(doomed.c_str(), from.c_str());
      continue;
    }
    ++stats_.pruned;
    --count;
    total -= bytes[i];
  }
  (void)fsync_path(config_.dir, true);
  stats_.kept = static_cast<std::uint32_t>(count);
  stats_.kept_bytes = total;
}

}  // namespace twister::station_app
