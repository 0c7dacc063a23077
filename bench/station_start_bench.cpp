// How long twister-station takes to be ready (issue 11, item 10): the real start-up
// (assemble_station: config, OBJ, journal lock and scan, checkpoint verify + restore,
// replay, simulator backends) on a 100 x 100 grid (10,000 vertices) whose journal
// holds 20,000 stroke records, in one run:
//   StationStart/empty_journal      baseline: the same start-up with no records
//   StationStart/full_replay        the 20,000 records replayed (no checkpoint)
//   StationStart/checkpoint         a checkpoint of the 20,000 records restored
// and, with [sculpt] refine on (spare_vertices 40,000), a journal of 2,000 such strokes
// each refined to 1 mm at commit (checkpoint format 2 holds the grown mesh and the
// topology in the history):
//   StationStart/refined_full_replay  the 2,000 refined records replayed
//   StationStart/refined_checkpoint   a checkpoint of them restored
// The program prints ratio lines (full_replay / checkpoint, checkpoint /
// empty_journal, and the refined pair) from the same run. Files live in a temporary
// folder (page cache).
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "config/station_config.hpp"
#include "station_assembly.hpp"
#include "twister/journal/journal_format.hpp"
#include "twister/journal/journal_record.hpp"
#include "twister/meshio/mesh_generator.hpp"
#include "twister/meshio/obj_file.hpp"

namespace {

using namespace twister;
namespace fs = std::filesystem;

constexpr std::size_t kGrid = 100;
constexpr std::uint32_t kRecords = 20'000;
constexpr std::uint32_t kRefinedRecords = 2'000;
constexpr double kRefineThreshold = 0.001;

const fs::path& folder() {
  static const fs::path dir =
      fs::temp_directory_path() / ("twister_start_bench_" + std::to_string(::getpid()));
  return dir;
}

// `records` one-hand strokes with a twist, at random grid points (radius 0.1 m: ~80
// vertices each), refined at commit to `threshold` (0: not), encoded back to back.
// The format new journals get (version 2, its identity in each record).
constexpr journal::JournalFormat kFormat = journal::version2_format(1);

std::vector<std::byte> journal_header() {
  const auto header = journal::file_header(kFormat);
  return {header.begin(), header.begin() + static_cast<std::ptrdiff_t>(kFormat.header_bytes())};
}

std::vector<std::byte> journal_bytes(std::uint32_t records, double threshold) {
  std::vector<std::byte> out = journal_header();
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> at(-0.9, 0.9);
  std::array<std::byte, journal::kMaxRecordBytes> buf{};
  for (std::uint32_t k = 0; k < records; ++k) {
    journal::JournalRecord r;
    r.sequence = k;
    r.stroke.hand_mask = 1;
    r.stroke.radius_m = 0.1;
    r.stroke.refine_threshold_m = threshold;
    const glm::dvec3 p{at(rng), at(rng), 0.0};
    r.stroke.start[0].origin = p;
    r.stroke.end[0].origin = p + glm::dvec3(0.01, 0.0, 0.02);
    r.stroke.end[0].u = {std::cos(0.2), std::sin(0.2), 0.0};
    r.stroke.end[0].v = {-std::sin(0.2), std::cos(0.2), 0.0};
    const auto n = journal::encode_record(r, buf, kFormat);
    out.insert(out.end(), buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(*n));
  }
  return out;
}

station_app::StationFileConfig config_for(const std::string& journal, bool refine = false) {
  const std::string text =
      "[station]\njournal = \"" + journal + "\"\nmesh = \"" + (folder() / "grid.obj").string() +
      "\"\n" + (refine ? "spare_vertices = 40000\n" : "") +
      "[tracker]\nbackend = \"sim\"\n[tracker.sim]\nscenario = \"idle\"\n"
      "[buttons]\nbackend = \"stylus\"\n[systemd]\nnotify = false\nwatchdog = false\n" +
      (refine ? "[sculpt]\nrefine = true\nrefine_threshold_m = 0.001\n" : "");
  return station_app::parse_station_config(text, "bench.toml").config;
}

void write_bytes(const fs::path& path, const std::vector<std::byte>& bytes) {
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()),
             static_cast<std::streamsize>(bytes.size()));
}

// A clean stop of `journal` writes its checkpoint.
void write_checkpoint(const char* journal, bool refine) {
  auto parts = station_app::assemble_station(config_for((folder() / journal).string(), refine),
                                             {folder(), ""});
  if (!parts) {
    std::fprintf(stderr, "bench set-up: %s\n", parts.error().message.c_str());
    std::exit(1);
  }
  (*parts)->core->stop();
}

