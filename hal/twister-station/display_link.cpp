#include "display_link.hpp"

#include <algorithm>
#include <array>
#include <chrono>

#include "config/link_config.hpp"
#include "station_memory.hpp"
#include "twister/hal/startup_signals.hpp"

namespace twister::station_app {
namespace {

using Clock = std::chrono::steady_clock;

// Milliseconds left until `until`, at most 50 (so the link's own timers run).
int ms_left(Clock::time_point until) {
  const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(until - Clock::now());
  return static_cast<int>(std::clamp<std::int64_t>(left.count(), 0, 50));
}

}  // namespace

DisplayLink::DisplayLink() = default;
DisplayLink::~DisplayLink() = default;

hal::Expected<void> DisplayLink::open(const LinkSection& settings,
                                      const session::SculptSession& session,
                                      const link::Workspace& workspace, hal::Logger& log) {
  log_ = &log;
  stall_seconds_ = settings.spectator_stall_seconds;
  const std::string& address = settings.address;
  if (const std::string why = internal::unauthenticated_tcp_problem(settings); !why.empty()) {
    return hal::make_error(StatusCode::invalid_argument, "link: " + why);
  }
  if (!settings.psk_file.empty()) {
    if (auto ready = hal::SodiumAuthenticator::init(); !ready) return ready.error();
    auto key = hal::load_link_key(settings.psk_file);
    if (!key) return key.error();
    auth_ = std::make_unique<hal::SodiumAuthenticator>(*key);
  } else if (settings.listen == LinkListen::network) {
    return hal::make_error(StatusCode::invalid_argument,
                           "link " + address + ": listen = \"network\" needs psk_file");
  }
  station::StationLinkOptions options;
  options.authenticator = auth_.get();
  if (address.rfind("serial:", 0) == 0) {
    hal::SerialLinkConfig config;
    config.path = address.substr(7);
    config.baud = static_cast<int>(settings.baud);
    serial_ = std::make_unique<hal::SerialLink>(config);
    if (auto opened = serial_->open(); !opened) {
      if (opened.error().status.code() != StatusCode::unavailable) return opened.error();
      log.warning("link", "%s; retrying", opened.error().message.c_str());
    }
    port_ = serial_.get();
    poll_ = serial_.get();
  } else {
    hal::SocketLinkConfig config(address, true, 200);
    config.socket_mode = settings.socket_mode;
    config.socket_group = settings.socket_group;
    config.allow_network = settings.listen == LinkListen::network;
    socket_ = std::make_unique<hal::SocketLink>(config);
    if (auto opened = socket_->open(); !opened) {
      return hal::Error{opened.error().status, "link: " + opened.error().message};
    }
    port_ = socket_.get();
    poll_ = socket_.get();
    options.newcomers = socket_.get();
    // Spectators (issue 25): read-only displays in their own slots, each with a bounded
    // queue; a serial line has one display (a --spectator bridge there is admitted as
    // a read-only main display).
    options.spectators = socket_.get();
    options.max_spectators = settings.max_spectators;
    if (settings.max_spectators > 0) {
      spectator_queues_.resize(settings.max_spectators * kSpectatorQueueFrames *
                               link::kMaxFrameBytes);
      spectator_staging_.resize(kSpectatorQueueFrames * link::kMaxFrameBytes);
    }
    options.spectator_queues = spectator_queues_;
    options.spectator_staging = spectator_staging_;
    options.spectator_stall_us =
        static_cast<ports::TimestampUs>(settings.spectator_stall_seconds * 1e6);
  }
  const std::size_t n = session.mesh().vertex_capacity();
  x_.resize(n);
  y_.resize(n);
  z_.resize(n);
  indices_.resize(3 * session.mesh().triangle_capacity());
  // Room for a few hundred frames: a whole commit of a large stroke fits at once.
  out_.resize(512 * link::kMaxFrameBytes);
  station::StationLinkConfig link_config;
  link_config.workspace = workspace;
  link_ = std::make_unique<station::StationLink>(
      *port_, station::StationLinkStorage{x_, y_, z_, indices_, out_}, link_config, options);
  if (const Status s = link_->start(session); !s.ok()) {
    return hal::Error{s, std::string("link: ") + s.name()};
  }
  return {};
}

void DisplayLink::poll(station::Station& core, ports::TimestampUs now_us) {
  if (!link_) return;
  link_->poll(core, now_us);
  log_changes();
}

void DisplayLink::log_changes() {
  const station::StationLinkCounters& c = link_->counters();
  if (c.connects != logged_.connects) log_->notice("link", "display admitted");
  log_spectators(c);
  if (c.displaced != logged_.displaced) {
    log_->notice("link", "a newly admitted display took over; the previous one was told so");
  }
  if (c.commands != logged_.commands) {
    log_->info("link", "display commands passed to the session: %llu",
               static_cast<unsigned long long>(c.commands - logged_.commands));
  }
  if (c.commands_refused != logged_.commands_refused) {
    log_->warning("link", "display command refused (not admitted, or the command queue is full)");
  }
  // Refusals: at most one line per 10 s (a stranger may retry every 100 ms).
  const std::uint64_t refused = c.refused.errors();
  const std::uint64_t before = logged_.refused.errors();
  const auto now = Clock::now();
  if (refused != before && now - last_refusal_log_ >= std::chrono::seconds(10)) {
    const char* why = c.refused.unauthorised != logged_.refused.unauthorised
                          ? "unauthorised (no or wrong key)"
                      : c.refused.version != logged_.refused.version ? "another protocol version"
                      : c.refused.timeout != logged_.refused.timeout ? "no handshake within 2 s"
                                                                     : "it broke the handshake";
    log_->warning(
        "link", "refused a peer: %s (peer protocol %u, this station %u; %llu refused so far)", why,
        static_cast<unsigned>(link_->refused_version()),
        static_cast<unsigned>(link::kProtocolVersion), static_cast<unsigned long long>(refused));
    last_refusal_log_ = now;
  }
  logged_ = c;
}

void DisplayLink::log_spectators(const station::StationLinkCounters& c) {
  const station::SpectatorCounters& now = c.spectators;
  const station::SpectatorCounters& was = logged_.spectators;
  const auto n = static_cast<unsigned>(c.spectators_now);
  if (now.admitted != was.admitted) {
    log_->notice("link", "spectator display admitted (read-only; %u connected)", n);
  }
  if (now.left != was.left) log_->notice("link", "spectator display left (%u connected)", n);
  if (now.dropped != was.dropped) {
    log_->warning("link",
                  "spectator display dropped: it took nothing for %.1f s (%u connected; %llu "
                  "of its hands updates dropped in all)",
                  stall_seconds_, n, static_cast<unsigned long long>(now.live_dropped));
  }
  if (c.refused.full != logged_.refused.full) {
    log_->info("link", "spectator refused: all %zu spectator slots are taken",
               link_->spectator_slots());
  }
  if (now.commands_refused != was.commands_refused) {
    log_->info("link", "a spectator display sent a command: refused (read-only)");
  }
}

void DisplayLink::wait_ready(int timeout_ms) const {
  std::array<pollfd, hal::PollSource::kMaxFds> fds{};
  const std::size_t n = poll_->poll_fds(fds);
  // The peer's descriptor comes first; wait for room only while bytes are queued.
  if (n > 0 && link_->connected() && link_->pending_bytes() > 0) fds[0].events |= POLLOUT;
  ::poll(fds.data(), n, timeout_ms);
}

bool DisplayLink::wait_for_peer(station::Station& core, double seconds) {
  if (!link_) return false;
  const auto until = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                        std::chrono::duration<double>(seconds));
  while (Clock::now() < until && hal::startup_stop_signal() == 0) {
    poll(core, 0);
    if (link_->peer_synced()) return true;
    wait_ready(ms_left(until));
  }
  return false;
}

