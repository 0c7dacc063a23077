// The station does not warp on the CPU between commits (issue 24): while a stroke is
// live, a step moves the warp plan (its screws, which the display's shader and the
// bridge's own scodef path evaluate) and writes no warped position; the live columns
// are computed only when something asks (SculptSession::live_positions()), and a
// commit warps the plan's vertices once at its end poses. What the model becomes is
// bit-for-bit what a warp at every step made of it: the property below drives a lazy
// session and a reference that asks for the live positions after every step (the
// station before issue 24) with the same random strokes, clutch included.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <memory>
#include <random>
#include <vector>

#include "allocation_counter.hpp"
#include "session_harness.hpp"
#include "twister/session/sculpt_session.hpp"

namespace twister::session {
namespace {

using namespace test_support;

using Arrays = SculptStorageArrays<kVertices, kVertices, 8192, 32>;

// A session over storage the test can see: its live columns start as NaN, so a
// column entry the session wrote is told from one it never touched.
struct VisibleSession {
  explicit VisibleSession(math::WarpMethod method) {
    make_grid(mesh, 33);
    for (auto* column : {&arrays->live_x, &arrays->live_y, &arrays->live_z}) {
      column->fill(std::nanf(""));
    }
    SculptSessionConfig config = test_config();
    config.method = method;
    session = std::make_unique<SculptSession>(config, mesh, arrays->spans(), nullptr);
  }

  // Live column entries the session has written (not NaN any more).
  std::size_t written() const {
    std::size_t n = 0;
    for (std::size_t i = 0; i < mesh.vertex_count(); ++i) {
      n += std::isnan(arrays->live_x[i]) && std::isnan(arrays->live_y[i]) &&
                   std::isnan(arrays->live_z[i])
               ? 0
               : 1;
    }
    return n;
  }

  SessionEvents tick() {
    now_us += 8'000;
    return session->step(now_us);
  }

