// The rotation's crash points (issue 25, label exhibit): the station is stopped at each
// step of the documented on-disk protocol (docs/reliability.md "Exhibit mode"), then a
// new station starts on those files. The stop is deterministic: the first life (a
// forked child running the core Station on real files, with its checkpoint, as the
// exhibit day does)
// archives a first sculpture, sculpts a second and ends it; at the chosen step of its
// archive (ExhibitArchiveConfig::step_hook) or of the journal's cut and new header (a
// Storage that reports each call on the journal) the child calls _exit: no destructor,
// no flush, the lock released by the kernel, as after SIGKILL. The second life
// recovers, starts, ends the sculpture its journal holds (if any) and stops. Checked on
// disk: the station started; no temporary is left; every archive is complete (five
// files) and replays to its record's checksum; the second sculpture is archived exactly
// once (v0002, every stroke reported saved in it); the first one is complete or pruned,
// never partial; right after the restart the journal holds exactly the current
// sculpture (the second one, whole, before the archive's rename; a new, empty journal
// after it); at the end it is a new empty journal that no archive holds.
#include <cinttypes>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "exhibit_life.hpp"

namespace twister::station_app {
namespace {

using namespace exhibit_test;  // NOLINT: the exhibit lives' names
namespace fs = std::filesystem;

// Where the first life stops (after the named step).
enum class Stop : std::uint8_t {
  temporary_made,
  journal_copied,
  writer_temporary,  // inside the STL writer: its own temporary written, not renamed
  stl_written,
  glb_written,
  thumbnail_written,
  record_written,
  temporary_synced,
  renamed,
  archive_synced,
  prune_renamed,  // and one of its files removed (partly emptied)
  before_cut,     // archive() returned ok; the journal's truncate not yet called
  cut,            // truncate(0) done, not synced
  cut_synced,
  header_written,  // the new header appended, not synced
  header_synced,
};
constexpr const char* kStopNames[] = {"temporary_made",
                                      "journal_copied",
                                      "writer_temporary",
                                      "stl_written",
                                      "glb_written",
                                      "thumbnail_written",
                                      "record_written",
                                      "temporary_synced",
                                      "renamed",
                                      "archive_synced",
                                      "prune_renamed",
                                      "before_cut",
                                      "cut",
                                      "cut_synced",
                                      "header_written",
                                      "header_synced"};
bool before_rename(Stop s) { return s < Stop::renamed; }

station::StationConfig crash_config() {
  station::StationConfig c = exhibit_test_config();
  c.checkpoint_interval = 2;
  c.exhibit.visitor.idle_us = 60 * kS;
  c.exhibit.visitor.grace_us = 2 * kS;
  c.exhibit.chord_lines = 0;  // ended by the command only
  return c;
}

// The journal's Storage, reporting the cut and the new header to `hook` when armed.
class HookedStorage final : public ports::Storage {
 public:
  explicit HookedStorage(ports::Storage& inner) : inner_(inner) {}
  std::function<void(Stop)> hook;
  bool armed = false;

