// How long twister-station takes to be ready (issue 11, item 10): the real start-up
// (assemble_station: config, OBJ, journal lock and scan, checkpoint verify + restore,
// replay, simulator backends) on a 100 x 100 grid (10,000 vertices) whose journal
// holds 20,000 stroke records, in one run:
//   StationStart/empty_journal      baseline: the same start-up with no records
//   StationStart/full_replay        the 20,000 records replayed (no checkpoint)
//   StationStart/checkpoint         a checkpoint of the 20,000 records restored
// The program prints ratio lines (full_replay / checkpoint, checkpoint /
// empty_journal) from the same run. Files live in a temporary folder (page cache).
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
#include "twister/journal/journal_record.hpp"
#include "twister/meshio/mesh_generator.hpp"
#include "twister/meshio/obj_file.hpp"

namespace {

using namespace twister;
namespace fs = std::filesystem;

constexpr std::size_t kGrid = 100;
constexpr std::uint32_t kRecords = 20'000;

const fs::path& folder() {
  static const fs::path dir =
      fs::temp_directory_path() / ("twister_start_bench_" + std::to_string(::getpid()));
  return dir;
}

// 20,000 one-hand strokes with a twist, at random grid points (radius 0.1 m: ~80
// vertices each), encoded back to back.
std::vector<std::byte> journal_bytes() {
  std::vector<std::byte> out(journal::kFileHeader.begin(), journal::kFileHeader.end());
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> at(-0.9, 0.9);
  std::array<std::byte, journal::kMaxRecordBytes> buf{};
  for (std::uint32_t k = 0; k < kRecords; ++k) {
    journal::JournalRecord r;
    r.sequence = k;
    r.stroke.hand_mask = 1;
    r.stroke.radius_m = 0.1;
    const glm::dvec3 p{at(rng), at(rng), 0.0};
    r.stroke.start[0].origin_m = p;
    r.stroke.end[0].origin_m = p + glm::dvec3(0.01, 0.0, 0.02);
    r.stroke.end[0].u = {std::cos(0.2), std::sin(0.2), 0.0};
    r.stroke.end[0].v = {-std::sin(0.2), std::cos(0.2), 0.0};
    const auto n = journal::encode_record(r, buf);
    out.insert(out.end(), buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(*n));
  }
  return out;
}

station_app::StationConfig config_for(const std::string& journal) {
  const std::string text =
      "[station]\njournal = \"" + journal + "\"\nmesh = \"" + (folder() / "grid.obj").string() +
      "\"\n[tracker]\nbackend = \"sim\"\n[tracker.sim]\nscenario = \"idle\"\n"
      "[buttons]\nbackend = \"stylus\"\n[systemd]\nnotify = false\nwatchdog = false\n";
  return station_app::parse_station_config(text, "bench.toml").config;
}

// The files, once: the grid OBJ, an empty journal, the 20,000-record journal twice
// (one with the checkpoint a clean stop writes, one without).
void prepare() {
  static bool done = false;
  if (done) return;
  done = true;
  fs::create_directories(folder());
  meshio::MeshBuffer grid(meshio::grid_vertices(kGrid), meshio::grid_triangles(kGrid));
  (void)meshio::make_grid(grid.mesh(), kGrid, 1.0f);
  (void)meshio::save_obj(folder() / "grid.obj", grid.mesh());
  const std::vector<std::byte> bytes = journal_bytes();
  for (const char* name : {"full.twj", "checkpointed.twj"}) {
    std::ofstream(folder() / name, std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()),
               static_cast<std::streamsize>(bytes.size()));
  }
  std::ofstream(folder() / "empty.twj", std::ios::binary)
      .write(reinterpret_cast<const char*>(journal::kFileHeader.data()),
             journal::kFileHeader.size());
  auto parts = station_app::assemble_station(config_for((folder() / "checkpointed.twj").string()),
                                             {folder(), ""});
  if (!parts) {
    std::fprintf(stderr, "bench set-up: %s\n", parts.error().message.c_str());
    std::exit(1);
  }
  (*parts)->core->stop();  // writes checkpointed.twj.ckpt
  std::remove((folder() / "full.twj.ckpt").c_str());
}

void start(benchmark::State& state, const char* journal) {
  prepare();
  const station_app::StationConfig config = config_for((folder() / journal).string());
  std::uint64_t records = 0;
  for (auto _ : state) {
    auto parts = station_app::assemble_station(config, {folder(), ""});
    if (!parts) {
      state.SkipWithError(parts.error().message.c_str());
      return;
    }
    records = (*parts)->core->journal_records();
    benchmark::DoNotOptimize((*parts)->core->mesh().checksum());
  }
  state.counters["records"] = static_cast<double>(records);
}

void StationStart_empty_journal(benchmark::State& s) { start(s, "empty.twj"); }
void StationStart_full_replay(benchmark::State& s) { start(s, "full.twj"); }
void StationStart_checkpoint(benchmark::State& s) { start(s, "checkpointed.twj"); }

BENCHMARK(StationStart_empty_journal)->Unit(benchmark::kMillisecond)->Iterations(10);
BENCHMARK(StationStart_full_replay)->Unit(benchmark::kMillisecond)->Iterations(2);
BENCHMARK(StationStart_checkpoint)->Unit(benchmark::kMillisecond)->Iterations(10);

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
