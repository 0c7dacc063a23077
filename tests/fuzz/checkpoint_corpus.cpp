// The seed corpus of checkpoint_reader_fuzz, made from the harness's own refined
// session (checkpoint_fuzz_session.hpp) and the format's layout, so a format change
// regenerates it:
//   checkpoint_corpus DIR           writes the seeds into DIR
//   checkpoint_corpus --check DIR   exit 1 when DIR is not exactly these seeds (CTest
//                                   checkpoint_corpus_current)
// Seeds (first byte: even = a file as is; odd = edits of the harness's checkpoint,
// with bit 1 = its CRC made right again): the valid checkpoint whole and as is,
// one flipped byte in every section (header, positions, triangles, entries, vertex
// changes, triangle changes, CRC), structural edits with a right CRC (a triangle
// index out of range, a refined entry's counts, an appended triangle out of order, an
// entry without topology with topology fields, a mesh triangle on a vertex that an
// undoable refined entry added), a version-1 header, the magic alone.
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "checkpoint_fuzz_session.hpp"
#include "fakes/fake_storage.hpp"

namespace {

using namespace twister;
using namespace twister::fuzz_support;
using Seed = std::vector<std::uint8_t>;

// Field offsets in an entry (session_checkpoint.hpp).
constexpr std::size_t kEntryVerticesBefore = 32, kEntryVerticesAfter = 36, kEntryTopology = 49;

struct Edit {
  std::size_t at;
  std::uint8_t mask;
};

Seed edits(bool reseal, const std::vector<Edit>& list) {
  Seed s{static_cast<std::uint8_t>(reseal ? 3 : 1)};
  for (const Edit& e : list) {
    s.push_back(static_cast<std::uint8_t>(e.at >> 8));
    s.push_back(static_cast<std::uint8_t>(e.at & 0xffu));
    s.push_back(e.mask);
  }
  return s;
}

// Edits that make the u32 at `at` of `file` hold `value`.
std::vector<Edit> set_u32(std::span<const std::byte> file, std::size_t at, std::uint32_t value) {
  std::vector<Edit> out;
  for (std::size_t i = 0; i < 4; ++i) {
    const auto mask = static_cast<std::uint8_t>(std::to_integer<std::uint8_t>(file[at + i]) ^
                                                ((value >> (8 * i)) & 0xffu));
    if (mask != 0) out.push_back({at + i, mask});
  }
  return out;
}

// A mesh triangle that the last undoable refined entry did not rewrite, moved onto the
// first vertex that entry added: only its undo can tell (UndoHistory refuses it).
std::vector<Edit> triangle_on_added_vertex(std::span<const std::byte> file, std::size_t triangles,
                                           const session::UndoHistory& history) {
  std::size_t k = history.undo_depth();
  while (k-- > 0 && !history.entries()[k].topology) {
  }
  const session::UndoEntry& e = history.entries()[k];
  std::uint32_t t = 0;
  for (std::size_t i = 0; i < e.triangle_change_count; ++i) {
    if (history.triangle_changes()[e.first_triangle_change + i].index == t) {
      ++t;
      i = std::size_t(-1);  // again from the first
    }
  }
  return set_u32(file, triangles + checkpoint::kCheckpointTriangleBytes * t, e.vertices_before);
}

Seed raw(std::span<const std::byte> bytes) {
  Seed s{0};
  for (const std::byte b : bytes) s.push_back(std::to_integer<std::uint8_t>(b));
  return s;
}

std::map<std::string, Seed> seeds(std::span<const std::byte> file,
                                  const checkpoint::CheckpointHeader& h,
                                  const session::UndoHistory& history) {
  using namespace checkpoint;
  using session::UndoEntry;
  const std::size_t positions = kCheckpointHeaderBytes;
  const std::size_t triangles = positions + std::size_t{12} * h.vertex_count;
  const std::size_t entries = triangles + kCheckpointTriangleBytes * h.triangle_count;
  const std::size_t changes = entries + kCheckpointEntryBytes * h.entry_count;
  const std::size_t triangle_changes = changes + kCheckpointChangeBytes * h.used_changes;
  const std::size_t crc =
      triangle_changes + kCheckpointTriangleChangeBytes * h.used_triangle_changes;
  const std::size_t last = entries + (h.entry_count - 1) * kCheckpointEntryBytes;
  const std::size_t move = last - kCheckpointEntryBytes;  // the object move
  const UndoEntry& e = history.entries().back();
  const std::size_t appended = e.first_triangle_change + e.triangle_change_count -
                               (std::size_t{e.triangles_after} - e.triangles_before);
  std::vector<std::byte> version1(file.begin(), file.end());
  version1[4] = std::byte{1};
  return {
      {"valid", edits(false, {})},
      {"raw_valid", raw(file)},
      {"raw_version1", raw(version1)},
      {"raw_magic", raw(std::as_bytes(std::span("TWCK", 4)))},
      {"flip_header", edits(false, {{40, 0x01}})},  // vertex_count
      {"flip_position", edits(false, {{positions + std::size_t{4} * 5 + 3, 0x80}})},
      {"flip_triangle", edits(false, {{triangles + std::size_t{12} * 3 + 1, 0x10}})},
      {"flip_entry", edits(false, {{last + kEntryTopology, 0x01}})},
      {"flip_change", edits(false, {{changes + kCheckpointChangeBytes * 2, 0x01}})},
      {"flip_triangle_change", edits(false, {{triangle_changes + 4, 0x01}})},
      {"flip_crc", edits(false, {{crc, 0x01}})},
      {"reseal_triangle_index", edits(true, {{triangles + 3, 0x01}})},
      {"reseal_vertices_after", edits(true, {{last + kEntryVerticesAfter, 0x01}})},
      {"reseal_appended_order",
       edits(true, {{triangle_changes + appended * kCheckpointTriangleChangeBytes, 0x02}})},
      {"reseal_move_topology_fields", edits(true, {{move + kEntryVerticesBefore, 0x04}})},
      {"reseal_triangle_on_added_vertex",
       edits(true, triangle_on_added_vertex(file, triangles, history))},
  };
}

Seed read_seed(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

int main(int argc, char** argv) {
  const bool check = argc == 3 && std::strcmp(argv[1], "--check") == 0;
  if (argc != 2 && !check) {
    std::fprintf(stderr, "usage: %s [--check] DIR\n", argv[0]);
    return 2;
  }
  const std::filesystem::path dir = argv[argc - 1];
  static Mesh mesh;
  static Sink sink;
  const Session* source = write_checkpoint(mesh, sink);
  test::FakeStorageWithStorage<1 << 16> file;
  file.load(sink.bytes());
  const auto header = checkpoint::read_checkpoint_header(file);
  if (source == nullptr || !header.ok() || header->entry_count < 2 ||
      !source->history().entries().back().topology ||
      source->history().entries()[header->entry_count - 2].topology) {
    std::fprintf(stderr, "the harness's session is not the one the seeds expect\n");
    return 1;
  }
  std::printf(
      "checkpoint: %zu bytes, %u vertices, %u triangles, %llu entries (%llu undone), "
      "%llu vertex changes, %llu triangle changes\n",
      sink.bytes().size(), header->vertex_count, header->triangle_count,
      static_cast<unsigned long long>(header->entry_count),
      static_cast<unsigned long long>(header->entry_count - header->undo_count),
      static_cast<unsigned long long>(header->used_changes),
      static_cast<unsigned long long>(header->used_triangle_changes));
  const auto all = seeds(sink.bytes(), *header, source->history());
  int stale = 0;
  std::set<std::string> names;
  for (const auto& [name, seed] : all) {
    names.insert(name);
    const std::filesystem::path path = dir / name;
    if (!check) {
      std::ofstream(path, std::ios::binary)
          .write(reinterpret_cast<const char*>(seed.data()),
                 static_cast<std::streamsize>(seed.size()));
    } else if (!std::filesystem::exists(path) || read_seed(path) != seed) {
      std::fprintf(stderr, "stale or missing: %s\n", path.c_str());
      ++stale;
    }
  }
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (names.count(entry.path().filename().string()) != 0) continue;
    if (!check) {
      std::filesystem::remove(entry.path());  // a seed of an older format
      continue;
    }
    std::fprintf(stderr, "not a seed of this format: %s\n", entry.path().c_str());
    ++stale;
  }
  if (stale > 0) {
    std::fprintf(stderr, "regenerate: %s %s\n", argv[0], dir.c_str());
    return 1;
  }
  std::printf("%zu seeds %s %s\n", all.size(), check ? "current in" : "written to", dir.c_str());
  return 0;
}