 private:
  Result<std::uint64_t> do_size() override { return inner_.size(); }
  Result<std::size_t> do_read_at(std::uint64_t offset, std::span<std::byte> dest) override {
    return inner_.read_at(offset, dest);
  }
  Status do_append(std::span<const std::byte> src) override {
    const Status s = inner_.append(src);
    if (armed && cut_) {
      header_ = true;
      hook(Stop::header_written);
    }
    return s;
  }
  Status do_sync() override {
    const Status s = inner_.sync();
    if (armed && header_) hook(Stop::header_synced);
    if (armed && cut_) hook(Stop::cut_synced);
    return s;
  }
  Status do_truncate(std::uint64_t length) override {
    if (armed && length == 0) hook(Stop::before_cut);
    const Status s = inner_.truncate(length);
    if (armed && length == 0) {
      cut_ = true;
      hook(Stop::cut);
    }
    return s;
  }
  ports::Storage& inner_;
  bool cut_ = false, header_ = false;
};

// Writes the STL writer's own temporary (PosixFileSink's name) and stops there.
class StoppingWriter final : public ArchiveModelWriter {
 public:
  StoppingWriter(std::unique_ptr<ArchiveModelWriter> inner, std::function<void()> stop)
      : inner_(std::move(inner)), stop_(std::move(stop)) {}
  bool armed = false;
  int write_stl(const std::string& path, const mesh::Mesh& m, const Pose& pose) override {
    if (armed) {
      std::ofstream(path + ".tmp-" + std::to_string(::getpid()) + "-0") << "solid half";
      stop_();
    }
    return inner_->write_stl(path, m, pose);
  }
  int write_glb(const std::string& path, const mesh::Mesh& m, const Pose& pose) override {
    return inner_->write_glb(path, m, pose);
  }
  int write_thumbnail(const std::string& path, const mesh::Mesh& m, const Pose& pose) override {
    return inner_->write_thumbnail(path, m, pose);
  }

 private:
  std::unique_ptr<ArchiveModelWriter> inner_;
  std::function<void()> stop_;
};

// One life in a forked child. Reports "saved ID SEQ", "recovered T F", "started ID
// RECORDS", "ended_today N", "done" to `fd`. `stop`: where the first life stops.
class Life : StationLife {
 public:
  Life(const LifePaths& p, int fd, ports::TimestampUs t0)
      : StationLife(p, fd, t0, crash_config()) {}

  int run(bool first, Stop stop) {
    if (!journal_.open({paths_.journal, true, true, false}).ok()) return 3;
    HookedStorage hooked(journal_);
    const auto at = [this, stop](Stop s) {
      if (s == stop) {
        if (s == Stop::prune_renamed) remove_one_pruned_file();
        say("stopped %s\n", kStopNames[static_cast<int>(s)]);
        ::_exit(0);  // as SIGKILL: nothing flushed, nothing destroyed
      }
    };
    hooked.hook = at;
    ExhibitArchiveConfig a = archive_config(1);  // the second archive prunes the first
    bool armed = false;
    a.step_hook = [&armed, &at](ArchiveStep s) {
      if (armed) at(static_cast<Stop>(static_cast<int>(s) + (s >= ArchiveStep::stl_written)));
    };
    auto writer = std::make_unique<StoppingWriter>(meshio_model_writer({0.0F, 0.0F, 1.0F}),
                                                   [&at] { at(Stop::writer_temporary); });
    StoppingWriter* stopping = writer.get();
    ExhibitArchive archive(a, std::move(writer));
    if (const int rc = start(archive, hooked, 0x1234567u + (first ? 0u : 1u)); rc != 0) return rc;
    if (first) {
      sculpture(2);  // the first sculpture: archived, whole
      armed = true;
      hooked.armed = true;
      stopping->armed = stop == Stop::writer_temporary;
      sculpture(3);  // the second: stopped in its rotation
      return 6;      // not stopped: the step was never met
    }
    if (station_->visitor_view().records > 0) end_and_archive();
    station_->stop();
    drain();
    say("ended_today %u\n", static_cast<unsigned>(station_->exhibit_counters().ended_today));
    say("done\n");
    return 0;
  }