void DisplayLink::settle(station::Station& core, ports::TimestampUs now_us, double seconds) {
  if (!link_ || !link_->connected() || link_->idle()) return;
  const auto until = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                        std::chrono::duration<double>(seconds));
  while (link_->connected() && !link_->idle() && Clock::now() < until) {
    wait_ready(ms_left(until));
    poll(core, now_us);
  }
}

// Waits while the display (and every spectator) takes what is queued: up to `seconds`
// without progress (a refined commit's change set can need longer than that on a slow
// serial line, but it keeps moving), and never more than a minute in all.
void DisplayLink::drain(station::Station& core, ports::TimestampUs now_us, double seconds) {
  if (!link_) return;
  const auto patience =
      std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
  const auto last = Clock::now() + std::chrono::minutes(1);
  auto until = std::min(Clock::now() + patience, last);
  // The spectators too (issue 25): each gets what was queued for it, the same patience.
  const auto busy = [this] {
    return (link_->connected() && !link_->idle()) || !link_->spectators_idle();
  };
  const auto pending_now = [this] {
    return link_->pending_bytes() + link_->spectator_pending_bytes();
  };
  std::size_t pending = pending_now();
  while (busy() && Clock::now() < until) {
    poll(core, now_us);
    // Progress: the queue changed (bytes left, or a full mesh's next chunk came in).
    if (pending_now() != pending) {
      pending = pending_now();
      until = std::min(Clock::now() + patience, last);
    }
    if (busy()) wait_ready(ms_left(until));
  }
  link_->say_goodbye();
}

}  // namespace twister::station_app
