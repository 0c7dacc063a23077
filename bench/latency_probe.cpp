// Latency by stage, tracker record to presented frame (issue 16), in one process with
// the real code of each stage and real kernel transports between them:
//   record   the simulator encodes a Fastrak record (IEEE binary, position +
//            quaternion + stylus) and writes it into a PTY master;
//   read     the station's side polls the raw PTY slave until the whole record is in
//            (write -> last byte read);
//   station  parse + pose conversion + SculptSession::set_hand/step (the plan follows
//            the hand; no vertex is warped on the CPU between commits since issue 24)
//            + the hands message encoded and written to the display socket (last
//            record byte in -> message out);
//   link     the bridge's side reads the Unix socket and decodes byte-wise into the
//            scene replica (message out -> received and applied);
//   frame    MeshRenderer::set_live + draw, which ends with glFinish (offscreen
//            llvmpipe, 800x600 unless --size): received -> frame finished;
//   total    record write -> frame finished.
// Worst case for the station: the grab radius covers the whole model (it was the
// per-record CPU warp's; the stage no longer grows with the model). The hands
// message is built with bridge::make_live_messages (the content StationLink sends).
// Usage: latency_probe [--size WxH] [VERTICES...] (default 800x600; 30000 100000
// 1000000 vertices); prints median
// and p99 of each stage in microseconds.
#include <fcntl.h>
#include <poll.h>
#include <pty.h>
#include <sys/socket.h>
#include <termios.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "gl_context.hpp"
#include "latency_rig.hpp"
#include "mesh_renderer.hpp"
#include "scene_replica.hpp"
#include "twister/link/link_codec.hpp"
#include "twister/tracker/fastrak_encoder.hpp"
#include "twister/tracker/fastrak_parser.hpp"
#include "twister/tracker/pose_conversion.hpp"

namespace {

using namespace twister;
using Clock = std::chrono::steady_clock;

double us_between(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::micro>(b - a).count();
}

struct Stages {
  std::array<std::vector<double>, 5> us;  // read, station, link, frame, total
};

double percentile(std::vector<double> v, double p) {
  std::sort(v.begin(), v.end());
  const auto k = static_cast<std::size_t>(std::lround(p * static_cast<double>(v.size() - 1)));
  return v[k];
}

tracker::FastrakConfig record_config() {
  tracker::FastrakConfig c;
  c.format = tracker::Format::binary;
  using tracker::Item;
  c.stations[1].enabled = true;
  c.stations[1].list =
      tracker::OutputList::of({Item::position, Item::quaternion, Item::stylus, Item::crlf});
  return c;
}

// The record of hand 1 (receiver 2) at step t: a turning, moving grab point.
tracker::FastrakPose hand_record(double t) {
  tracker::FastrakPose p;
  p.station = 2;
  p.has_position = true;
  p.position = {0.0F, 0.0F, static_cast<float>((0.5 + 0.1 * std::sin(t)) / 0.0254)};
  p.has.quaternion = true;
  const double a = 0.15 * std::sin(t);
  p.quaternion = {static_cast<float>(std::cos(a)), 0.0F, 0.0F, static_cast<float>(std::sin(a))};
  p.has_button = true;
  p.button = true;
  return p;
}

bool read_record(int fd, std::vector<std::byte>& buf, std::size_t want) {
  std::size_t got = 0;
  while (got < want) {
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, 1000) <= 0) return false;
    const ssize_t n = ::read(fd, buf.data() + got, buf.size() - got);
    if (n <= 0) return false;
    got += static_cast<std::size_t>(n);
  }
  return true;
}

bool receive(int fd, link::LinkDecoder& decoder, bridge::SceneReplica& replica) {
  std::array<std::byte, 4096> buf{};
  for (;;) {
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, 1000) <= 0) return false;
    const ssize_t n = ::read(fd, buf.data(), buf.size());
    if (n <= 0) return false;
    for (ssize_t i = 0; i < n; ++i) {
      auto m = decoder.process(buf[static_cast<std::size_t>(i)]);
      if (m.ok()) return !replica.apply(**m).has_value();
    }
  }
}

