// The exhibit day (issue 25, label exhibit): a simulated day in virtual time. Each
// "life" of the station is a forked child running the real core Station (fake tracker
// and buttons, virtual clock) on real files: the journal (PosixFileStorage, locked),
// its checkpoint (PosixFileSink) and the archive (ExhibitArchive with hal/meshio's
// writers). Visitors come one after another with random strokes and idle gaps and end
// by idle, by the chord or by the display's command (some undone in the grace). The
// parent SIGKILLs the first lives at random real moments (anywhere: start-up, strokes,
// checkpoints, the archive, the rotation) and restarts the station on the same files;
// the last life fills the disk for a while (RLIMIT_FSIZE: writes past the limit fail
// with EFBIG) and stops cleanly. Then every check runs on what is on disk:
//   - every archive is complete (five files) and its journal replays to the model
//     checksum its record.json names; every archived journal holds one sculpture;
//   - every stroke a life reported saved (journal identity, sequence) is in its
//     sculpture's archived journal or the current journal; a sculpture with no archive
//     left is older than every archive kept (retention pruned it);
//   - the current journal is one sculpture (its identity is no archive's);
//   - the retention budget holds; no temporary is left.
// EXHIBIT_DAY_VISITORS (default 50), EXHIBIT_DAY_KILLS (5), EXHIBIT_DAY_SEED set the day.
#include <sys/resource.h>

#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "exhibit_life.hpp"
#include "prometheus_text.hpp"
#include "station_health.hpp"

namespace twister::station_app {
namespace {

using namespace exhibit_test;  // NOLINT: the exhibit lives' names
namespace fs = std::filesystem;

constexpr std::uint32_t kKeepArchives = 30;

std::uint64_t env(const char* name, std::uint64_t fallback) {
  const char* v = std::getenv(name);
  return v == nullptr ? fallback : std::strtoull(v, nullptr, 10);
}

station::StationConfig day_config() {
  station::StationConfig c = exhibit_test_config();
  c.checkpoint_interval = 3;
  return c;
}

// One life of the station, in the child. Reports to `fd` one line per fact:
// "saved ID SEQ", "t US" (virtual time), "visitors N", "done".
class Life : StationLife {
 public:
  Life(const LifePaths& p, int fd, ports::TimestampUs t0, std::uint64_t seed)
      : StationLife(p, fd, t0, day_config()), rng_(seed) {
    report_time_ = true;
  }

  int run(std::uint32_t visitors, bool full_disk) {
    ::signal(SIGXFSZ, SIG_IGN);
    if (!journal_.open({paths_.journal, true, true, false}).ok()) return 3;
    ExhibitArchive archive(archive_config(kKeepArchives), meshio_model_writer({0.0F, 0.0F, 1.0F}));
    if (const int rc = start(archive, journal_, static_cast<std::uint32_t>(rng_() | 1u)); rc != 0) {
      return rc;
    }
    for (std::uint32_t v = 0; v < visitors; ++v) {
      visit(full_disk && v == 1);
      const station::VisitorView view = station_->visitor_view();
      const station::StationCounters& c = station_->counters();
      const station::ExhibitCounters& x = station_->exhibit_counters();
      say("visitors %u phase %u visitor %u sculpture %08x flags %u committed %u not_saved %u "
          "refused %u archived %u failed %u rotate_failed %u tracker %u tx %zu\n",
          v + 1, static_cast<unsigned>(view.phase), view.visitor, view.sculpture,
          static_cast<unsigned>(view.flags), static_cast<unsigned>(c.events.strokes_committed),
          static_cast<unsigned>(c.events.strokes_not_saved),
          static_cast<unsigned>(c.events.refused), static_cast<unsigned>(x.archived),
          static_cast<unsigned>(x.archive_failures), static_cast<unsigned>(x.rotate_failures),
          static_cast<unsigned>(station_->status().tracker), stream_.tx().size());
    }
    wait_s(5.0);
    station_->stop();
    drain();
    // The metrics an operator watches, written as the loop writes them at its end.
    if (auto file = hal::MetricsFile::open(paths_.dir + "/metrics.prom")) {
      StationHealthConfig hc;
      hc.file = std::move(*file);
      hc.archive_path = paths_.archive;
      StationHealth health(std::move(hc));
      Backends backends;
      DisplayLink display;
      health.report(*station_, backends, display, hal::process_log(), clock_.now_us());
    }
    say("committed %u\n", static_cast<unsigned>(station_->counters().events.strokes_committed));
    say("disk_full %u not_saved %u\n",
        static_cast<unsigned>(station_->exhibit_counters().disk_full),
        static_cast<unsigned>(station_->counters().events.strokes_not_saved));
    say("done\n");
    return 0;
  }