 private:
  void remove_one_pruned_file() {
    for (const auto& e : fs::directory_iterator(paths_.archive)) {
      if (e.path().filename().string().rfind(".tmp-prune-", 0) == 0) {
        fs::remove(e.path() / "model.glb");
      }
    }
  }
  void stroke(int k) {
    right_ = {10.0F + static_cast<float>(k % 3), static_cast<float>(k % 2), 5.0F};
    for (int i = 0; i < 3; ++i) tick();
    press(kRightGrab, true);
    for (int i = 0; i < 3; ++i) tick();
    for (int i = 0; i < 6; ++i) {
      right_[0] += 0.3F;
      right_[1] -= 0.2F;
      tick();
    }
    press(kRightGrab, false);
    for (int i = 0; i < 3; ++i) tick();
  }
  void end_and_archive() {
    (void)station_->new_sculpture();
    wait_s(4.0);  // the grace, then the archive and the rotation
  }
  void sculpture(int strokes) {
    for (int s = 0; s < strokes; ++s) {
      stroke(s);
      wait_s(0.5);
    }
    end_and_archive();
  }
};

struct Report {
  std::vector<std::uint32_t> order;
  std::map<std::uint32_t, std::set<std::uint32_t>> saved;
  std::vector<std::pair<std::uint32_t, unsigned>> started;  // identity, records
  int temporaries_removed = 0, rotations_finished = 0;
  unsigned ended_today = 0;
  std::string stopped;
  bool done = false;
};

void parse(const std::string& text, Report& r) {
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    unsigned id = 0, n = 0;
    int t = 0, f = 0;
    char name[64] = {};
    if (std::sscanf(line.c_str(), "saved %x %u", &id, &n) == 2) {
      if (!r.saved.count(id)) r.order.push_back(id);
      r.saved[id].insert(n);
    } else if (std::sscanf(line.c_str(), "started %x %u", &id, &n) == 2) {
      r.started.emplace_back(id, n);
    } else if (std::sscanf(line.c_str(), "recovered %d %d", &t, &f) == 2) {
      r.temporaries_removed += t;
      r.rotations_finished += f;
    } else if (std::sscanf(line.c_str(), "ended_today %u", &n) == 1) {
      r.ended_today = n;
    } else if (std::sscanf(line.c_str(), "stopped %63s", name) == 1) {
      r.stopped = name;
    } else if (line == "done") {
      r.done = true;
    }
  }
}

int run_life(const LifePaths& p, Report& r, bool first, Stop stop, ports::TimestampUs t0) {
  const LifeRun run = fork_life([&](int fd) {
    Life life(p, fd, t0);
    return life.run(first, stop);
  });
  parse(run.text, r);
  return run.status;
}

class RotationCrash : public ::testing::TestWithParam<Stop> {};

TEST_P(RotationCrash, TheNextStartLosesNothingAndArchivesExactlyOnce) {
  const Stop stop = GetParam();
  const fs::path dir = fs::temp_directory_path() / ("exhibit_crash_" + std::to_string(::getpid()) +
                                                    "_" + kStopNames[static_cast<int>(stop)]);
  fs::remove_all(dir);
  fs::create_directories(dir);
  const LifePaths p{dir.string(), (dir / "journal.twj").string(), (dir / "archive").string()};
  Report first, second;
  ASSERT_EQ(run_life(p, first, true, stop, 1 * kS), 0) << "the first life did not stop";
  ASSERT_EQ(first.stopped, kStopNames[static_cast<int>(stop)]);
  ASSERT_EQ(first.order.size(), 2u) << "two sculptures with saved strokes";
  const std::uint32_t s1 = first.order[0], s2 = first.order[1];
  ASSERT_EQ(first.saved[s1].size(), 2u);
  ASSERT_EQ(first.saved[s2].size(), 3u);

  ASSERT_EQ(run_life(p, second, false, stop, 1000 * kS), 0) << "the station did not start";
  ASSERT_TRUE(second.done);
  ASSERT_EQ(second.started.size(), 1u);
  // Right after the restart the journal holds exactly the current sculpture.
  if (before_rename(stop)) {
    EXPECT_EQ(second.started[0].first, s2);
    EXPECT_EQ(second.started[0].second, 3u) << "the second sculpture, whole";
    EXPECT_EQ(second.rotations_finished, 0);
  } else {
    EXPECT_NE(second.started[0].first, s2);
    EXPECT_EQ(second.started[0].second, 0u) << "a new, empty journal";
    EXPECT_EQ(second.rotations_finished, stop < Stop::cut ? 1 : 0);
  }
  EXPECT_EQ(second.saved.size(), 0u);
  EXPECT_EQ(second.ended_today, 2u) << "metrics' visitors today";

  // On disk: no temporary; every archive complete, replaying to its record.
  std::map<std::uint32_t, int> archives_of;
  std::map<std::uint32_t, Replayed> archived;
  std::map<std::uint32_t, std::uint32_t> visitor_of;
  for (const auto& e : fs::directory_iterator(p.archive)) {
    const std::string name = e.path().filename().string();
    std::uint32_t id = 0, visitor = 0;
    ASSERT_TRUE(parse_archive_name(name, &id, &visitor, nullptr)) << "left: " << name;
    for (const char* f :
         {"journal.twj", "model.stl", "model.glb", "thumbnail.png", "record.json"}) {
      EXPECT_TRUE(fs::is_regular_file(e.path() / f) && fs::file_size(e.path() / f) > 0)
          << name << "/" << f;
    }
    std::size_t entries = 0;
    for ([[maybe_unused]] const auto& f : fs::directory_iterator(e.path())) ++entries;
    EXPECT_EQ(entries, 5u) << name;
    const Replayed rep = replay(read_file(e.path() / "journal.twj"), crash_config());
    ASSERT_TRUE(rep.ok) << name;
    EXPECT_EQ(rep.id, id);
    char sum[20];
    std::snprintf(sum, sizeof sum, "%016" PRIx64, rep.checksum);
    EXPECT_EQ(json_value(read_file(e.path() / "record.json"), "model_checksum"), sum) << name;
    ++archives_of[id];
    archived[id] = rep;
    visitor_of[id] = visitor;
  }
  EXPECT_EQ(archives_of[s2], 1) << "the second sculpture archived exactly once";
  EXPECT_EQ(visitor_of[s2], 2u);
  EXPECT_LE(archives_of[s1], 1);
  if (archives_of[s1] == 1) {
    EXPECT_EQ(visitor_of[s1], 1u);
  }
  // Nothing reported saved is lost.
  std::uint64_t lost = 0, strokes = 0;
  for (const std::uint32_t id : {s1, s2}) {
    if (!archived.count(id)) continue;  // s1: pruned by retention (keep 1)
    for (const std::uint32_t seq : first.saved[id]) {
      ++strokes;
      lost += seq >= archived[id].records;
    }
  }
  EXPECT_EQ(lost, 0u);
  // The journal now: a new, empty one that no archive holds.
  const Replayed current = replay(read_file(p.journal), crash_config());
  ASSERT_TRUE(current.ok);
  EXPECT_EQ(current.records, 0u);
  EXPECT_EQ(archives_of.count(current.id), 0u);
  std::printf(
      "stop after %-17s: restart removed %d temporar%s, finished %d rotation%s; "
      "archives %zu (second sculpture once, %u records, %" PRIu64
      " saved strokes checked, 0 lost); journal at restart %u records\n",
      kStopNames[static_cast<int>(stop)], second.temporaries_removed,
      second.temporaries_removed == 1 ? "y" : "ies", second.rotations_finished,
      second.rotations_finished == 1 ? "" : "s", archived.size(), archived[s2].records, strokes,
      second.started[0].second);
  if (::testing::Test::HasFailure()) {
    std::printf("kept for inspection: %s\n", dir.c_str());
  } else {
    fs::remove_all(dir);
  }
}

INSTANTIATE_TEST_SUITE_P(EachStep, RotationCrash,
                         ::testing::Values(Stop::temporary_made, Stop::journal_copied,
                                           Stop::writer_temporary, Stop::stl_written,
                                           Stop::glb_written, Stop::thumbnail_written,
                                           Stop::record_written, Stop::temporary_synced,
                                           Stop::renamed, Stop::archive_synced, Stop::prune_renamed,
                                           Stop::before_cut, Stop::cut, Stop::cut_synced,
                                           Stop::header_written, Stop::header_synced),
                         [](const ::testing::TestParamInfo<Stop>& param) {
                           return std::string(kStopNames[static_cast<int>(param.param)]);
                         });

}  // namespace
}  // namespace twister::station_app