  TestMesh mesh;
  std::unique_ptr<Arrays> arrays = std::make_unique<Arrays>();
  std::unique_ptr<SculptSession> session;
  ports::TimestampUs now_us = 0;
};

// The plan's warp of the rest mesh into fresh columns (what a warp at every step
// wrote into the live columns).
struct Warped {
  std::vector<float> x, y, z;
};
Warped warp_now(const SculptSession& s) {
  const mesh::Mesh& m = s.mesh();
  Warped w{std::vector<float>(m.x().begin(), m.x().end()),
           std::vector<float>(m.y().begin(), m.y().end()),
           std::vector<float>(m.z().begin(), m.z().end())};
  EXPECT_TRUE(s.live().plan->apply({m.x(), m.y(), m.z()}, {w.x, w.y, w.z}).ok());
  return w;
}

class LiveWarpOnDemand : public ::testing::TestWithParam<math::WarpMethod> {};

// Two hands twist and pull for 60 tracker records: no live column is written, for
// every method (scodef too: the display runs its own CPU warp from the stroke and hands
// messages), and no step allocates.
TEST_P(LiveWarpOnDemand, NoCpuWarpWhileAStrokeIsLive) {
  VisibleSession s(GetParam());
  ASSERT_TRUE(s.session->set_hand(0, true, z_turn({-0.3, 0, 0}, 0)).ok());
  ASSERT_TRUE(s.session->set_hand(1, true, z_turn({0.3, 0, 0}, 0)).ok());
  ASSERT_TRUE(s.session->feed_button({kGrab0, true, s.now_us}).ok());
  ASSERT_TRUE(s.session->feed_button({kGrab1, true, s.now_us}).ok());
  ASSERT_TRUE(has_event(s.tick(), SessionEventKind::grab_begin));
  ASSERT_TRUE(s.session->live().active);
  ASSERT_EQ(s.session->live().hand_mask, 3);
  EXPECT_NO_ALLOCATIONS({
    for (int k = 1; k <= 60; ++k) {
      (void)s.session->set_hand(0, true, z_turn({-0.3, 0, 0.004 * k}, 0.01 * k));
      (void)s.session->set_hand(1, true, z_turn({0.3, 0, 0.002 * k}, -0.01 * k));
      (void)s.tick();
    }
  });
  EXPECT_EQ(s.written(), 0u) << "the station warped on the CPU between commits";
  // The plan followed the hands all the same (the display's hands message reads it).
  const LiveWarp live = s.session->live();
  EXPECT_LT(glm::distance(live.plan->end_frame(0).origin, glm::dvec3(-0.3, 0, 0.24)), 1e-9);
  EXPECT_GT(live.plan->screw(0).angle, 0.5);
  EXPECT_GT(live.plan->indices().size(), 500u);
}

// Asked for, the live positions are the plan's warp of this step, bit for bit, on the
// plan's vertices only; asked again before the plan moves, they are not warped again;
// the commit puts exactly them into the mesh.
TEST_P(LiveWarpOnDemand, LivePositionsOnDemandAreTheStepsWarpAndWhatTheCommitMakes) {
  VisibleSession s(GetParam());
  ASSERT_TRUE(s.session->set_hand(0, true, z_turn({-0.3, 0, 0}, 0)).ok());
  ASSERT_TRUE(s.session->set_hand(1, true, z_turn({0.3, 0, 0}, 0)).ok());
  ASSERT_TRUE(s.session->feed_button({kGrab0, true, s.now_us}).ok());
  ASSERT_TRUE(s.session->feed_button({kGrab1, true, s.now_us}).ok());
  (void)s.tick();
  for (int k = 1; k <= 20; ++k) {
    (void)s.session->set_hand(0, true, z_turn({-0.3, 0, 0.01 * k}, 0.02 * k));
    (void)s.session->set_hand(1, true, z_turn({0.3, 0, 0.005 * k}, -0.03 * k));
    (void)s.tick();
  }
  const Warped expected = warp_now(*s.session);
  math::ConstVertexColumns live;
  EXPECT_NO_ALLOCATIONS(live = s.session->live_positions());
  const auto indices = s.session->live().plan->indices();
  ASSERT_EQ(live.size(), s.mesh.vertex_count());
  EXPECT_EQ(s.written(), indices.size());  // the plan's vertices, no other
  for (const std::uint32_t i : indices) {
    ASSERT_EQ(live.x[i], expected.x[i]);
    ASSERT_EQ(live.y[i], expected.y[i]);
    ASSERT_EQ(live.z[i], expected.z[i]);
  }
  // Cached: a second ask before the plan moves warps nothing (a planted value stays).
  const std::uint32_t probe = indices[indices.size() / 2];
  s.arrays->live_x[probe] = 123.0f;
  EXPECT_EQ(s.session->live_positions().x[probe], 123.0f);
  // The next step moves the plan: asked again, the warp is computed again.
  (void)s.session->set_hand(0, true, z_turn({-0.3, 0, 0.21}, 0.42));
  (void)s.tick();
  const Warped moved = warp_now(*s.session);
  EXPECT_EQ(s.session->live_positions().x[probe], moved.x[probe]);
  // Released at the same poses: the model is what the display was last shown.
  ASSERT_TRUE(s.session->feed_button({kGrab0, false, s.now_us}).ok());
  ASSERT_TRUE(s.session->feed_button({kGrab1, false, s.now_us}).ok());
  ASSERT_TRUE(has_event(s.tick(), SessionEventKind::committed));
  for (std::size_t i = 0; i < s.mesh.vertex_count(); ++i) {
    ASSERT_EQ(s.mesh.x()[i], moved.x[i]) << i;
    ASSERT_EQ(s.mesh.y()[i], moved.y[i]) << i;
    ASSERT_EQ(s.mesh.z()[i], moved.z[i]) << i;
  }
}

INSTANTIATE_TEST_SUITE_P(Methods, LiveWarpOnDemand,
                         ::testing::Values(math::WarpMethod::twister, math::WarpMethod::rottran,
                                           math::WarpMethod::scodef),
                         [](const auto& method) {
                           return std::string(math::warp_method_name(method.param));
                         });

// One random step's inputs, applied alike to both sessions of the property.
struct StepInputs {
  std::array<int, 2> toggles{-1, -1};  // button lines toggled (-1: none)
  std::array<bool, 2> tracked{};
  std::array<math::Frame, 2> poses{};
  bool command = false;
  SessionCommand submitted{};
  ports::TimestampUs dt_us = 8'000;
  bool undo_redo = false;  // when idle: undo, and half the time redo
  bool redo_too = false;
};

struct RandomStrokes {
  explicit RandomStrokes(std::uint32_t seed) : rng(seed) {}
  int pick(int n) { return std::uniform_int_distribution<int>(0, n - 1)(rng); }
  double real(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); }

  StepInputs next() {
    StepInputs in;
    // The grab lines and hand 1's freeze (the clutch) most often, so strokes happen,
    // hands join and leave and chains of freeze steps form.
    for (int& t : in.toggles) {
      if (pick(3) != 0) continue;
      static constexpr std::array<int, 8> kLines{kGrab0,   kGrab1,   kFreeze1, kFreeze1,
                                                 kRadius0, kRadius1, kMove0,   kGrab0};
      t = kLines[static_cast<std::size_t>(pick(8))];
    }
    for (std::size_t h = 0; h < 2; ++h) {
      if (pick(40) == 0) tracked[h] = !tracked[h];
      in.tracked[h] = tracked[h];
      position[h] += glm::dvec3(real(-0.05, 0.05), real(-0.05, 0.05), real(-0.05, 0.05));
      position[h] = glm::clamp(position[h], glm::dvec3(-1.2), glm::dvec3(1.2));
      angle[h] += real(-0.3, 0.5);
      in.poses[h] = z_turn(position[h], angle[h]);
    }
    if (pick(25) == 0) {
      in.command = true;
      in.submitted = {SessionCommandKind::set_method, static_cast<std::uint8_t>(pick(2)),
                      static_cast<math::WarpMethod>(pick(3))};
    }
    in.dt_us = pick(50) == 0 ? 200'000 : 8'000;
    in.undo_redo = pick(12) == 0;
    in.redo_too = pick(2) == 0;
    return in;
  }

