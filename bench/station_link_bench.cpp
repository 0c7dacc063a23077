// The station's cost per spectator display (issue 25), in one run: StationLink on a
// listening transport whose displays take every byte at once without copying it (the
// station's own work: encoding, queueing, flushing; not a socket's) with the main
// display and 0, 1, 2 or 4 spectators admitted. The 0-spectator
// case of each benchmark is the baseline (docs/performance.md "Spectator displays").
//   LiveStep/<s>    one tracker update while dragging at 120 Hz: SculptSession::set_hand
//                   + step, then StationLink::poll (hands, status; each spectator its
//                   own LiveStream, queues and flush)
//   Stroke/<s>      one whole stroke (grab, one move, release) and the polls that queue
//                   its commit: the change set is encoded once and copied per spectator
// The mesh is a UV sphere (about 10k vertices) grabbed with radius 1: every vertex moves.
#include <benchmark/benchmark.h>

#include <array>
#include <cmath>
#include <memory>
#include <vector>

#include "counting_storage.hpp"
#include "twister/journal/journal_writer.hpp"
#include "twister/link/link_codec.hpp"
#include "twister/meshio/mesh_buffer.hpp"
#include "twister/meshio/mesh_generator.hpp"
#include "twister/ports/link_newcomers.hpp"
#include "twister/ports/link_spectators.hpp"
#include "twister/session/sculpt_session.hpp"
#include "twister/station/station_link.hpp"

namespace {

using namespace twister;

constexpr std::size_t kRings = 70;  // 70 x 140: 9 662 vertices

// One display's channel: the hello it says once, the bytes it was sent (counted).
struct Channel {
  std::vector<std::byte> hello;
  std::size_t read = 0;
  std::uint64_t received = 0;
};

// Peer, newcomer and spectator slots; every send is taken whole at once.
class DiscardListener final : public ports::LinkPort,
                              public ports::LinkNewcomers,
                              public ports::LinkSpectators {
 public:
  void connect(Channel& c) {
    newcomer_ = &c;
    ++id_;
  }

 private:
  static Result<std::size_t> put(Channel* c, std::span<const std::byte> src) {
    if (c == nullptr) return StatusCode::unavailable;
    c->received += src.size();
    return src.size();
  }
  static Result<std::size_t> get(Channel* c, std::span<std::byte> dest) {
    if (c == nullptr) return StatusCode::unavailable;
    std::size_t n = 0;
    while (n < dest.size() && c->read < c->hello.size()) dest[n++] = c->hello[c->read++];
    return n;
  }
  Result<std::size_t> do_send(std::span<const std::byte> src) override { return put(peer_, src); }
  Result<std::size_t> do_receive(std::span<std::byte> dest) override { return get(peer_, dest); }
  std::uint64_t do_newcomer_id() override { return id_; }
  Result<std::size_t> do_send_newcomer(std::span<const std::byte> src) override {
    return put(newcomer_, src);
  }
  Result<std::size_t> do_receive_newcomer(std::span<std::byte> dest) override {
    return get(newcomer_, dest);
  }
  void do_admit_newcomer() override {
    peer_ = newcomer_;
    newcomer_ = nullptr;
  }
  void do_refuse_newcomer() override { newcomer_ = nullptr; }
  std::size_t do_spectator_capacity() const override { return 8; }
  Status do_admit_spectator(std::size_t slot) override {
    slots_[slot] = newcomer_;
    newcomer_ = nullptr;
    return ok_status();
  }
  Result<std::size_t> do_send_spectator(std::size_t slot, std::span<const std::byte> src) override {
    return put(slots_[slot], src);
  }
  Result<std::size_t> do_receive_spectator(std::size_t slot, std::span<std::byte> dest) override {
    return get(slots_[slot], dest);
  }
  void do_close_spectator(std::size_t slot) override { slots_[slot] = nullptr; }

  Channel* peer_ = nullptr;
  Channel* newcomer_ = nullptr;
  std::array<Channel*, 8> slots_{};
  std::uint64_t id_ = 0;
};

struct Rig {
  explicit Rig(std::size_t spectators)
      : buffer(meshio::sphere_vertices(kRings, 2 * kRings),
               meshio::sphere_triangles(kRings, 2 * kRings)),
        writer(storage),
        displays(spectators + 1) {
    (void)meshio::make_sphere(buffer.mesh(), kRings, 2 * kRings, 0.5f);
    const std::size_t n = buffer.mesh().vertex_capacity();
    for (auto* v : {&lx, &ly, &lz, &w1, &w2, &x, &y, &z}) v->resize(n);
    indices.resize(n);
    idx.resize(3 * buffer.mesh().triangle_capacity());
    changes.resize(session::kDefaultUndoChanges);
    entries.resize(session::kDefaultUndoEntries);
    session::SculptSessionConfig config;
    for (auto& i : config.debounce.interval_us) i = 0;
    config.interaction.initial_radius_m = 1.0f;
    (void)writer.open();
    session = std::make_unique<session::SculptSession>(
        config, buffer.mesh(),
        session::SculptStorage{lx, ly, lz, math::WarpPlanStorage{indices, w1, w2}, changes,
                               entries},
        &writer);
    out.resize(512 * link::kMaxFrameBytes);
    queues.resize(4 * 64 * link::kMaxFrameBytes);
    staging.resize(64 * link::kMaxFrameBytes);
    station::StationLinkOptions options;
    options.newcomers = &listener;
    options.spectators = &listener;
    options.max_spectators = 4;
    options.spectator_queues = queues;
    options.spectator_staging = staging;
    link = std::make_unique<station::StationLink>(listener,
                                                  station::StationLinkStorage{x, y, z, idx, out},
                                                  station::StationLinkConfig{}, options);
    (void)link->start(*session);
    for (std::size_t d = 0; d < displays.size(); ++d) {
      const std::uint8_t flags = d == 0 ? 0 : link::kHelloSpectator;
      std::vector<std::byte> frame(link::kMaxFrameBytes);
      const auto k = link::encode_frame(link::Hello{link::Role::bridge, flags, 0, 0, {}}, frame);
      frame.resize(*k);
      displays[d].hello = frame;
      listener.connect(displays[d]);
      for (int i = 0; i < 200; ++i) poll();
    }
  }
  math::Frame pose(double t) const {
    const double a = 0.3 * std::sin(t);
    return math::frame_from_uv({0.0, 0.0, 0.5 + 0.1 * std::sin(t)}, {std::cos(a), std::sin(a), 0.0},
                               {-std::sin(a), std::cos(a), 0.0});
  }
  // The station's loop: the session's step, then the link's poll.
  void poll() { link->poll(*session, now); }
  void step(double t) {
    now += 8'333;
    (void)session->set_hand(1, true, pose(t));
    (void)session->step(now);
    poll();
  }
  void button(bool down) {
    now += 8'333;
    (void)session->feed_button({3, down, now});
    (void)session->step(now);
    poll();
  }