 private:
  void stroke() {
    std::uniform_real_distribution<float> d(-3.0F, 3.0F);
    right_ = {10.0F + d(rng_), d(rng_), 5.0F + 0.3F * d(rng_)};
    for (int i = 0; i < 3; ++i) tick();
    press(kRightGrab, true);
    for (int i = 0; i < 3; ++i) tick();
    for (int k = 0; k < 6; ++k) {
      right_[0] += 0.2F * d(rng_);
      right_[1] += 0.2F * d(rng_);
      tick();
    }
    press(kRightGrab, false);
    for (int i = 0; i < 3; ++i) tick();
  }
  void chord(double hold_s) {
    press(kLeftRadius, true);
    press(kRightFreeze, true);
    wait_s(hold_s);
    press(kLeftRadius, false);
    press(kRightFreeze, false);
    tick();
  }
  void visit(bool full_disk) {
    const int strokes = std::uniform_int_distribution<int>(1, 5)(rng_);
    for (int s = 0; s < strokes; ++s) {
      stroke();
      wait_s(std::uniform_real_distribution<double>(0.2, 8.0)(rng_));
    }
    if (full_disk) {  // the disk fills: the end's archive fails until it is freed
      const rlimit small{4096, RLIM_INFINITY};
      (void)::setrlimit(RLIMIT_FSIZE, &small);
      stroke();  // likely not saved (the journal is past the limit)
    }
    switch (std::uniform_int_distribution<int>(0, 2)(rng_)) {
      case 0:
        wait_s(21.0);  // idle ends it
        break;
      case 1:
        chord(1.2);
        if (std::uniform_int_distribution<int>(0, 4)(rng_) == 0) {  // changed their mind
          wait_s(0.5);
          chord(1.2);
          stroke();
          chord(1.2);
        }
        break;
      default:
        (void)station_->new_sculpture();
        if (std::uniform_int_distribution<int>(0, 4)(rng_) == 0) {
          wait_s(1.0);
          (void)station_->undo_new_sculpture();
          stroke();
          (void)station_->new_sculpture();
        }
        break;
    }
    if (full_disk) {
      wait_s(8.0);
      const rlimit freed{RLIM_INFINITY, RLIM_INFINITY};
      (void)::setrlimit(RLIMIT_FSIZE, &freed);
    }
    // Grace, archive (retried every 2 s), then nobody for a while.
    wait_s(std::uniform_real_distribution<double>(6.0, 15.0)(rng_));
  }