// One model size: `iterations` records through every stage.
bool measure(bench::LatencyRig& rig, bridge::MeshRenderer& renderer, int iterations, Stages& out) {
  int master = -1;
  int slave = -1;
  if (::openpty(&master, &slave, nullptr, nullptr, nullptr) != 0) return false;
  termios tio{};
  ::tcgetattr(slave, &tio);
  ::cfmakeraw(&tio);
  ::tcsetattr(slave, TCSANOW, &tio);
  std::array<int, 2> sock{-1, -1};
  if (::socketpair(AF_UNIX, SOCK_STREAM, 0, sock.data()) != 0) return false;
  const tracker::FastrakConfig config = record_config();
  tracker::FastrakParser parser(config);
  tracker::PoseConversion conv;
  conv.format = config.format;
  link::LinkDecoder decoder;
  std::vector<std::byte> rec(256), in(256), frame(link::kMaxFrameBytes);
  bool ok = true;
  int done = 0;
  for (int i = 0; i < iterations && ok; ++i, ++done) {
    const double t = 0.02 * (i + 1);
    const auto t0 = Clock::now();
    const auto n = tracker::encode_record(hand_record(t), config, rec);
    ok = n.ok() && ::write(master, rec.data(), *n) == static_cast<ssize_t>(*n) &&
         read_record(slave, in, *n);
    if (!ok) break;
    const auto t1 = Clock::now();
    std::span<const std::byte> bytes(in.data(), *n);
    auto ev = parser.next(bytes);
    if (!ev.ok() || ev->kind != tracker::EventKind::pose) break;
    auto hand = tracker::to_station_frame(ev->pose, conv);
    if (!hand.ok()) break;
    const link::Hands msg = rig.step(*hand);
    const auto fn = link::encode_frame(msg, frame);
    ok = ok && fn.ok() && ::write(sock[0], frame.data(), *fn) == static_cast<ssize_t>(*fn);
    const auto t2 = Clock::now();
    ok = ok && receive(sock[1], decoder, rig.replica());
    const auto t3 = Clock::now();
    renderer.set_live(&rig.replica().live());
    renderer.draw();
    const auto t4 = Clock::now();
    const std::array<double, 5> v{us_between(t0, t1), us_between(t1, t2), us_between(t2, t3),
                                  us_between(t3, t4), us_between(t0, t4)};
    for (std::size_t s = 0; s < v.size(); ++s) out.us[s].push_back(v[s]);
  }
  for (int fd : {master, slave, sock[0], sock[1]}) ::close(fd);
  return ok && done == iterations;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<long> sizes;
  int width = 800;
  int height = 600;
  for (int i = 1; i < argc; ++i) {
    if (std::string(argv[i]) == "--size" && i + 1 < argc) {
      std::sscanf(argv[++i], "%dx%d", &width, &height);
    } else {
      sizes.push_back(std::strtol(argv[i], nullptr, 10));
    }
  }
  if (sizes.empty()) sizes = {30'000, 100'000, 1'000'000};
  ::unsetenv("DISPLAY");
  auto context = bridge::make_offscreen_context(width, height);
  if (!context) {
    std::fprintf(stderr, "latency_probe: no offscreen GL context\n");
    return 1;
  }
  std::printf("frame %dx%d\n%-10s %-8s %10s %10s\n", width, height, "vertices", "stage",
              "median_us", "p99_us");
  const char* names[] = {"read", "station", "link", "frame", "total"};
  for (const long v : sizes) {
    bench::LatencyRig rig(static_cast<std::size_t>(v));
    bridge::MeshRenderer renderer;
    if (!rig.ready() || !renderer.init(width, height, true, {})) return 1;
    renderer.set_mesh(rig.replica().mesh(), false);
    renderer.set_weights(rig.replica().live().weight1, rig.replica().live().weight2);
    Stages st;
    const int iterations = v >= 1'000'000 ? 30 : 200;
    if (!measure(rig, renderer, iterations, st)) {
      std::fprintf(stderr, "latency_probe: a stage failed at %ld vertices\n", v);
      return 1;
    }
    for (std::size_t s = 0; s < st.us.size(); ++s) {
      std::printf("%-10zu %-8s %10.1f %10.1f\n", rig.vertices(), names[s],
                  percentile(st.us[s], 0.5), percentile(st.us[s], 0.99));
    }
  }
  return 0;
}
