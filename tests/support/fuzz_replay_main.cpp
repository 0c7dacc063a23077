// Driver for fuzz harnesses in ordinary (non-libFuzzer) builds: runs every file of
// the seed corpus, then a bounded number of deterministic mutations of them, through
// LLVMFuzzerTestOneInput. A crash or sanitizer report fails the CTest run.
//   <harness> CORPUS_DIR [ITERATIONS]
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s CORPUS_DIR [ITERATIONS]\n", argv[0]);
    return 2;
  }
  const long iterations = argc > 2 ? std::strtol(argv[2], nullptr, 10) : 20000;
  std::vector<std::vector<std::uint8_t>> seeds;
  for (const auto& entry : std::filesystem::directory_iterator(argv[1])) {
    if (!entry.is_regular_file()) continue;
    std::ifstream in(entry.path(), std::ios::binary);
    seeds.emplace_back(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  if (seeds.empty()) {
    std::fprintf(stderr, "no seed files in %s\n", argv[1]);
    return 2;
  }
  for (const auto& s : seeds) LLVMFuzzerTestOneInput(s.data(), s.size());

  std::mt19937_64 rng(0x7715737e5);  // fixed seed: reproducible CI runs
  std::vector<std::uint8_t> buf;
  for (long i = 0; i < iterations; ++i) {
    buf = seeds[rng() % seeds.size()];
    const int edits = 1 + static_cast<int>(rng() % 8);
    for (int e = 0; e < edits; ++e) {
      const auto kind = rng() % 4;
      if (kind == 0 && !buf.empty()) {
        buf[rng() % buf.size()] ^= static_cast<std::uint8_t>(1u << (rng() % 8));
      } else if (kind == 1 && !buf.empty()) {
        buf[rng() % buf.size()] = static_cast<std::uint8_t>(rng());
      } else if (kind == 2 && !buf.empty()) {
        buf.erase(buf.begin() + static_cast<long>(rng() % buf.size()));
      } else {
        const auto at = buf.empty() ? 0 : rng() % (buf.size() + 1);
        buf.insert(buf.begin() + static_cast<long>(at), static_cast<std::uint8_t>(rng()));
      }
    }
    if (rng() % 16 == 0 && buf.size() > 1) buf.resize(rng() % buf.size());
    LLVMFuzzerTestOneInput(buf.data(), buf.size());
  }
  std::printf("%zu seeds, %ld mutated inputs: no crash\n", seeds.size(), iterations);
  return 0;
}