  std::mt19937_64 rng_;
};

struct Reported {
  std::vector<std::uint32_t> order;  // sculptures in the order strokes were saved
  std::map<std::uint32_t, std::set<std::uint32_t>> saved;
  ports::TimestampUs t = 0;
  bool done = false;
  std::uint32_t visitors = 0;
  int temporaries_removed = 0, rotations_finished = 0;
  unsigned disk_full = 0, not_saved = 0, last_committed = 0;
};

void parse(const std::string& text, Reported& r) {
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    unsigned id = 0, seq = 0;
    long long t = 0;
    if (std::sscanf(line.c_str(), "saved %x %u", &id, &seq) == 2) {
      if (!r.saved.count(id)) r.order.push_back(id);
      r.saved[id].insert(seq);
    } else if (std::sscanf(line.c_str(), "t %lld", &t) == 1) {
      r.t = std::max<ports::TimestampUs>(r.t, t);
    } else if (std::sscanf(line.c_str(), "visitors %u", &seq) == 1) {
      r.visitors = seq;
    } else if (int tmp = 0, fin = 0;
               std::sscanf(line.c_str(), "recovered %d %d", &tmp, &fin) == 2) {
      r.temporaries_removed += tmp;
      r.rotations_finished += fin;
    } else if (std::sscanf(line.c_str(), "disk_full %u not_saved %u", &r.disk_full, &r.not_saved) ==
               2) {
    } else if (std::sscanf(line.c_str(), "committed %u", &r.last_committed) == 1) {
    } else if (line == "done") {
      r.done = true;
    }
  }
}

// Forks a life; kills it after `kill_after_ms` of real time (0: runs to its end).
// Returns its exit status (or -SIGKILL) and appends its report.
int run_life(const LifePaths& p, Reported& r, std::uint64_t seed, std::uint32_t visitors,
             bool full_disk, int kill_after_ms) {
  const ports::TimestampUs t0 = r.t + 10 * kS;
  const LifeRun run = fork_life(
      [&](int fd) {
        Life life(p, fd, t0, seed);
        return life.run(visitors, full_disk);
      },
      kill_after_ms);
  parse(run.text, r);
  if (std::getenv("EXHIBIT_DAY_VERBOSE") != nullptr) std::fputs(run.text.c_str(), stdout);
  return run.status;
}

TEST(ExhibitDay, VisitorsKillsAndAFullDiskLoseNothingAndEveryArchiveReplays) {
  const std::uint64_t want_visitors = env("EXHIBIT_DAY_VISITORS", 50);
  const std::uint64_t kills = env("EXHIBIT_DAY_KILLS", 5);
  const std::uint64_t seed = env("EXHIBIT_DAY_SEED", 2511);
  std::mt19937_64 rng(seed);
  const fs::path dir = fs::temp_directory_path() / ("exhibit_day_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const LifePaths p{dir.string(), (dir / "journal.twj").string(), (dir / "archive").string()};
  Reported r;
  int killed = 0;
  for (std::uint64_t life = 0; life < kills; ++life) {
    const int after = std::uniform_int_distribution<int>(40, 900)(rng);
    const int rc = run_life(p, r, seed * 100 + life, 1000, false, after);
    ASSERT_TRUE(rc == -SIGKILL || rc == 0) << "life " << life << " exited with " << rc;
    killed += rc == -SIGKILL;
    std::printf("life %d: %s after %d ms, %zu sculptures so far, virtual %.0f s\n",
                static_cast<int>(life), rc == -SIGKILL ? "SIGKILL" : "ended", after, r.order.size(),
                static_cast<double>(r.t) / kS);
  }
  // The last life: the rest of the day, with the full disk; stops cleanly.
  const std::uint32_t so_far = static_cast<std::uint32_t>(r.order.size());
  const std::uint32_t rest = std::max<std::uint32_t>(
      3, static_cast<std::uint32_t>(want_visitors) -
             std::min<std::uint32_t>(so_far, static_cast<std::uint32_t>(want_visitors)) + 1);
  ASSERT_EQ(run_life(p, r, seed * 100 + 99, rest, true, 0), 0);
  ASSERT_TRUE(r.done);
  EXPECT_EQ(killed, static_cast<int>(kills));

  // The archives: complete, each journal one sculpture replaying to its record.
  std::map<std::uint32_t, Replayed> archived;
  std::vector<std::string> names;
  std::uint64_t bytes = 0;
  for (const auto& e : fs::directory_iterator(p.archive)) {
    const std::string name = e.path().filename().string();
    ASSERT_TRUE(parse_archive_name(name, nullptr, nullptr, nullptr))
        << "left in the archive: " << name;
    names.push_back(name);
  }
  std::sort(names.begin(), names.end());
  for (const std::string& name : names) {
    const fs::path a = fs::path(p.archive) / name;
    for (const char* f :
         {"journal.twj", "model.stl", "model.glb", "thumbnail.png", "record.json"}) {
      ASSERT_TRUE(fs::is_regular_file(a / f) && fs::file_size(a / f) > 0) << name << "/" << f;
      bytes += fs::file_size(a / f);
    }
    const std::string json = read_file(a / "record.json");
    const Replayed rep = replay(read_file(a / "journal.twj"), day_config());
    ASSERT_TRUE(rep.ok) << name;
    std::uint32_t id = 0;
    (void)parse_archive_name(name, &id, nullptr, nullptr);
    EXPECT_EQ(rep.id, id) << name;
    char sum[20];
    std::snprintf(sum, sizeof sum, "%016" PRIx64, rep.checksum);
    EXPECT_EQ(json_value(json, "model_checksum"), sum) << name << ": replay differs";
    EXPECT_EQ(json_value(json, "journal_records"), std::to_string(rep.records)) << name;
    EXPECT_GT(rep.records, 0u) << name;
    EXPECT_EQ(archived.count(id), 0u) << "two archives of sculpture " << id;
    archived[id] = rep;
  }
  EXPECT_LE(names.size(), kKeepArchives);
  // Visitor numbers go on across restarts: the kept archives are the newest, numbered
  // one after the other, the last one the day's last visitor.
  std::uint32_t previous = 0;
  for (const std::string& name : names) {
    std::uint32_t v = 0;
    (void)parse_archive_name(name, nullptr, &v, nullptr);
    if (previous != 0) {
      EXPECT_EQ(v, previous + 1) << name;
    }
    previous = v;
  }
  EXPECT_EQ(previous, r.order.size());
  // The full disk was met: archives refused (EFBIG counts as full) and retried.
  EXPECT_GE(r.disk_full, 1u);
  // The current journal: one sculpture, none of the archived ones.
  const Replayed current = replay(read_file(p.journal), day_config());
  ASSERT_TRUE(current.ok);
  EXPECT_EQ(archived.count(current.id), 0u);
  // Every stroke reported saved is in its sculpture's journal; sculptures without an
  // archive are older than every archive kept (pruned) or the current one.
  std::size_t first_kept = r.order.size();
  for (std::size_t i = 0; i < r.order.size(); ++i) {
    if (archived.count(r.order[i])) first_kept = std::min(first_kept, i);
  }
  std::uint64_t strokes = 0, lost = 0;
  for (std::size_t i = 0; i < r.order.size(); ++i) {
    const std::uint32_t id = r.order[i];
    const std::set<std::uint32_t>& seqs = r.saved[id];
    strokes += seqs.size();
    const Replayed* in = archived.count(id) ? &archived[id] : id == current.id ? &current : nullptr;
    if (in == nullptr) {
      EXPECT_LT(i, first_kept) << "sculpture " << std::hex << id << " has no archive";
      continue;
    }
    for (const std::uint32_t s : seqs) lost += s >= in->records;
  }
  EXPECT_EQ(lost, 0u);
  EXPECT_GE(r.order.size(), want_visitors) << "visitors with saved strokes";
  // The metrics file: valid for promtool, its numbers the day's.
  const fs::path prom = dir / "metrics.prom";
  ASSERT_TRUE(fs::is_regular_file(prom));
  const std::string text = read_file(prom);
  const auto metric = [&](const std::string& name) { return test::prometheus_sample(text, name); };
  EXPECT_EQ(metric("twister_visitors_today"), static_cast<double>(r.order.size()));
  EXPECT_EQ(metric("twister_strokes_committed_total"), static_cast<double>(r.last_committed));
  EXPECT_GT(metric("twister_archive_free_bytes"), 0.0);
  ASSERT_EQ(std::system("command -v promtool >/dev/null 2>&1"), 0)
      << "promtool is missing (.ci/deps.sh installs Debian's prometheus)";
  const std::string check = "promtool check metrics < " + prom.string() + " >/dev/null 2>&1";
  EXPECT_EQ(std::system(check.c_str()), 0) << "promtool check metrics refuses " << prom;
  std::printf("exhibit day: %zu sculptures with saved strokes (%" PRIu64
              " strokes reported saved, 0 lost), %d SIGKILLs, %zu archives kept (%" PRIu64
              " bytes), current journal %u records; full disk: %u archive attempts refused, %u "
              "strokes not saved; restarts removed %d unfinished archive(s), finished %d "
              "rotation(s)\n",
              r.order.size(), strokes, killed, names.size(), bytes, current.records, r.disk_full,
              r.not_saved, r.temporaries_removed, r.rotations_finished);
  if (::testing::Test::HasFailure()) {
    std::printf("kept for inspection: %s\n", dir.c_str());
  } else {
    fs::remove_all(dir);
  }
}

}  // namespace
}  // namespace twister::station_app
