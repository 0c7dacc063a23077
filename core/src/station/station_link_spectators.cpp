// StationSpectators: read-only displays, each on its own bounded queues, served
// after the main display (issue 25).
#include "twister/station/station_link_spectators.hpp"

#include <algorithm>
#include <utility>

namespace twister::station {
namespace {

constexpr std::size_t kReceiveChunk = 256;

template <std::size_t... I>
std::array<Spectator, sizeof...(I)> make_slots(const LiveStreamConfig& live,
                                               std::index_sequence<I...> /*slots*/) {
  return {{((void)I, Spectator(live))...}};
}

}  // namespace

SpectatorCounters& SpectatorCounters::operator+=(const SpectatorCounters& o) {
  admitted += o.admitted;
  left += o.left;
  dropped += o.dropped;
  commands_refused += o.commands_refused;
  live_sent += o.live_sent;
  live_dropped += o.live_dropped;
  commits_sent += o.commits_sent;
  commits_resent += o.commits_resent;
  full_sends += o.full_sends;
  resend_requests += o.resend_requests;
  return *this;
}

Result<std::size_t> SpectatorChannel::do_send(std::span<const std::byte> src) {
  if (port_ == nullptr) return StatusCode::unavailable;
  return port_->send_spectator(slot_, src);
}

Result<std::size_t> SpectatorChannel::do_receive(std::span<std::byte> dest) {
  if (port_ == nullptr) return StatusCode::unavailable;
  return port_->receive_spectator(slot_, dest);
}

SpectatorView Spectator::view() const {
  SpectatorView v{open_, counters_, queues_.pending_bytes()};
  v.counters.live_sent = live_.counters().live_sent - live_base_.live_sent;
  v.counters.live_dropped = live_.counters().live_dropped - live_base_.live_dropped;
  v.counters.full_sends = mesh_.full_sends;
  return v;
}

StationSpectators::StationSpectators(ports::LinkSpectators* port, const SpectatorConfig& config,
                                     const LiveStreamConfig& live, std::span<std::byte> queues)
    : slots_(make_slots(live, std::make_index_sequence<kMaxSpectators>{})),
      port_(port),
      config_(config),
      queue_bytes_(queues) {}

Status StationSpectators::start() {
  slots_used_ = 0;
  if (config_.max_spectators == 0 || port_ == nullptr) return ok_status();
  const std::size_t n =
      std::min({config_.max_spectators, kMaxSpectators, port_->spectator_capacity()});
  if (n == 0) return ok_status();
  const std::size_t each = queue_bytes_.size() / n;
  if (each < 4 * link::kMaxFrameBytes) return StatusCode::resource_exhausted;
  for (std::size_t i = 0; i < n; ++i) {
    slots_[i].channel_.bind(port_, i);
    slots_[i].queues_.set_bulk(queue_bytes_.subspan(i * each, each));
  }
  slots_used_ = n;
  return ok_status();
}

bool StationSpectators::has_room() const {
  for (std::size_t i = 0; i < slots_used_; ++i) {
    if (!slots_[i].open_) return true;
  }
  return false;
}

bool StationSpectators::admit(MeshMirror& mirror, const MeshIdentity& holds,
                              ports::TimestampUs now_us) {
  for (std::size_t i = 0; i < slots_used_; ++i) {
    Spectator& s = slots_[i];
    if (s.open_) continue;
    if (!port_->admit_spectator(i).ok()) return false;
    s.open_ = true;
    s.catching_up_ = false;
    s.decoder_.clear();
    s.queues_.clear();
    s.mesh_ = MeshSendState{};
    mirror.resync(s.mesh_, holds);
    s.live_.restart();  // workspace, stroke (mid-stroke: its begin), hands, status at once
    s.visitor_.restart();
    s.live_base_ = s.live_.counters();
    s.counters_ = SpectatorCounters{};
    s.counters_.admitted = 1;
    s.progress_us_ = now_us;
    return true;
  }
  return false;
}

void StationSpectators::send_visitor(const Station& station, ports::TimestampUs now_us) {
  for (std::size_t i = 0; i < slots_used_; ++i) {
    if (slots_[i].open_) slots_[i].visitor_.send(station, slots_[i].queues_, now_us);
  }
}

bool StationSpectators::any_current() const {
  for (std::size_t i = 0; i < slots_used_; ++i) {
    if (slots_[i].open_ && slots_[i].mesh_.idle()) return true;
  }
  return false;
}

void StationSpectators::on_commit(std::span<const std::byte> staged) {
  for (std::size_t i = 0; i < slots_used_; ++i) {
    Spectator& s = slots_[i];
    if (!s.open_) continue;
    if (s.mesh_.active) {
      s.mesh_.restart();  // from the fresh shadow
    } else if (s.mesh_.wanted) {
      continue;  // a full send is due anyway
    } else if (!staged.empty() && s.queues_.bulk_bytes(staged)) {
      ++s.counters_.commits_sent;
    } else {
      s.mesh_.wanted = true;  // no room (or nothing staged): the whole mesh instead
      ++s.counters_.commits_resent;
    }
  }
}

void StationSpectators::close(Spectator& s, std::uint64_t SpectatorCounters::*why) {
  s.counters_.*why += 1;
  const std::size_t slot = static_cast<std::size_t>(&s - slots_.data());
  port_->close_spectator(slot);
  closed_ += s.view().counters;
  s.open_ = false;
  s.queues_.clear();
  s.mesh_ = MeshSendState{};
}

void StationSpectators::on_message(Spectator& s, const link::LinkMessage& m) {
  if (std::holds_alternative<link::ResendRequest>(m)) {
    ++s.counters_.resend_requests;
    s.mesh_.wanted = true;
  } else if (std::holds_alternative<link::Command>(m)) {
    ++s.counters_.commands_refused;
    (void)s.queues_.urgent(link::Notice{link::NoticeCode::command_refused_spectator, 0});
  } else if (std::holds_alternative<link::Bye>(m) || std::holds_alternative<link::Hello>(m)) {
    // It leaves, or starts a new session (a silent station): it connects anew as a
    // newcomer and is authenticated again.
    close(s, &SpectatorCounters::left);
  }
  // Anything else (station-only types) is ignored: it is read-only.
}

void StationSpectators::read(Spectator& s) {
  std::array<std::byte, kReceiveChunk> buf{};
  for (int round = 0; round < 4 && s.open_; ++round) {
    const Result<std::size_t> got = s.channel_.receive(buf);
    if (!got.ok()) {
      close(s, &SpectatorCounters::left);
      return;
    }
    for (std::size_t i = 0; i < *got && s.open_; ++i) {
      if (const auto m = s.decoder_.process(buf[i]); m.ok()) on_message(s, **m);
    }
    if (*got < buf.size()) return;
  }
}

void StationSpectators::poll(const session::SculptSession& session, const StationStatus& status,
                             MeshMirror& mirror, ports::TimestampUs now_us) {
  const auto present = static_cast<std::uint32_t>(count());
  for (std::size_t i = 0; i < slots_used_; ++i) {
    Spectator& s = slots_[i];
    if (!s.open_) continue;
    read(s);
    if (!s.open_) continue;
    s.catching_up_ = s.catching_up_ || !s.mesh_.idle();
    mirror.send(s.mesh_, s.queues_);
    const link::DecoderCounters d = s.decoder_.counters();
    s.live_.poll(session, status,
                 LinkFacts{mirror.version(), d.bad_crc + d.bad_cobs + d.bad_payload, present},
                 now_us);
    const std::size_t before = s.queues_.pending_bytes();
    s.queues_.flush();
    const std::size_t after = s.queues_.pending_bytes();
    if (after == 0 || after < before) s.progress_us_ = now_us;
    if (s.catching_up_ && s.mesh_.idle() && s.queues_.bulk_pending() == 0) {
      // Its mesh has gone: the next hands update (sent even if unchanged) finds it
      // there, so an open stroke shows at once (joining mid-stroke).
      s.catching_up_ = false;
      s.live_.resend_hands();
    }
    if (now_us - s.progress_us_ > config_.stall_timeout_us) close(s, &SpectatorCounters::dropped);
  }
}

void StationSpectators::refuse_command(FrameQueues& out) {
  ++closed_.commands_refused;
  (void)out.urgent(link::Notice{link::NoticeCode::command_refused_spectator, 0});
}

void StationSpectators::say_goodbye() {
  for (std::size_t i = 0; i < slots_used_; ++i) {
    Spectator& s = slots_[i];
    if (!s.open_) continue;
    (void)s.queues_.urgent(link::Bye{link::ByeReason::shutdown});
    s.queues_.flush();
  }
}

std::size_t StationSpectators::count() const {
  std::size_t n = 0;
  for (std::size_t i = 0; i < slots_used_; ++i)
    n += slots_[i].open_ ? std::size_t{1} : std::size_t{0};
  return n;
}

SpectatorCounters StationSpectators::totals() const {
  SpectatorCounters t = closed_;
  for (std::size_t i = 0; i < slots_used_; ++i) {
    if (slots_[i].open_) t += slots_[i].view().counters;
  }
  return t;
}

SpectatorView StationSpectators::view(std::size_t slot) const {
  return slot < slots_used_ ? slots_[slot].view() : SpectatorView{};
}

std::size_t StationSpectators::pending_bytes() const {
  std::size_t n = 0;
  for (std::size_t i = 0; i < slots_used_; ++i) n += slots_[i].queues_.pending_bytes();
  return n;
}

bool StationSpectators::idle() const {
  for (std::size_t i = 0; i < slots_used_; ++i) {
    const Spectator& s = slots_[i];
    if (s.open_ && (s.queues_.pending_bytes() > 0 || !s.mesh_.idle())) return false;
  }
  return true;
}

}  // namespace twister::station
