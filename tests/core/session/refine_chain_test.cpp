// Clutch chains refined at their end (issue 24, "clutch-chained strokes refined like
// any other"): a random chain of freeze steps on a sphere, refined by the commit that
// ends it under the chain's combined warp C (each step's screws applied in turn, every
// step weighted by the step-0 weight of the chain-start point), against
//  - a reference C written here from the journal's records: C at the old vertices'
//    chain-start positions is where the freeze steps' float kernels took them, the
//    mesh the session made is the reference refiner's on the chain-start mesh (same
//    topology, new vertices at C of their rest midpoint, bit for bit), and every edge
//    it looked at is within the threshold unless a capacity stopped it;
//  - the same inputs with refinement off: every old vertex has the same bits;
//  - undo (the unrefined state before the chain's end, exactly) and redo;
//  - the journal replayed into a fresh session (the same bits).
// Plus: a chain longer than kMaxChainSteps ends unrefined and is counted; the chain's
// end allocates nothing.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <array>
#include <cmath>
#include <memory>
#include <numbers>
#include <vector>

#include "allocation_counter.hpp"
#include "mesh_checks.hpp"
#include "refine_harness.hpp"
#include "refine_random.hpp"
#include "twister/math/decay.hpp"
#include "twister/math/screw.hpp"
#include "twister/mesh/mesh_refiner.hpp"
#include "twister/meshio/refiner_buffer.hpp"
#include "twister/session/clutch_chain.hpp"

namespace twister::session {
namespace {

using namespace test_support;
using twister::test_support::closed_manifold;

// A UV sphere of radius 0.5 m with room for `spare` more vertices.
struct SphereStation {
  SphereStation(std::size_t rings, std::size_t spare, SculptSessionConfig config,
                bool with_journal = true)
      : buffer(meshio::sphere_vertices(rings, 2 * rings) + spare,
               meshio::sphere_triangles(rings, 2 * rings) + 2 * spare),
        writer(storage) {
    EXPECT_TRUE(meshio::make_sphere(buffer.mesh(), rings, 2 * rings, 0.5f).ok());
    if (with_journal) {
      EXPECT_TRUE(writer.open().ok());
    }
    session =
        std::make_unique<RefineSession>(config, buffer.mesh(), with_journal ? &writer : nullptr);
  }
  mesh::Mesh& mesh() { return buffer.mesh(); }
  void button(std::uint8_t line, bool pressed) {
    EXPECT_TRUE(session->feed_button({line, pressed, now_us}).ok());
  }
  void hand(std::uint8_t h, const math::Frame& f) {
    EXPECT_TRUE(session->set_hand(h, true, f).ok());
  }
  void tick() {
    now_us += 10'000;
    (void)session->step(now_us);
  }

