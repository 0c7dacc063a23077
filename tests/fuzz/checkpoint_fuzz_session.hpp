// The session behind the checkpoint reader's fuzz harness and its corpus generator
// (checkpoint_reader_fuzz.cpp, checkpoint_corpus.cpp): a 9 x 9 grid with room for
// refinement, three strokes refined at commit, an object move and an undo, so its
// checkpoint (format version 2) has triangles, refined entries (one of them undone,
// its topology redoable), an entry without topology and both change pools in use.
// Sessions live in static storage (no allocation per input).
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <new>

#include "fakes/fake_file_sink.hpp"
#include "twister/checkpoint/session_checkpoint.hpp"
#include "twister/session/sculpt_session.hpp"

namespace twister::fuzz_support {

inline constexpr std::uint32_t kGrid = 9;
inline constexpr std::size_t kSpare = 96;
inline constexpr std::size_t kVertices = kGrid * kGrid + kSpare;
inline constexpr std::size_t kTriangles = 2 * (kGrid - 1) * (kGrid - 1) + 2 * kSpare;
using Mesh = mesh::MeshWithStorage<kVertices, kTriangles>;
using Session = session::SculptSessionWithStorage<kVertices, kVertices, 512, 8, kTriangles>;
using Sink = test::FakeFileSinkWithStorage<1 << 16>;
inline constexpr checkpoint::CheckpointAnchor kAnchor{8, 5, 0};
inline constexpr std::uint64_t kBaseChecksum = 7;

// 9 x 9 vertices over [-1, 1]^2 at z = 0, two triangles per cell.
inline void make_grid(mesh::Mesh& m) {
  m.clear();
  for (std::uint32_t j = 0; j < kGrid; ++j) {
    for (std::uint32_t i = 0; i < kGrid; ++i) {
      (void)m.add_vertex({0.25f * float(i) - 1.0f, 0.25f * float(j) - 1.0f, 0.0f});
    }
  }
  for (std::uint32_t j = 0; j + 1 < kGrid; ++j) {
    for (std::uint32_t i = 0; i + 1 < kGrid; ++i) {
      const std::uint32_t a = j * kGrid + i;
      (void)m.add_triangle(a, a + 1, a + kGrid);
      (void)m.add_triangle(a + 1, a + kGrid + 1, a + kGrid);
    }
  }
}

// A fresh session on a fresh grid (the previous one ends).
inline Session& fresh_session(mesh::Mesh& mesh) {
  alignas(Session) static std::byte memory[sizeof(Session)];
  static Session* session = nullptr;
  static const session::SculptSessionConfig config;
  if (session != nullptr) session->~Session();
  make_grid(mesh);
  session = new (memory) Session(config, mesh, nullptr);
  return *session;
}

// One-hand stroke record `sequence`: grabs at `at`, drags by `by`, turns by `turn`
// about z; refined at commit to 4 mm.
inline journal::JournalRecord stroke(std::uint32_t sequence, glm::dvec3 at, glm::dvec3 by,
                                     double turn) {
  journal::JournalRecord r;
  r.sequence = sequence;
  r.stroke.hand_mask = 1;
  r.stroke.radius_m = 0.6;
  r.stroke.refine_threshold_m = 0.004;
  r.stroke.start[0].origin = at;
  r.stroke.end[0].origin = at + by;
  r.stroke.end[0].u = {std::cos(turn), std::sin(turn), 0.0};
  r.stroke.end[0].v = {-std::sin(turn), std::cos(turn), 0.0};
  return r;
}

// Refined strokes, a move, a refined stroke, an undo of it (calls only out-of-line
// session functions: see the harness).
inline void sculpt(Session& s) {
  (void)s.apply_record(stroke(0, {0.1, 0.0, 0.0}, {0.0, 0.0, 0.2}, 0.3));
  (void)s.apply_record(stroke(1, {-0.4, 0.3, 0.0}, {0.05, 0.0, -0.2}, -0.4));
  journal::JournalRecord move;
  move.type = journal::RecordType::object_move;
  move.sequence = 2;
  move.move.object_after.origin = {0.5, 0, 0};
  (void)s.apply_record(move);
  (void)s.apply_record(stroke(3, {0.4, -0.4, 0.0}, {0.0, 0.1, 0.15}, 0.5));
  journal::JournalRecord undo;
  undo.type = journal::RecordType::undo;
  undo.sequence = 4;
  (void)s.apply_record(undo);
}

// The checkpoint of the sculpted session, whole, into `sink`; returns that session
// (until the next fresh_session()), or null when it was not written.
inline const Session* write_checkpoint(mesh::Mesh& mesh, Sink& sink) {
  Session& source = fresh_session(mesh);
  sculpt(source);
  sink = Sink();
  checkpoint::CheckpointWriter writer(&sink);
  if (!writer.begin(source, kAnchor, kBaseChecksum).ok()) return nullptr;
  const auto done = writer.step(source, 1 << 20);
  return done.ok() && *done ? &source : nullptr;
}

}  // namespace twister::fuzz_support
