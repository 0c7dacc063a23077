// FastrakParser throughput on a recorded-style binary stream (two stations, list
// 2,11,1, 33-byte records) against baselines measured in the same run: memcpy of the
// same bytes and a plain byte scan (counting '0' bytes). Also ASCII and a stream with
// noise bursts. Heap allocations inside the timed loops are counted (must be 0).
// After the runs it prints "ratio" lines: parser MB/s divided by each baseline's.
#include <benchmark/benchmark.h>

#include <array>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <new>
#include <random>
#include <string>
#include <vector>

#include "twister/tracker/fastrak_encoder.hpp"
#include "twister/tracker/fastrak_parser.hpp"

// Counting allocator for this program only: the timed loops must not allocate.
// (GCC flags free() after a replaced operator new as mismatched; it is not.)
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
#endif
namespace {
std::atomic<std::uint64_t> g_allocs{0};
}
void* operator new(std::size_t n) {
  g_allocs.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(n == 0 ? 1 : n)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace {

using namespace twister::tracker;

constexpr std::size_t kStreamBytes = 4 << 20;
constexpr std::size_t kReadChunk = 4096;  // a serial read() buffer

FastrakConfig make_config(Format f) {
  FastrakConfig c;
  c.format = f;
  for (int s = 0; s < 2; ++s) {
    c.stations[static_cast<std::size_t>(s)].enabled = true;
    c.stations[static_cast<std::size_t>(s)].list =
        OutputList::of({Item::position, Item::quaternion, Item::crlf});
  }
  return c;
}

std::vector<std::byte> make_stream(Format f, double noise_fraction) {
  const FastrakConfig c = make_config(f);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<std::byte> out;
  out.reserve(kStreamBytes + 256);
  std::array<std::byte, 256> buf{};
  std::uint64_t k = 0;
  while (out.size() < kStreamBytes) {
    FastrakPose p;
    p.station = static_cast<std::uint8_t>(1 + k % 2);
    const float t = static_cast<float>(k++) / 120.0f;
    p.position = {20.0f + 5.0f * std::sin(t), 3.0f * std::cos(t), 2.0f + u(rng) * 0.01f};
    const float h = 0.5f * t;
    p.quaternion = {std::cos(h), 0.0f, 0.0f, std::sin(h)};
    auto n = encode_record(p, c, buf);
    out.insert(out.end(), buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(*n));
    if (noise_fraction > 0 && std::uniform_real_distribution<double>(0, 1)(rng) < noise_fraction) {
      for (int i = 0; i < 20; ++i) out.push_back(static_cast<std::byte>(rng() & 0xFF));
    }
  }
  return out;
}

const std::vector<std::byte>& stream(int which) {
  static const std::vector<std::byte> binary = make_stream(Format::binary, 0.0);
  static const std::vector<std::byte> ascii = make_stream(Format::ascii, 0.0);
  static const std::vector<std::byte> noisy = make_stream(Format::binary, 0.01);
  return which == 0 ? binary : which == 1 ? ascii : noisy;
}

void parse(benchmark::State& state, int which, Format f) {
  const auto& s = stream(which);
  FastrakParser parser(make_config(f));
  std::uint64_t poses = 0;
  float sum = 0;
  const std::uint64_t allocs_before = g_allocs.load();
  for (auto _ : state) {
    for (std::size_t pos = 0; pos < s.size(); pos += kReadChunk) {
      const std::size_t n = std::min(kReadChunk, s.size() - pos);
      parser.feed(std::span<const std::byte>(s.data() + pos, n), [&](const FastrakEvent& e) {
        if (e.kind == EventKind::pose) {
          ++poses;
          sum += e.pose.position[0];
        }
      });
    }
    benchmark::DoNotOptimize(sum);
  }
  state.counters["heap_allocs"] = static_cast<double>(g_allocs.load() - allocs_before);
  state.counters["poses_per_iter"] =
      static_cast<double>(poses) / static_cast<double>(state.iterations());
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * s.size()));
}

void BM_ParserBinary(benchmark::State& state) { parse(state, 0, Format::binary); }
void BM_ParserAscii(benchmark::State& state) { parse(state, 1, Format::ascii); }
void BM_ParserBinaryNoisy(benchmark::State& state) { parse(state, 2, Format::binary); }

void BM_BaselineMemcpy(benchmark::State& state) {
  const auto& s = stream(0);
  std::vector<std::byte> dst(s.size());
  for (auto _ : state) {
    std::memcpy(dst.data(), s.data(), s.size());
    benchmark::ClobberMemory();
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * s.size()));
}

void BM_BaselineByteScan(benchmark::State& state) {
  const auto& s = stream(0);
  for (auto _ : state) {
    std::size_t zeros = 0;
    for (std::byte b : s) zeros += b == std::byte{'0'};
    benchmark::DoNotOptimize(zeros);
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * s.size()));
}

BENCHMARK(BM_BaselineMemcpy);
BENCHMARK(BM_BaselineByteScan);
BENCHMARK(BM_ParserBinary);
BENCHMARK(BM_ParserBinaryNoisy);
BENCHMARK(BM_ParserAscii);

// Keeps each run's bytes/s so the ratios can be printed after the table.
class RatioReporter : public benchmark::ConsoleReporter {
 public:
  std::map<std::string, double> rate;
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& r : runs) {
      auto it = r.counters.find("bytes_per_second");
      if (it != r.counters.end()) rate[r.benchmark_name()] = it->second.value;
    }
    ConsoleReporter::ReportRuns(runs);
  }
};

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  RatioReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  auto get = [&](const char* n) {
    auto it = reporter.rate.find(n);
    return it == reporter.rate.end() ? 0.0 : it->second;
  };
  const double memcpy_rate = get("BM_BaselineMemcpy");
  const double scan_rate = get("BM_BaselineByteScan");
  for (const char* n : {"BM_ParserBinary", "BM_ParserBinaryNoisy", "BM_ParserAscii"}) {
    const double r = get(n);
    if (r == 0.0) continue;
    std::printf("ratio %-22s %8.1f MB/s  = %.4f x memcpy, %.3f x byte scan\n", n, r / 1e6,
                memcpy_rate > 0 ? r / memcpy_rate : 0.0, scan_rate > 0 ? r / scan_rate : 0.0);
  }
  benchmark::Shutdown();
  return 0;
}