// The files, once: the grid OBJ, an empty journal, the 20,000-record journal twice
// (one with the checkpoint a clean stop writes, one without), the refined journal twice.
void prepare() {
  static bool done = false;
  if (done) return;
  done = true;
  fs::create_directories(folder());
  meshio::MeshBuffer grid(meshio::grid_vertices(kGrid), meshio::grid_triangles(kGrid));
  (void)meshio::make_grid(grid.mesh(), kGrid, 1.0f);
  (void)meshio::save_obj(folder() / "grid.obj", grid.mesh(), true);
  const std::vector<std::byte> bytes = journal_bytes(kRecords, 0.0);
  write_bytes(folder() / "full.twj", bytes);
  write_bytes(folder() / "checkpointed.twj", bytes);
  const std::vector<std::byte> refined = journal_bytes(kRefinedRecords, kRefineThreshold);
  write_bytes(folder() / "refined_full.twj", refined);
  write_bytes(folder() / "refined_checkpointed.twj", refined);
  write_bytes(folder() / "empty.twj", journal_header());
  write_checkpoint("checkpointed.twj", false);
  write_checkpoint("refined_checkpointed.twj", true);
}

void start(benchmark::State& state, const char* journal, bool refine = false) {
  prepare();
  const station_app::StationFileConfig config = config_for((folder() / journal).string(), refine);
  std::uint64_t records = 0;
  std::uint64_t replayed = 0;
  std::size_t vertices = 0;
  for (auto _ : state) {
    auto parts = station_app::assemble_station(config, {folder(), ""});
    if (!parts) {
      state.SkipWithError(parts.error().message.c_str());
      return;
    }
    records = (*parts)->core->journal_records();
    replayed = (*parts)->core->recovery().replayed;
    vertices = (*parts)->core->mesh().vertex_count();
    benchmark::DoNotOptimize((*parts)->core->mesh().checksum());
  }
  state.counters["records"] = static_cast<double>(records);
  state.counters["replayed"] = static_cast<double>(replayed);
  state.counters["vertices"] = static_cast<double>(vertices);
}

void StationStart_empty_journal(benchmark::State& s) { start(s, "empty.twj"); }
void StationStart_full_replay(benchmark::State& s) { start(s, "full.twj"); }
void StationStart_checkpoint(benchmark::State& s) { start(s, "checkpointed.twj"); }
void StationStart_refined_full_replay(benchmark::State& s) { start(s, "refined_full.twj", true); }
void StationStart_refined_checkpoint(benchmark::State& s) {
  start(s, "refined_checkpointed.twj", true);
}

BENCHMARK(StationStart_empty_journal)->Unit(benchmark::kMillisecond)->Iterations(10);
BENCHMARK(StationStart_full_replay)->Unit(benchmark::kMillisecond)->Iterations(2);
BENCHMARK(StationStart_checkpoint)->Unit(benchmark::kMillisecond)->Iterations(10);
BENCHMARK(StationStart_refined_full_replay)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(StationStart_refined_checkpoint)->Unit(benchmark::kMillisecond)->Iterations(10);

// Prints the ratios of the rows' real times from this very run.
class RatioReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    ConsoleReporter::ReportRuns(runs);
    for (const Run& r : runs) times_[r.benchmark_name()] = r.GetAdjustedRealTime();
  }
  void Finalize() override {
    ConsoleReporter::Finalize();
    const double empty = times_["StationStart_empty_journal/iterations:10"];
    const double full = times_["StationStart_full_replay/iterations:2"];
    const double ckpt = times_["StationStart_checkpoint/iterations:10"];
    if (empty > 0 && full > 0 && ckpt > 0) {
      std::printf("ratio full_replay / checkpoint: %.1f\n", full / ckpt);
      std::printf("ratio checkpoint / empty_journal: %.2f\n", ckpt / empty);
    }
    const double refined_full = times_["StationStart_refined_full_replay/iterations:1"];
    const double refined_ckpt = times_["StationStart_refined_checkpoint/iterations:10"];
    if (refined_full > 0 && refined_ckpt > 0) {
      std::printf("ratio refined_full_replay / refined_checkpoint: %.1f\n",
                  refined_full / refined_ckpt);
    }
    fs::remove_all(folder());
  }

 private:
  std::map<std::string, double> times_;
};

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  RatioReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();
  return 0;
}
