// The exhibit tests' station "lives" (issue 25): each is a forked child running the
// real core Station (fake tracker and buttons, virtual clock) on real files: the
// journal (locked), its checkpoint (PosixFileSink) and the archive (ExhibitArchive),
// reporting one line per fact through a pipe ("recovered T F", "started ID RECORDS",
// "saved ID SEQ", ...). The parent then checks what is on disk: an archived journal
// replayed on an in-memory copy, record.json's values. Used by exhibit_day_test and
// exhibit_rotation_crash_test.
#pragma once

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <thread>

#include "../../core/station/station_fixture.hpp"
#include "exhibit_archive.hpp"
#include "fakes/fake_storage.hpp"
#include "twister/checkpoint/session_checkpoint.hpp"
#include "twister/hal/posix_file_sink.hpp"
#include "twister/hal/posix_file_storage.hpp"

namespace twister::station_app::exhibit_test {

using namespace station::test_fixture;  // NOLINT: the station fixture's names

inline constexpr ports::TimestampUs kS = 1'000'000;
inline constexpr std::time_t kDay0 = 1'795'000'000;  // 2026-11-18 (a virtual day's morning)
inline constexpr std::uint8_t kRightGrab = 3;        // the paper map's right grab

struct LifePaths {
  std::string dir, journal, archive;
};

// One life of the station, in the child. A test's life derives from it, opens the
// journal, builds its archive (archive_config()) and calls start(); then it sculpts
// with tick() / wait_s() and reports with say().
class StationLife {
 public:
  StationLife(const LifePaths& p, int fd, ports::TimestampUs t0, station::StationConfig config)
      : paths_(p),
        fd_(fd),
        config_(std::move(config)),
        clock_(t0),
        responder_(stream_, config_.session.protocol) {}

 protected:
  // The archive under paths_.archive for paths_.journal, on the virtual clock.
  ExhibitArchiveConfig archive_config(std::uint32_t keep_count) {
    ExhibitArchiveConfig a;
    a.dir = paths_.archive;
    a.journal_path = paths_.journal;
    a.keep_count = keep_count;
    a.wall_clock = [this] { return kDay0 + static_cast<std::time_t>(clock_.now_us() / kS); };
    a.mono_clock = [this] { return clock_.now_us(); };
    return a;
  }

  // Recovers the archive, then starts the station on `journal` (paths_.journal's
  // storage, possibly wrapped), its checkpoint and `archive`, and waits for the
  // tracker. Says "recovered T F" and "started ID RECORDS". 0, or the life's exit
  // code: 4 the archive did not recover, 5 the station did not start.
  int start(ExhibitArchive& archive, ports::Storage& journal, std::uint32_t journal_id) {
    auto recovered = archive.recover();
    if (!recovered) return 4;
    say("recovered %d %d\n", recovered->temporaries_removed, recovered->rotation_finished ? 1 : 0);
    make_grid(*mesh_);
    make_grid(*base_);
    // The checkpoint: after a cut, the old one names the old journal.
    hal::PosixFileSinkConfig out;
    out.path = paths_.journal + ".ckpt";
    out.replace = hal::PosixFileSinkConfig::Replace::own_magic;
    out.magic.assign(checkpoint::kCheckpointMagic.begin(), checkpoint::kCheckpointMagic.end());
    checkpoint_out_.emplace(out);
    const bool have_in = checkpoint_in_.open({out.path, false, false, true}).ok();
    const station::StationFiles files{nullptr,
                                      have_in ? &checkpoint_in_ : nullptr,
                                      &*checkpoint_out_,
                                      journal_id,
                                      &archive,
                                      base_.get(),
                                      recovered->visitors_today};
    station_ = std::make_unique<station::Station>(stream_, buttons_, clock_, journal, *mesh_,
                                                  work_->spans(), config_, files);
    if (!station_->start().ok()) return 5;
    say("started %08x %u\n", station_->visitor_view().sculpture,
        static_cast<unsigned>(station_->visitor_view().records));
    for (int i = 0; i < 500 && !station_->tracker_session().streaming(); ++i) tick();
    return 0;
  }

