// Fuzz target of the journal reader and of journal replay into a SculptSession.
// Input: a journal file. Properties: never crashes or reads out of bounds; the
// reader stops at the first torn/corrupt record; truncate_tail() cuts only what an
// interrupted append can leave (a complete record that is refused is never cut), and
// after it the file reads back cleanly with the same records; replay never corrupts the mesh (every
// coordinate stays finite). The same bytes are also decoded as a raw record
// payload and applied to the session (exercises apply_record with any values).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <new>
#include <span>

#include "fakes/fake_storage.hpp"
#include "twister/journal/journal_format.hpp"
#include "twister/journal/journal_reader.hpp"
#include "twister/journal/journal_record.hpp"
#include "twister/session/sculpt_session.hpp"

namespace {

using namespace twister;

constexpr std::size_t kMaxInput = 1 << 16;
using Storage = test::FakeStorageWithStorage<kMaxInput>;
using Session = session::SculptSessionWithStorage<256, 256, 1024, 8>;

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

bool finite(const mesh::Mesh& m) {
  for (std::size_t i = 0; i < m.vertex_count(); ++i) {
    if (!std::isfinite(m.x()[i]) || !std::isfinite(m.y()[i]) || !std::isfinite(m.z()[i]))
      return false;
  }
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > kMaxInput) return 0;
  static Storage storage;
  static mesh::MeshWithStorage<256, 256> mesh;
  static session::SculptSessionConfig config;
  storage.load(std::as_bytes(std::span(data, size)));
  make_grid(mesh);
  static Session* session = nullptr;
  // One session object reused across inputs: re-created in place each run.
  alignas(Session) static std::byte session_memory[sizeof(Session)];
  if (session != nullptr) session->~Session();
  session = new (session_memory) Session(config, mesh, nullptr);

  journal::JournalReader reader(storage);
  if (!reader.open().ok()) return 0;  // not a journal: left alone
  std::size_t good = 0;
  for (;;) {
    auto record = reader.next();
    if (!record.ok()) break;
    ++good;
    (void)session->apply_record(*record);  // refused records leave the mesh as it was
    check(finite(mesh));
  }
  check(reader.good_end() <= size);
  const journal::TailProblem problem = reader.problem();
  const Status cut = reader.truncate_tail();
  if (!cut.ok()) {
    check(cut.code() == StatusCode::data_loss && !journal::may_be_torn(problem));
    check(storage.bytes().size() == size);  // nothing cut
  } else {
    journal::JournalReader again(storage);
    check(again.open().ok());
    std::size_t second = 0;
    for (auto r = again.next(); r.ok(); r = again.next()) ++second;
    check(second == good);
    check(again.problem() == journal::TailProblem::none);
  }

  // The raw bytes as one record payload: header bytes pick version and type.
  if (size >= 2) {
    auto record =
        journal::decode_payload(data[0], data[1], std::as_bytes(std::span(data + 2, size - 2)));
    if (record.ok()) {
      (void)session->apply_record(*record);
      check(finite(mesh));
    }
  }
  return 0;
}
