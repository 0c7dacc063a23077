// Fuzz target of the station link's handlers (issue 25): StationLink on a listening
// transport with a newcomer channel and spectator slots (tests/fakes/fake_link_listener.hpp)
// driven by a script of displays' actions. Input: ops, one byte each (wire = bits 0-1,
// action = bits 2-4): 0 raw bytes from that display (length in the next byte, % 64,
// then the bytes), 1 it connects (as the newcomer), 2 a main display's hello, 3 a
// spectator's hello, 4 a command, 5 a resend request, 6 the station steps (the hand
// moves; every fourth step grabs or releases: strokes and commits), 7 the display
// stops / starts reading. The link is polled after every op. Properties: never crashes
// or reads out of bounds; never more spectators than slots; every spectator present
// was admitted.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <new>
#include <span>
#include <vector>

#include "fakes/fake_link_listener.hpp"
#include "fakes/memory_wire.hpp"
#include "twister/link/link_codec.hpp"
#include "twister/math/frame.hpp"
#include "twister/session/sculpt_session.hpp"
#include "twister/station/station_link.hpp"

namespace {

using namespace twister;

using Session = session::SculptSessionWithStorage<256, 256, 1024, 8>;
constexpr std::size_t kWires = 4;
constexpr std::size_t kSlots = 2;

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

template <link::LinkBody M>
void say(test::MemoryWire& w, const M& m) {
  std::array<std::byte, 256> frame{};
  const auto n = link::encode_frame(m, frame);
  if (!n.ok()) return;
  for (std::size_t i = 0; i < *n; ++i) (void)w.b_to_a.push(frame[i]);
}

struct World {
  World() {
    for (auto& w : wires) w = std::make_unique<test::MemoryWire>();
    x.resize(256);
    y.resize(256);
    z.resize(256);
    idx.resize(3 * 256);
    out.resize(8 * link::kMaxFrameBytes);
    queues.resize(kSlots * 4 * link::kMaxFrameBytes);
    staging.resize(4 * link::kMaxFrameBytes);
  }
  std::array<std::unique_ptr<test::MemoryWire>, kWires> wires;
  std::vector<float> x, y, z;
  std::vector<std::uint32_t> idx;
  std::vector<std::byte> out, queues, staging;
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > 4096) return 0;
  static World world;
  static mesh::MeshWithStorage<256, 256> mesh;
  static session::SculptSessionConfig config = [] {
    session::SculptSessionConfig c;
    for (auto& i : c.debounce.interval_us) i = 0;
    c.interaction.initial_radius_m = 1.0f;
    return c;
  }();
  make_grid(mesh);
  static Session* session = nullptr;
  alignas(Session) static std::byte session_memory[sizeof(Session)];
  if (session != nullptr) session->~Session();
  session = new (session_memory) Session(config, mesh, nullptr);
  for (auto& w : world.wires) {
    w->a_to_b.clear();
    w->b_to_a.clear();
    w->up = true;
    w->capacity = 4096;  // a display that stops reading fills this quickly
  }
  test::FakeListener listener;
  station::StationLinkOptions options;
  options.newcomers = &listener;
  options.spectators = &listener;
  options.max_spectators = kSlots;
  options.spectator_queues = world.queues;
  options.spectator_staging = world.staging;
  options.spectator_stall_us = 50'000;
  station::StationLink link(
      listener, station::StationLinkStorage{world.x, world.y, world.z, world.idx, world.out},
      station::StationLinkConfig{}, options);
  check(link.start(*session).ok());
  std::array<bool, kWires> reading{true, true, true, true};
  ports::TimestampUs now = 0;
  std::uint32_t steps = 0;
  bool grab = false;
  for (std::size_t i = 0; i < size; ++i) {
    const std::uint8_t op = data[i];
    test::MemoryWire& w = *world.wires[op & 3];
    switch ((op >> 2) & 7) {
      case 0: {
        const std::size_t n = i + 1 < size ? data[++i] % 64 : 0;
        for (std::size_t k = 0; k < n && i + 1 < size; ++k) {
          (void)w.b_to_a.push(static_cast<std::byte>(data[++i]));
        }
        break;
      }
      case 1:
        w.a_to_b.clear();
        w.b_to_a.clear();
        w.up = true;
        listener.connect(w);
        break;
      case 2:
        say(w, link::Hello{link::Role::bridge, 0, 0, 0, {}});
        break;
      case 3:
        say(w, link::Hello{link::Role::bridge, link::kHelloSpectator, 0, 0, {}});
        break;
      case 4:
        say(w, link::Command{link::CommandKind::undo, 0});
        break;
      case 5:
        say(w, link::ResendRequest{});
        break;
      case 6: {
        ++steps;
        const double a = 0.05 * steps;
        (void)session->set_hand(
            0, true,
            math::frame_from_uv({0.01 * steps, 0, 0.02 * std::sin(a)},
                                {std::cos(a), std::sin(a), 0.0}, {-std::sin(a), std::cos(a), 0.0}));
        if (steps % 4 == 0) {
          grab = !grab;
          (void)session->feed_button({0, grab, now});
        }
        now += 10'000;
        (void)session->step(now);
        break;
      }
      default:
        reading[op & 3] = !reading[op & 3];
        break;
    }
    now += 1'000;
    link.poll(*session, now);
    for (std::size_t k = 0; k < kWires; ++k) {
      if (reading[k]) world.wires[k]->a_to_b.clear();
    }
    const station::StationLinkCounters& c = link.counters();
    check(c.spectators_now <= kSlots);
    check(c.spectators.admitted >= c.spectators_now);
  }
  return 0;
}