  template <typename... A>
  void say(const char* format, A... args) {
    char line[512];
    const int n = std::snprintf(line, sizeof line, format, args...);
    if (n > 0) (void)!::write(fd_, line, std::min(sizeof line - 1, static_cast<std::size_t>(n)));
  }
  // "saved ID SEQ" for every stroke the station reports saved.
  void drain() {
    for (auto e = station_->next_event(); e.ok(); e = station_->next_event()) {
      if (e->kind == SessionEventKind::committed && e->status.ok() && !e->stroke_end().repeat) {
        say("saved %08x %u\n", station_->visitor_view().sculpture, e->stroke_end().sequence);
      }
    }
  }
  // One tracker cycle (or `step`) of both hands; "t US" once per virtual second when
  // report_time_ is set.
  void tick(ports::TimestampUs step = 8'333) {
    responder_.service();
    responder_.emit(1, left_, false);
    responder_.emit(2, right_, false);
    (void)station_->poll();
    drain();
    responder_.service();
    clock_.advance_us(step);
    if (report_time_ && clock_.now_us() - said_us_ >= kS) {
      said_us_ = clock_.now_us();
      say("t %lld\n", static_cast<long long>(said_us_));
    }
  }
  void wait_s(double s) {
    const ports::TimestampUs end = clock_.now_us() + static_cast<ports::TimestampUs>(s * kS);
    while (clock_.now_us() < end) tick(50'000);
  }
  void press(std::uint8_t line, bool down) { buttons_.press(line, down, clock_.now_us()); }

  LifePaths paths_;
  int fd_;
  station::StationConfig config_;
  test::FakeByteStream stream_;
  test::FakeClock clock_;
  test::FakeButtonSourceWithStorage<1 << 16> buttons_;  // a day of presses
  FastrakResponder responder_;
  hal::PosixFileStorage journal_;
  std::unique_ptr<station::Station> station_;
  std::array<float, 3> left_{-10.0F, 0.0F, 5.0F};
  std::array<float, 3> right_{10.0F, 0.0F, 5.0F};
  bool report_time_ = false;

 private:
  std::unique_ptr<TestMesh> mesh_ = std::make_unique<TestMesh>();
  std::unique_ptr<TestMesh> base_ = std::make_unique<TestMesh>();
  std::unique_ptr<TestWork> work_ = std::make_unique<TestWork>();
  std::optional<hal::PosixFileSink> checkpoint_out_;
  hal::PosixFileStorage checkpoint_in_;
  ports::TimestampUs said_us_ = 0;
};

struct LifeRun {
  int status = 0;    // the life's exit code, or -signal
  std::string text;  // its report lines
};

// Runs `life(fd)` in a forked child, reading its report; kills it after
// `kill_after_ms` of real time (0: lets it run to its end).
inline LifeRun fork_life(const std::function<int(int fd)>& life, int kill_after_ms = 0) {
  LifeRun run;
  int fds[2];
  if (::pipe(fds) != 0) return {-1, ""};
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::close(fds[0]);
    ::_exit(life(fds[1]));
  }
  ::close(fds[1]);
  const auto start = std::chrono::steady_clock::now();
  ::fcntl(fds[0], F_SETFL, O_NONBLOCK);
  bool killed = false;
  for (;;) {
    char buf[4096];
    const ssize_t n = ::read(fds[0], buf, sizeof buf);
    if (n > 0) {
      run.text.append(buf, static_cast<std::size_t>(n));
      continue;
    }
    if (n == 0) break;  // the child is gone
    if (!killed && kill_after_ms > 0 &&
        std::chrono::steady_clock::now() - start > std::chrono::milliseconds(kill_after_ms)) {
      ::kill(pid, SIGKILL);
      killed = true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  ::close(fds[0]);
  int status = 0;
  ::waitpid(pid, &status, 0);
  run.status = WIFSIGNALED(status) ? -WTERMSIG(status) : WEXITSTATUS(status);
  return run;
}

inline std::string read_file(const std::filesystem::path& p) {
  std::ifstream f(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

// A value of record.json's `"key": value` lines (quotes removed), or "".
inline std::string json_value(const std::string& json, const std::string& key) {
  const auto at = json.find("\"" + key + "\": ");
  if (at == std::string::npos) return "";
  const auto from = at + key.size() + 4;
  std::string v = json.substr(from, json.find_first_of(",\n", from) - from);
  if (!v.empty() && v.front() == '"') v = v.substr(1, v.size() - 2);
  return v;
}

// A journal replayed onto the base grid: the model's checksum, its records and its
// identity (the station's own start-up path, on an in-memory copy).
struct Replayed {
  bool ok = false;
  std::uint64_t checksum = 0;
  std::uint32_t records = 0, id = 0;
};
inline Replayed replay(const std::string& bytes, station::StationConfig c) {
  Replayed out;
  auto storage = std::make_unique<test::FakeStorageWithStorage<>>();
  storage->load(std::as_bytes(std::span(bytes.data(), bytes.size())));
  auto mesh = std::make_unique<TestMesh>();
  make_grid(*mesh);
  auto work = std::make_unique<TestWork>();
  test::FakeByteStream stream;
  test::FakeButtonSource buttons;
  test::FakeClock clock(1);
  c.exhibit = {};
  station::Station s(stream, buttons, clock, *storage, *mesh, work->spans(), c);
  if (!s.recover().ok()) return out;
  const station::JournalRecovery& r = s.recovery();
  out.ok = !r.survey.torn_tail() && !r.survey.corrupt();
  out.checksum = s.mesh().checksum();
  out.records = static_cast<std::uint32_t>(r.survey.records);
  journal::JournalReader reader(*storage);
  if (reader.open().ok()) out.id = reader.format().id;
  return out;
}

}  // namespace twister::station_app::exhibit_test