  std::mt19937 rng;
  std::array<bool, 2> tracked{true, true};
  std::array<glm::dvec3, 2> position{glm::dvec3(-0.4, 0, 0), glm::dvec3(0.4, 0, 0)};
  std::array<double, 2> angle{};
};

struct Driven {
  explicit Driven(const SculptSessionConfig& config) : station(17, config) {}

  SessionEvents apply(const StepInputs& in) {
    for (const int line : in.toggles) {
      if (line < 0) continue;
      const auto l = static_cast<std::size_t>(line);
      levels[l] = !levels[l];
      station.button(static_cast<std::uint8_t>(line), levels[l]);
    }
    for (std::uint8_t h = 0; h < 2; ++h) {
      if (in.tracked[h]) {
        station.hand(h, in.poses[h]);
      } else {
        station.lose(h);
      }
    }
    if (in.command) (void)station.session->submit(in.submitted);
    SessionEvents events = station.tick(in.dt_us);
    if (in.undo_redo && !station.session->busy() && station.session->undo().ok() && in.redo_too) {
      EXPECT_TRUE(station.session->redo().ok());
    }
    return events;
  }

  Station station;
  std::array<bool, 8> levels{};
};

bool same_mesh(const mesh::Mesh& a, const mesh::Mesh& b) {
  if (a.vertex_count() != b.vertex_count() || a.triangle_count() != b.triangle_count()) {
    return false;
  }
  const std::size_t n = a.vertex_count() * sizeof(float);
  return std::memcmp(a.x().data(), b.x().data(), n) == 0 &&
         std::memcmp(a.y().data(), b.y().data(), n) == 0 &&
         std::memcmp(a.z().data(), b.z().data(), n) == 0 &&
         std::memcmp(a.triangle_indices().data(), b.triangle_indices().data(),
                     a.triangle_indices().size_bytes()) == 0;
}

// Random strokes with one and two hands, hands joining and leaving, the clutch
// (freeze chains), tracking lost and timed out, method changes, undo and redo, and
// (half the runs) refinement at commit: the lazy session's model, events and journal
// are bit-for-bit the reference's, which warps the live stroke at every step.
RC_GTEST_PROP(LiveWarpOnDemandProperty, CommitsAreBitIdenticalToAWarpAtEveryStep, ()) {
  const auto seed = *rc::gen::arbitrary<std::uint32_t>();
  const int steps = *rc::gen::inRange(50, 500);
  SculptSessionConfig config = test_config();
  config.refine.enabled = *rc::gen::arbitrary<bool>();
  config.refine.threshold_m = 0.002;
  Driven lazy(config);
  Driven reference(config);
  RandomStrokes strokes(seed);
  int live_steps = 0;
  int chain_steps = 0;
  for (int i = 0; i < steps; ++i) {
    const StepInputs in = strokes.next();
    const SessionEvents a = lazy.apply(in);
    const SessionEvents b = reference.apply(in);
    if (reference.station.session->live().active) {
      (void)reference.station.session->live_positions();  // a consumer of every step
      ++live_steps;
    }
    RC_ASSERT(a.items().size() == b.items().size());
    for (std::size_t k = 0; k < a.items().size(); ++k) {
      RC_ASSERT(a.items()[k].kind == b.items()[k].kind);
      RC_ASSERT(a.items()[k].hand == b.items()[k].hand);
      RC_ASSERT(a.items()[k].status.code() == b.items()[k].status.code());
      chain_steps += a.items()[k].kind == SessionEventKind::disengaged ? 1 : 0;
    }
    RC_ASSERT(same_mesh(lazy.station.mesh, reference.station.mesh));
  }
  RC_CLASSIFY(live_steps > 0, "strokes live");
  RC_CLASSIFY(chain_steps > 0, "clutch chain");
  RC_CLASSIFY(lazy.station.session->next_sequence() > 3, "more than 3 records");
  const auto journal = lazy.station.storage.bytes();
  const auto expected = reference.station.storage.bytes();
  RC_ASSERT(journal.size() == expected.size());
  RC_ASSERT(std::memcmp(journal.data(), expected.data(), journal.size()) == 0);
}

}  // namespace
}  // namespace twister::session