  meshio::MeshBuffer buffer;
  RefineStorage storage;
  journal::JournalWriter writer;
  std::unique_ptr<RefineSession> session;
  ports::TimestampUs now_us = 0;
};

// One clutched stroke of hand 1 (hand 0 holding, drifting, when two_hands): `cycles`
// times turn and drag, press freeze, turn back on the clutch, release freeze; then a
// last turn and release.
struct ChainScript {
  math::WarpMethod method = math::WarpMethod::twister;
  bool two_hands = false;
  int cycles = 1;
  float radius_m = 0.6f;
  glm::dvec3 grab0{0, 0, -0.5};
  glm::dvec3 grab1{0, 0, 0.5};
  glm::dvec3 axis{0, 0, 1};
  std::vector<double> turns;       // per segment (cycles + 1), radians
  std::vector<glm::dvec3> drags;   // per segment
  double back = 1.0;               // turned back on the clutch, radians
};

SculptSessionConfig chain_config(const ChainScript& c, double threshold, bool on) {
  SculptSessionConfig config = refine_config(threshold, on);
  config.method = c.method;
  config.interaction.initial_radius_m = c.radius_m;
  return config;
}

void play(SphereStation& s, const ChainScript& c) {
  glm::dvec3 at = c.grab1;
  double phase = 0.0;
  glm::dvec3 hold = c.grab0;
  s.hand(1, turned(at, c.axis, phase));
  s.button(kGrab1, true);
  if (c.two_hands) {
    s.hand(0, math::identity_frame(hold));
    s.button(kGrab0, true);
  }
  s.tick();
  const auto drift = [&] {
    if (!c.two_hands) return;
    hold += glm::dvec3(0.004, -0.003, 0.002);
    s.hand(0, math::identity_frame(hold));
  };
  for (int seg = 0; seg <= c.cycles; ++seg) {
    for (int k = 1; k <= 2; ++k) {
      s.hand(1, turned(at + 0.5 * k * c.drags[seg], c.axis, phase + 0.5 * k * c.turns[seg]));
      drift();
      s.tick();
    }
    at += c.drags[seg];
    phase += c.turns[seg];
    if (seg == c.cycles) break;
    s.button(kFreeze1, true);
    s.tick();
    phase -= c.back;  // on the clutch: moves nothing
    s.hand(1, turned(at, c.axis, phase));
    drift();
    s.tick();
    s.button(kFreeze1, false);
    s.tick();
  }
  s.button(kGrab1, false);
  if (c.two_hands) s.button(kGrab0, false);
  s.tick();
}

std::vector<journal::JournalRecord> records_of(RefineStorage& storage) {
  journal::JournalReader reader(storage);
  EXPECT_TRUE(reader.open().ok());
  std::vector<journal::JournalRecord> out;
  for (auto r = reader.next(); r.ok(); r = reader.next()) out.push_back(*r);
  return out;
}

// C from the chain's stroke records, written independently of ClutchChain: each
// record's screws from its poses (long turns the long way round), applied in turn to
// the moving point, each hand at the step-0 weight of the chain-start point.
class ReferenceChain final : public mesh::PointWarp {
 public:
  explicit ReferenceChain(const std::vector<journal::JournalRecord>& records) {
    const journal::StrokeRecord& first = records.front().stroke;
    radius_ = first.radius_m;
    method_ = static_cast<math::WarpMethod>(first.method);
    for (std::uint8_t h = 0; h < 2; ++h) {
      if ((first.hand_mask & (1u << h)) != 0) grabs_.push_back(math::Frame(first.start[h]).origin);
    }
    for (const journal::JournalRecord& r : records) {
      Step step;
      for (std::uint8_t h = 0; h < 2; ++h) {
        if ((r.stroke.hand_mask & (1u << h)) == 0) continue;
        const math::Frame start = r.stroke.start[h];
        const math::Frame end = r.stroke.end[h];
        math::Screw screw = math::compute_screw(start, end);
        if ((r.stroke.long_turns & (1u << h)) != 0) screw = math::long_way_round(screw);
        step.screws.push_back(screw);
        step.start.push_back(start);
        step.end.push_back(end);
      }
      steps_.push_back(step);
    }
  }
  double weight(std::size_t h, glm::dvec3 p) const {
    const glm::dvec3* other = grabs_.size() == 2 ? &grabs_[1 - h] : nullptr;
    return math::hand_weight(grabs_[h], other, radius_, p);
  }
  bool influenced(glm::dvec3 p) const {
    for (std::size_t h = 0; h < grabs_.size(); ++h) {
      if (weight(h, p) > 0.0) return true;
    }
    return false;
  }

