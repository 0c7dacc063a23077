// Fuzz target of the session checkpoint reader (issue 11; format version 2 with the
// topology of refined commits). Input: either a checkpoint file as is (first byte
// even), or edits (offset hi, offset lo, xor) applied to the valid checkpoint of a
// refined session that the harness writes itself (first byte odd; with bit 1 set the
// CRC is then made right again, so edits reach the structural checks behind it).
// Properties: never crashes or reads out of bounds; verify_checkpoint() never changes
// the session; a checkpoint that verifies restores into a model with only finite
// positions and triangles within the vertex count, and a history that undoes and
// redoes within the mesh. Seeds: tests/fuzz/corpus/checkpoint_reader_fuzz, written by
// checkpoint_corpus (tests/fuzz/checkpoint_corpus.cpp).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>

#include "checkpoint_fuzz_session.hpp"
#include "fakes/fake_storage.hpp"
#include "twister/base/checksum.hpp"

namespace {

using namespace twister;
using namespace twister::fuzz_support;

constexpr std::size_t kMaxInput = 1 << 15;  // the whole refined checkpoint fits
using Storage = test::FakeStorageWithStorage<1 << 16>;

void check(bool ok) {
  if (!ok) std::abort();
}

// Finite positions, triangles within the vertex count.
bool sound(const mesh::Mesh& m) {
  for (std::size_t i = 0; i < m.vertex_count(); ++i) {
    if (!std::isfinite(m.x()[i]) || !std::isfinite(m.y()[i]) || !std::isfinite(m.z()[i]))
      return false;
  }
  for (const std::uint32_t v : m.triangle_indices()) {
    if (v >= m.vertex_count()) return false;
  }
  return true;
}

// The harness's checkpoint with the input's edits (and the CRC made right again).
void load_edited(Storage& file, mesh::Mesh& mesh, const std::uint8_t* data, std::size_t size) {
  static Sink sink;  // the checkpoint, written once (the session is deterministic)
  static const bool written = write_checkpoint(mesh, sink) != nullptr;
  check(written);
  static std::array<std::byte, 1 << 16> bytes;
  const std::size_t n = sink.bytes().size();
  check(n >= 4 && n <= bytes.size());
  std::copy(sink.bytes().begin(), sink.bytes().end(), bytes.begin());
  for (std::size_t i = 1; i + 2 < size; i += 3) {
    const std::size_t at = (std::size_t{data[i]} << 8 | data[i + 1]) % n;
    bytes[at] ^= std::byte{data[i + 2]};
  }
  if ((data[0] & 2) != 0) {
    std::uint32_t crc = crc32(std::span<const std::byte>(bytes).first(n - 4));
    for (std::size_t k = 0; k < 4; ++k, crc >>= 8) bytes[n - 4 + k] = std::byte(crc & 0xffu);
  }
  file.load(std::span<const std::byte>(bytes).first(n));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0 || size > kMaxInput) return 0;
  static Mesh mesh;
  static Storage file;
  file = Storage();
  if ((data[0] & 1) == 0) {
    file.load(std::as_bytes(std::span(data + 1, size - 1)));
  } else {
    load_edited(file, mesh, data, size);
  }
  Session& target = fresh_session(mesh);
  const std::uint64_t before = mesh.checksum();
  const auto header = checkpoint::read_checkpoint_header(file);
  if (!header.ok()) return 0;
  const Status verified = checkpoint::verify_checkpoint(file, *header, target);
  check(mesh.checksum() == before);
  if (!verified.ok()) return 0;
  check(checkpoint::restore_checkpoint(file, *header, target).ok());
  check(sound(mesh));
  // Undo until the restored history is empty (at most its 8 entries), then redo it
  // all. The harness calls only out-of-line session functions: core is built without
  // RTTI, so UBSan's vptr check must not see its polymorphic members from here.
  journal::JournalRecord step;
  step.type = journal::RecordType::undo;
  for (int i = 0; i < 16 && target.apply_record(step).ok(); ++i) check(sound(mesh));
  step.type = journal::RecordType::redo;
  for (int i = 0; i < 16 && target.apply_record(step).ok(); ++i) check(sound(mesh));
  return 0;
}
