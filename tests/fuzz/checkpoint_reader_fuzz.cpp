// Fuzz target of the session checkpoint reader (issue 11). Input: either a checkpoint
// file as is (first byte even), or edits (offset, xor) applied to a valid checkpoint
// of a small session that the harness writes itself (first byte odd), so damaged
// files reach every section. Properties: never crashes or reads out of bounds;
// verify_checkpoint() never changes the session; a checkpoint that verifies restores
// into a model with only finite positions and a history that undoes within the mesh.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <new>
#include <span>

#include "fakes/fake_file_sink.hpp"
#include "fakes/fake_storage.hpp"
#include "twister/input/session_checkpoint.hpp"

namespace {

using namespace twister;

constexpr std::size_t kMaxInput = 1 << 14;
using Storage = test::FakeStorageWithStorage<1 << 16>;
using Sink = test::FakeFileSinkWithStorage<1 << 16>;
using Session = input::SculptSessionWithStorage<81, 81, 256, 8>;

void check(bool ok) {
  if (!ok) std::abort();
}

void make_grid(mesh::Mesh& m) {
  m.clear();
  for (int j = 0; j < 9; ++j) {
    for (int i = 0; i < 9; ++i)
      (void)m.add_vertex({0.25f * float(i) - 1.0f, 0.25f * float(j) - 1.0f, 0.0f});
  }
  for (std::uint32_t j = 0; j < 8; ++j) {
    for (std::uint32_t i = 0; i < 8; ++i)
      (void)m.add_triangle(j * 9 + i, j * 9 + i + 1, j * 9 + i + 9);
  }
}

// A session with two strokes, a move and an undo behind it.
Session& fresh_session(mesh::Mesh& mesh) {
  alignas(Session) static std::byte memory[sizeof(Session)];
  static Session* session = nullptr;
  static input::SculptSessionConfig config;
  if (session != nullptr) session->~Session();
  make_grid(mesh);
  session = new (memory) Session(config, mesh, nullptr);
  return *session;
}

void sculpt(Session& s) {
  journal::JournalRecord r;
  r.stroke.hand_mask = 1;
  r.stroke.radius_m = 0.6;
  r.stroke.end[0].origin_m = {0.1, 0.0, 0.2};
  (void)s.apply_record(r);
  r.sequence = 1;
  r.stroke.end[0].origin_m = {0.0, 0.1, -0.2};
  (void)s.apply_record(r);
  journal::JournalRecord move;
  move.type = journal::RecordType::object_move;
  move.sequence = 2;
  move.move.object_after.origin_m = {0.5, 0, 0};
  (void)s.apply_record(move);
  journal::JournalRecord undo;
  undo.type = journal::RecordType::undo;
  undo.sequence = 3;
  (void)s.apply_record(undo);
}

bool finite(const mesh::Mesh& m) {
  for (std::size_t i = 0; i < m.vertex_count(); ++i) {
    if (!std::isfinite(m.x()[i]) || !std::isfinite(m.y()[i]) || !std::isfinite(m.z()[i]))
      return false;
  }
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0 || size > kMaxInput) return 0;
  static mesh::MeshWithStorage<81, 128> mesh;
  static Storage file;
  file = Storage();
  if ((data[0] & 1) == 0) {
    file.load(std::as_bytes(std::span(data + 1, size - 1)));
  } else {
    Session& source = fresh_session(mesh);
    sculpt(source);
    static Sink sink;
    sink = Sink();
    input::CheckpointWriter writer(&sink);
    check(writer.begin(source, {8, 4, 0}, 7).ok());
    check(writer.step(source, 1 << 20).ok());
    file.load(sink.bytes());
    for (std::size_t i = 1; i + 2 < size; i += 3) {
      const std::size_t at = (std::size_t{data[i]} << 8 | data[i + 1]) % sink.bytes().size();
      file.corrupt(at, std::byte{data[i + 2]});
    }
  }
  Session& target = fresh_session(mesh);
  const std::uint64_t before = mesh.checksum();
  const auto header = input::read_checkpoint_header(file);
  if (!header.ok()) return 0;
  const Status verified = input::verify_checkpoint(file, *header, target);
  check(mesh.checksum() == before);
  if (!verified.ok()) return 0;
  check(input::restore_checkpoint(file, *header, target).ok());
  check(finite(mesh));
  // Undo until the restored history is empty (at most its 8 entries). The harness
  // calls only out-of-line session functions: core is built without RTTI, so UBSan's
  // vptr check must not see its polymorphic members from here.
  journal::JournalRecord undo;
  undo.type = journal::RecordType::undo;
  for (int i = 0; i < 16 && target.apply_record(undo).ok(); ++i) check(finite(mesh));
  return 0;
}