 private:
  struct Step {
    std::vector<math::Screw> screws;
    std::vector<math::Frame> start, end;
  };
  glm::dvec3 do_warp(glm::dvec3 p) const override {
    std::array<double, 2> w{};
    for (std::size_t h = 0; h < grabs_.size(); ++h) w[h] = weight(h, p);
    glm::dvec3 q = p;
    for (const Step& s : steps_) {
      glm::dvec3 moved = q;
      for (std::size_t h = 0; h < grabs_.size(); ++h) {
        if (w[h] <= 0.0) continue;
        const glm::dvec3 r = method_ == math::WarpMethod::rottran
                                 ? math::rottran_at(s.screws[h], s.start[h], s.end[h], w[h], q)
                                 : math::screw_at(s.screws[h], w[h], q);
        moved += r - q;
      }
      q = moved;
    }
    return q;
  }
  double radius_ = 1.0;
  math::WarpMethod method_ = math::WarpMethod::twister;
  std::vector<glm::dvec3> grabs_;
  std::vector<Step> steps_;
};

ChainScript any_chain() {
  ChainScript c;
  c.method = *rc::gen::element(math::WarpMethod::twister, math::WarpMethod::rottran);
  c.two_hands = *rc::gen::inRange(0, 3) == 0;
  c.cycles = *rc::gen::inRange(1, 5);  // one hand: chains of 2 to 5 steps
  c.radius_m = static_cast<float>(*rc::gen::inRange(30, 101) / 100.0);
  c.grab1 = glm::dvec3(0, 0, 0.5) + 0.2 * any_point();
  c.grab0 = glm::dvec3(0, 0, -0.5) + 0.2 * any_point();
  c.axis = any_axis();
  for (int seg = 0; seg <= c.cycles; ++seg) {
    // Up to 200 degrees a segment: past a half turn the screw goes the long way round.
    c.turns.push_back(*rc::gen::inRange(-200, 201) * std::numbers::pi / 180.0);
    c.drags.push_back(0.15 * any_point());
  }
  c.back = *rc::gen::inRange(-120, 121) * std::numbers::pi / 180.0;
  return c;
}

RC_GTEST_PROP(RefineChain, AChainIsRefinedAtItsEndUnderItsCombinedWarp, ()) {
  const ChainScript script = any_chain();
  const auto rings = static_cast<std::size_t>(*rc::gen::inRange(6, 11));
  const double threshold = *rc::gen::element(0.002, 0.005, 0.01);
  const auto spare = static_cast<std::size_t>(*rc::gen::element(300, 8'000));
  SphereStation refined(rings, spare, chain_config(script, threshold, true));
  SphereStation plain(rings, spare, chain_config(script, threshold, false));
  meshio::MeshBuffer rest(refined.mesh().vertex_capacity(), refined.mesh().triangle_capacity());
  RC_ASSERT(rest.mesh().copy_from(refined.mesh()).ok());  // the chain's start
  const auto old_vertices = static_cast<std::uint32_t>(rest.mesh().vertex_count());
  play(refined, script);
  play(plain, script);

  // One chain, every step journaled; only its last record is refined.
  const std::vector<journal::JournalRecord> records = records_of(refined.storage);
  RC_ASSERT(records.size() >= 2u);
  for (std::size_t i = 0; i < records.size(); ++i) {
    RC_ASSERT(records[i].type == journal::RecordType::stroke);
    RC_ASSERT(records[i].stroke.chain_step == i);
    RC_ASSERT(records[i].stroke.refine_threshold_m == (i + 1 == records.size() ? threshold : 0.0));
  }
  RC_TAG(records.size() <= 5 ? "2-5 steps" : "6+ steps (two hands)");
  bool long_turn = false;
  for (const journal::JournalRecord& r : records) long_turn = long_turn || r.stroke.long_turns != 0;
  RC_TAG(long_turn ? "a long turn" : "minimal turns");
  for (const journal::JournalRecord& r : records_of(plain.storage)) {
    RC_ASSERT(r.stroke.refine_threshold_m == 0.0);
  }

  // (3) Refinement off: today's unrefined chain; the refined chain's old vertices have
  // exactly its bits.
  RC_ASSERT(plain.mesh().vertex_count() == old_vertices);
  for (std::uint32_t v = 0; v < old_vertices; ++v) {
    RC_ASSERT(refined.mesh().position(v) == plain.mesh().position(v));
  }

  // C is what the freeze steps did: at every influenced vertex's chain-start point it
  // gives where the float kernels took it (within float rounding).
  const ReferenceChain c(records);
  std::vector<std::uint32_t> influenced;
  double moved = 0.0;
  for (std::uint32_t v = 0; v < old_vertices; ++v) {
    const glm::dvec3 p(rest.mesh().position(v));
    if (!c.influenced(p)) {
      RC_ASSERT(plain.mesh().position(v) == rest.mesh().position(v));
      continue;
    }
    influenced.push_back(v);
    const glm::dvec3 kernel(plain.mesh().position(v));
    RC_ASSERT(glm::length(c.warp(p) - kernel) < 2e-5);
    moved = std::max(moved, glm::length(kernel - p));
  }
  RC_TAG(moved > 0.01 ? "moved" : "barely moved");

  // (1) The reference refiner on the chain-start mesh under the reference C: the same
  // mesh as the session's, and every edge it looked at within the threshold.
  meshio::RefinerBuffer buffer(rest.mesh().vertex_capacity(), rest.mesh().triangle_capacity());
  mesh::MeshRefiner refiner(buffer.storage());
  const auto result = refiner.refine_around(rest.mesh(), c, threshold, influenced);
  RC_ASSERT(result.ok());
  RC_ASSERT(rest.mesh().vertex_count() == refined.mesh().vertex_count());
  RC_ASSERT(rest.mesh().triangle_count() == refined.mesh().triangle_count());
  const auto ours = refined.mesh().triangle_indices();
  const auto theirs = rest.mesh().triangle_indices();
  RC_ASSERT(std::equal(ours.begin(), ours.end(), theirs.begin(), theirs.end()));
  for (std::uint32_t v = old_vertices; v < rest.mesh().vertex_count(); ++v) {
    RC_ASSERT(refined.mesh().position(v) == glm::vec3(c.warp(glm::dvec3(rest.mesh().position(v)))));
  }
  RC_ASSERT(closed_manifold(refined.mesh()));
  const bool complete = result->stop == mesh::RefineStop::done && result->blocked == 0;
  RC_TAG(complete ? "within threshold" : "stopped or blocked");
  RC_TAG(result->edges_split > 0 ? "split" : "nothing to split");
  if (complete) {
    // Every triangle with an influenced or a new vertex was looked at.
    std::vector<bool> looked(rest.mesh().vertex_count(), false);
    for (const std::uint32_t v : influenced) looked[v] = true;
    for (std::uint32_t v = old_vertices; v < looked.size(); ++v) looked[v] = true;
    const auto t = rest.mesh().triangle_indices();
    for (std::size_t i = 0; i < t.size(); i += 3) {
      if (!looked[t[i]] && !looked[t[i + 1]] && !looked[t[i + 2]]) continue;
      for (std::size_t j = 0; j < 3; ++j) {
        const glm::dvec3 a(rest.mesh().position(t[i + j]));
        const glm::dvec3 b(rest.mesh().position(t[i + (j + 1) % 3]));
        RC_ASSERT(mesh::MeshRefiner::midpoint_error(a, b, c) <= threshold);
      }
    }
  }

  // (4) Undo: exactly the unrefined state before the chain's end; redo: the refined.
  const std::uint64_t refined_sum = refined.mesh().checksum();
  RC_ASSERT(refined.session->undo().ok());
  RC_ASSERT(plain.session->undo().ok());
  RC_ASSERT(refined.mesh().checksum() == plain.mesh().checksum());
  RC_ASSERT(refined.session->redo().ok());
  RC_ASSERT(refined.mesh().checksum() == refined_sum);

  // (2) The journal replayed into a fresh session (its own settings off): the same bits.
  SphereStation replayed(rings, spare, chain_config(script, 0.05, false), false);
  journal::JournalReader reader(refined.storage);
  RC_ASSERT(reader.open().ok());
  const auto n = replayed.session->replay(reader);
  RC_ASSERT(n.ok());
  RC_ASSERT(*n == refined.session->next_sequence());
  RC_ASSERT(replayed.mesh().checksum() == refined_sum);
}

ChainScript long_chain(int cycles) {
  ChainScript c;
  c.cycles = cycles;
  c.radius_m = 0.8f;
  for (int seg = 0; seg <= cycles; ++seg) {
    c.turns.push_back(0.6);
    c.drags.push_back({0.0, 0.0, 0.0});
  }
  c.back = 0.6;
  return c;
}

// kMaxChainSteps steps are refined at the end; one more and the chain ends unrefined,
// counted in the refinement's status.
TEST(RefineChain, AChainLongerThanItsCapacityEndsUnrefinedAndSaysSo) {
  for (const int cycles : {static_cast<int>(kMaxChainSteps) - 1, static_cast<int>(kMaxChainSteps)}) {
    const ChainScript script = long_chain(cycles);
    SphereStation s(8, 8'000, chain_config(script, 0.002, true));
    const std::size_t before = s.mesh().vertex_count();
    play(s, script);
    const auto records = records_of(s.storage);
    ASSERT_EQ(records.size(), static_cast<std::size_t>(cycles) + 1);
    const RefineStatus status = s.session->state().refine;
    if (records.size() <= kMaxChainSteps) {
      EXPECT_EQ(records.back().stroke.refine_threshold_m, 0.002);
      EXPECT_GT(s.mesh().vertex_count(), before);
      EXPECT_EQ(status.refined_chains, 1u);
      EXPECT_EQ(status.chains_too_long, 0u);
    } else {
      EXPECT_EQ(records.back().stroke.refine_threshold_m, 0.0);
      EXPECT_EQ(s.mesh().vertex_count(), before);
      EXPECT_EQ(status.refined_chains, 0u);
      EXPECT_EQ(status.chains_too_long, 1u);
    }
  }
}

TEST(RefineChain, TheChainsEndAllocatesNothing) {
  ChainScript script = long_chain(2);
  SphereStation s(8, 8'000, chain_config(script, 0.002, true));
  EXPECT_NO_ALLOCATIONS({ play(s, script); });
  EXPECT_EQ(s.session->state().refine.refined_chains, 1u);
  EXPECT_GT(s.session->state().refine.last_vertices_added, 0u);
}

// A replaying session refuses a refined chain end whose chain it did not see begin.
TEST(RefineChain, ARefinedChainEndWithoutItsChainIsRefused) {
  const ChainScript script = long_chain(1);
  SphereStation live(8, 8'000, chain_config(script, 0.002, true));
  play(live, script);
  const auto records = records_of(live.storage);
  ASSERT_EQ(records.size(), 2u);
  SphereStation other(8, 8'000, chain_config(script, 0.002, true), false);
  const std::uint64_t before = other.mesh().checksum();
  EXPECT_EQ(other.session->apply_record(records[1]).code(), StatusCode::data_loss);
  EXPECT_EQ(other.mesh().checksum(), before);
}

}  // namespace
}  // namespace twister::session