  meshio::MeshBuffer buffer;
  bench::CountingStorage storage;
  journal::JournalWriter writer;
  std::vector<float> lx, ly, lz, w1, w2, x, y, z;
  std::vector<std::uint32_t> indices, idx;
  std::vector<session::VertexChange> changes;
  std::vector<session::UndoEntry> entries;
  std::unique_ptr<session::SculptSession> session;
  DiscardListener listener;
  std::vector<Channel> displays;
  std::vector<std::byte> out, queues, staging;
  std::unique_ptr<station::StationLink> link;
  ports::TimestampUs now = 0;
};

void BM_LiveStep(benchmark::State& state) {
  const auto spectators = static_cast<std::size_t>(state.range(0));
  Rig r(spectators);
  if (r.link->counters().spectators_now != spectators || !r.link->admitted()) {
    state.SkipWithError("displays not admitted");
    return;
  }
  (void)r.session->set_hand(1, true, r.pose(0.0));
  r.button(true);
  double t = 0.0;
  for (auto _ : state) r.step(t += 0.01);
  r.button(false);
  state.counters["spectators"] = static_cast<double>(spectators);
  state.counters["live_dropped"] = static_cast<double>(r.link->counters().live_dropped +
                                                       r.link->counters().spectators.live_dropped);
}
BENCHMARK(BM_LiveStep)->Arg(0)->Arg(1)->Arg(2)->Arg(4);

void BM_Stroke(benchmark::State& state) {
  const auto spectators = static_cast<std::size_t>(state.range(0));
  Rig r(spectators);
  if (r.link->counters().spectators_now != spectators || !r.link->admitted()) {
    state.SkipWithError("displays not admitted");
    return;
  }
  double t = 0.0;
  for (auto _ : state) {
    (void)r.session->set_hand(1, true, r.pose(t));
    r.button(true);
    r.step(t += 0.05);
    r.button(false);
    r.poll();
  }
  const station::StationLinkCounters& c = r.link->counters();
  state.counters["spectators"] = static_cast<double>(spectators);
  state.counters["full_sends"] = static_cast<double>(c.full_sends + c.spectators.full_sends);
  state.counters["commits_resent"] = static_cast<double>(c.spectators.commits_resent);
}
BENCHMARK(BM_Stroke)->Arg(0)->Arg(1)->Arg(2)->Arg(4);

}  // namespace

BENCHMARK_MAIN();
