#include "twister/station/station_link.hpp"

#include <algorithm>
#include <bit>
#include <cstring>

#include "twister/link/math_conversion.hpp"

namespace twister::station {
namespace {

constexpr std::size_t kReceiveChunk = 256;

bool same_frame(const math::Frame& a, const math::Frame& b) {
  return a.origin == b.origin && a.u == b.u && a.v == b.v && a.w == b.w;
}

}  // namespace

StationLink::StationLink(ports::LinkPort& port, StationLinkStorage storage,
                         const StationLinkConfig& config)
    : port_(port),
      storage_(storage),
      config_(config),
      shadow_(storage.x, storage.y, storage.z, storage.triangle_indices),
      out_(storage.out) {}

Status StationLink::start(const input::SculptSession& session) {
  if (out_.size() < 4 * link::kMaxFrameBytes) return StatusCode::resource_exhausted;
  TWISTER_TRY(shadow_.copy_from(session.mesh()));
  version_ = 1;
  last_sequence_ = session.next_sequence();
  started_ = true;
  return ok_status();
}

void StationLink::poll(const input::SculptSession& session, ports::TimestampUs now_us) {
  if (!started_) return;
  receive();
  if (session.next_sequence() != last_sequence_) {
    last_sequence_ = session.next_sequence();
    track_mesh(session.mesh());
  }
  if (connected_) {
    if (full_wanted_ && !full_active_) {
      full_wanted_ = false;
      full_active_ = true;
      full_phase_ = FullPhase::begin;
      full_next_ = 0;
      ++counters_.full_sends;
    }
    if (full_active_) continue_full();
    send_live(session, now_us);
    send_status(session, now_us);
  }
  flush();
}

void StationLink::receive() {
  std::array<std::byte, kReceiveChunk> buf{};
  for (int round = 0; round < 16; ++round) {
    const Result<std::size_t> got = port_.receive(buf);
    if (!got.ok()) {
      if (connected_) ++counters_.disconnects;
      connected_ = false;
      peer_hello_ = false;
      out_size_ = 0;  // a torn frame is harmless: the next peer resyncs at 0x00
      full_active_ = false;
      decoder_.clear();
      return;
    }
    if (!connected_) {
      // A new peer: it holds some version (maybe ours); wait for its hello, and
      // greet it so it knows our version.
      connected_ = true;
      ++counters_.connects;
      scratch_.type = link::MessageType::hello;
      scratch_.hello = link::Hello{link::Role::station, version_, shadow_.checksum()};
      queue(scratch_);
    }
    for (std::size_t i = 0; i < *got; ++i) {
      if (const auto m = decoder_.process(buf[i]); m.ok()) on_message(**m);
    }
    if (*got < buf.size()) return;
  }
}

void StationLink::on_message(const link::LinkMessage& m) {
  // Resync by version: a peer that holds exactly our mesh gets nothing again.
  std::uint32_t have = 0;
  std::uint64_t sum = 0;
  if (m.type == link::MessageType::hello && m.hello.role == link::Role::bridge) {
    have = m.hello.mesh_version;
    sum = m.hello.mesh_checksum;
    peer_hello_ = true;
  } else if (m.type == link::MessageType::resend_request) {
    ++counters_.resend_requests;
    have = m.resend_request.have_version;
    sum = m.resend_request.have_checksum;
    if (have == version_ && sum == shadow_.checksum()) have = 0;  // asked: send anyway
  } else {
    return;
  }
  if (have != version_ || sum != shadow_.checksum()) full_wanted_ = true;
}

void StationLink::track_mesh(const mesh::Mesh& mesh) {
  const auto old_vertices = static_cast<std::uint32_t>(shadow_.vertex_count());
  const auto old_triangles = static_cast<std::uint32_t>(shadow_.triangle_count());
  ++version_;
  const bool sent = connected_ && !full_active_ && !full_wanted_ &&
                    queue_commit(mesh, old_vertices, old_triangles);
  if (!shadow_.copy_from(mesh).ok()) {
    // Larger than the shadow (cannot happen when sized from the mesh capacity).
    shadow_.clear();
  }
  if (full_active_) {
    full_phase_ = FullPhase::begin;  // restart from the fresh shadow
    full_next_ = 0;
  } else if (!sent && connected_) {
    full_wanted_ = true;
  }
}

bool StationLink::queue_commit(const mesh::Mesh& mesh, std::uint32_t old_vertices,
                               std::uint32_t old_triangles) {
  // Triangles are only ever appended by the session; anything else is a full send.
  const auto old_idx = shadow_.triangle_indices();
  const auto new_idx = mesh.triangle_indices();
  if (new_idx.size() < old_idx.size() || mesh.vertex_count() < old_vertices ||
      !std::equal(old_idx.begin(), old_idx.end(), new_idx.begin())) {
    return false;
  }
  const std::size_t saved = out_size_;
  const auto fail = [&] {
    out_size_ = saved;  // all or nothing: never a half commit in the buffer
    return false;
  };
  scratch_.type = link::MessageType::mesh_begin;
  scratch_.mesh_begin = link::MeshBegin{false, version_ - 1, version_,
                                        static_cast<std::uint32_t>(mesh.vertex_count()),
                                        static_cast<std::uint32_t>(mesh.triangle_count())};
  if (!queue(scratch_)) return fail();
  scratch_.type = link::MessageType::vertices;
  scratch_.vertices.count = 0;
  const auto sx = shadow_.x();
  const auto sy = shadow_.y();
  const auto sz = shadow_.z();
  const auto mx = mesh.x();
  const auto my = mesh.y();
  const auto mz = mesh.z();
  for (std::size_t i = 0; i < mesh.vertex_count(); ++i) {
    const bool changed =
        i >= old_vertices ||
        std::bit_cast<std::uint32_t>(sx[i]) != std::bit_cast<std::uint32_t>(mx[i]) ||
        std::bit_cast<std::uint32_t>(sy[i]) != std::bit_cast<std::uint32_t>(my[i]) ||
        std::bit_cast<std::uint32_t>(sz[i]) != std::bit_cast<std::uint32_t>(mz[i]);
    if (!changed) continue;
    scratch_.vertices.items[scratch_.vertices.count++] =
        link::VertexEntry{static_cast<std::uint32_t>(i), mx[i], my[i], mz[i]};
    if (scratch_.vertices.count == link::kMaxVerticesPerChunk) {
      if (!queue(scratch_)) return fail();
      scratch_.vertices.count = 0;
    }
  }
  if (scratch_.vertices.count > 0 && !queue(scratch_)) return fail();
  scratch_.type = link::MessageType::triangles;
  for (std::size_t t = old_triangles; t < mesh.triangle_count(); t += link::kMaxTrianglesPerChunk) {
    const std::size_t n = std::min(link::kMaxTrianglesPerChunk, mesh.triangle_count() - t);
    scratch_.triangles.first = static_cast<std::uint32_t>(t);
    scratch_.triangles.count = static_cast<std::uint16_t>(n);
    std::copy_n(new_idx.begin() + static_cast<std::ptrdiff_t>(3 * t), 3 * n,
                scratch_.triangles.indices.begin());
    if (!queue(scratch_)) return fail();
  }
  scratch_.type = link::MessageType::mesh_end;
  scratch_.mesh_end = link::MeshEnd{version_, mesh.checksum()};
  if (!queue(scratch_)) return fail();
  ++counters_.commits_sent;
  return true;
}

void StationLink::continue_full() {
  // A few frames per poll keep the loop responsive; the rest follows next poll.
  while (full_active_ && room() >= link::kMaxFrameBytes) {
    switch (full_phase_) {
      case FullPhase::begin:
        scratch_.type = link::MessageType::mesh_begin;
        scratch_.mesh_begin =
            link::MeshBegin{true, 0, version_, static_cast<std::uint32_t>(shadow_.vertex_count()),
                            static_cast<std::uint32_t>(shadow_.triangle_count())};
        queue(scratch_);
        full_phase_ = FullPhase::vertices;
        full_next_ = 0;
        break;
      case FullPhase::vertices: {
        const std::size_t n =
            std::min(link::kMaxVerticesPerChunk, shadow_.vertex_count() - full_next_);
        scratch_.type = link::MessageType::vertices;
        scratch_.vertices.count = static_cast<std::uint16_t>(n);
        for (std::size_t k = 0; k < n; ++k) {
          const auto i = static_cast<std::uint32_t>(full_next_ + k);
          const glm::vec3 p = shadow_.position(i);
          scratch_.vertices.items[k] = link::VertexEntry{i, p.x, p.y, p.z};
        }
        if (n > 0) queue(scratch_);
        full_next_ += n;
        if (full_next_ >= shadow_.vertex_count()) {
          full_phase_ = FullPhase::triangles;
          full_next_ = 0;
        }
        break;
      }
      case FullPhase::triangles: {
        const std::size_t n =
            std::min(link::kMaxTrianglesPerChunk, shadow_.triangle_count() - full_next_);
        scratch_.type = link::MessageType::triangles;
        scratch_.triangles.first = static_cast<std::uint32_t>(full_next_);
        scratch_.triangles.count = static_cast<std::uint16_t>(n);
        std::copy_n(
            shadow_.triangle_indices().begin() + static_cast<std::ptrdiff_t>(3 * full_next_), 3 * n,
            scratch_.triangles.indices.begin());
        if (n > 0) queue(scratch_);
        full_next_ += n;
        if (full_next_ >= shadow_.triangle_count()) full_phase_ = FullPhase::end;
        break;
      }
      case FullPhase::end:
        scratch_.type = link::MessageType::mesh_end;
        scratch_.mesh_end = link::MeshEnd{version_, shadow_.checksum()};
        queue(scratch_);
        full_active_ = false;
        break;
    }
  }
}

void StationLink::send_live(const input::SculptSession& session, ports::TimestampUs now_us) {
  const input::LiveWarp live = session.live();
  const bool active = live.active && live.plan != nullptr && live.plan->built();
  if (!active && !live_was_active_) return;
  if (active && live_was_active_ && now_us - last_live_us_ < config_.live_interval_us) return;
  if (full_active_) {
    ++counters_.live_dropped;  // the mesh it applies to is not there yet
    return;
  }
  link::LiveWarp& l = scratch_.live_warp;
  scratch_.type = link::MessageType::live_warp;
  l = link::LiveWarp{};
  l.mesh_version = version_;
  l.active = active;
  if (active) {
    const math::WarpPlan& plan = *live.plan;
    bool new_stroke = !live_was_active_;
    l.method = static_cast<std::uint8_t>(plan.method());
    l.radius_m = plan.radius();
    for (std::size_t h = 0; h < plan.hand_count() && h < link::kLinkHands; ++h) {
      l.hand_mask = static_cast<std::uint8_t>(l.hand_mask | (1u << h));
      l.hands[h] = link::LiveHand{link::to_wire(plan.start_frame(h)),
                                  link::to_wire(plan.end_frame(h)), link::to_wire(plan.screw(h))};
      new_stroke = new_stroke || !same_frame(plan.start_frame(h), live_start_[h]);
      live_start_[h] = plan.start_frame(h);
    }
    if (new_stroke) ++stroke_;
  }
  l.stroke = stroke_;
  if (!queue(scratch_)) {
    ++counters_.live_dropped;
    return;
  }
  ++counters_.live_sent;
  live_was_active_ = active;
  last_live_us_ = now_us;
}

void StationLink::send_status(const input::SculptSession& session, ports::TimestampUs now_us) {
  if (status_sent_ && now_us - last_status_us_ < config_.status_interval_us) return;
  if (full_active_ || room() < 2 * link::kMaxFrameBytes) return;  // keep room for commits
  scratch_.type = link::MessageType::status;
  scratch_.status = link::StatusReport{
      version_,
      session.next_sequence(),
      counters_.live_sent,
      counters_.live_dropped,
      counters_.full_sends,
      counters_.commits_sent,
      decoder_counters().bad_crc + decoder_counters().bad_cobs + decoder_counters().bad_payload};
  if (queue(scratch_)) {
    status_sent_ = true;
    last_status_us_ = now_us;
  }
}

bool StationLink::queue(const link::LinkMessage& m) {
  const Result<std::size_t> n = link::encode_frame(m, out_.subspan(out_size_));
  if (!n.ok()) return false;
  out_size_ += *n;
  return true;
}

void StationLink::flush() {
  std::size_t sent = 0;
  while (sent < out_size_) {
    const Result<std::size_t> n =
        port_.send(std::span<const std::byte>(out_).subspan(sent, out_size_ - sent));
    if (!n.ok()) {
      ++counters_.send_errors;
      break;
    }
    if (*n == 0) break;
    sent += *n;
  }
  if (sent > 0) {
    std::memmove(out_.data(), out_.data() + sent, out_size_ - sent);
    out_size_ -= sent;
  }
}

}  // namespace twister::station
