// StationLink: admission of the display (hello, challenge-response, newcomers),
// the display's requests, and the two outgoing queues. Mesh sync is in
// station_link_mesh.cpp, the live stream in station_link_live.cpp.
#include "twister/station/station_link.hpp"

#include <algorithm>
#include <cstring>

namespace twister::station {
namespace {

constexpr std::size_t kReceiveChunk = 256;

// Length of the frame at the start of `bytes` (up to and including its 0x00), or
// bytes.size() when it is not complete.
std::size_t frame_length(std::span<const std::byte> bytes) {
  const auto end = std::find(bytes.begin(), bytes.end(), std::byte{0});
  return end == bytes.end() ? bytes.size() : static_cast<std::size_t>(end - bytes.begin()) + 1;
}

}  // namespace

StationLink::StationLink(ports::LinkPort& port, StationLinkStorage storage,
                         const StationLinkConfig& config, const StationLinkOptions& options)
    : port_(port),
      storage_(storage),
      config_(config),
      options_(options),
      shadow_(storage.x, storage.y, storage.z, storage.triangle_indices),
      out_(storage.out) {}

Status StationLink::start(const session::SculptSession& session) {
  if (out_.size() < 4 * link::kMaxFrameBytes) return StatusCode::resource_exhausted;
  TWISTER_TRY(shadow_.copy_from(session.mesh()));
  version_ = 1;
  last_sequence_ = session.next_sequence();
  started_ = true;
  return ok_status();
}

void StationLink::poll(const session::SculptSession& session, const StationStatus& status,
                       ports::TimestampUs now_us) {
  if (!started_) return;
  receive(now_us);
  poll_newcomer(now_us);
  if (session.next_sequence() != last_sequence_) {
    last_sequence_ = session.next_sequence();
    track_mesh(session.mesh());
  }
  if (admitted()) {
    if (full_wanted_ && !full_active_) start_full();
    if (full_active_) continue_full();
    send_live(session, status, now_us);
  }
  flush();
}

void StationLink::lose_display() {
  if (connected_) ++counters_.disconnects;
  connected_ = false;
  display_ = Handshake{};
  clear_queues();
  full_active_ = false;
  full_wanted_ = false;
  decoder_.clear();
}

void StationLink::receive(ports::TimestampUs now_us) {
  std::array<std::byte, kReceiveChunk> buf{};
  for (int round = 0; round < 16; ++round) {
    const Result<std::size_t> got = port_.receive(buf);
    if (!got.ok()) {
      lose_display();
      return;
    }
    if (!connected_) {
      // A new connection: a fresh decoder and handshake; the display speaks first.
      connected_ = true;
      display_ = Handshake{};
      display_.since_us = now_us;
      decoder_.clear();
    }
    for (std::size_t i = 0; i < *got; ++i) {
      if (const auto m = decoder_.process(buf[i]); m.ok()) on_display_message(**m);
    }
    if (decoder_.other_version() != 0) refuse_version(decoder_);
    if (*got < buf.size()) return;
  }
}

void StationLink::refuse_version(link::LinkDecoder& decoder) {
  refused_version_ = decoder.other_version();
  ++counters_.refused_version;
  decoder.clear();
}

link::LinkMessage StationLink::begin_handshake(Handshake& hs, const link::Hello& hello) {
  hs.hello = true;
  hs.bridge_nonce = hello.nonce;
  hs.have_version = hello.mesh_version;
  hs.have_checksum = hello.mesh_checksum;
  hs.station_nonce =
      options_.authenticator != nullptr ? options_.authenticator->make_nonce() : link::Nonce{};
  link::LinkMessage reply;
  reply.type = link::MessageType::hello;
  reply.hello = link::Hello{link::Role::station,
                            options_.authenticator != nullptr ? link::kHelloAuth : std::uint8_t{0},
                            version_, shadow_.checksum(), hs.station_nonce};
  return reply;
}

bool StationLink::check_auth(const Handshake& hs, const link::Auth& auth) const {
  return options_.authenticator != nullptr && hs.hello &&
         options_.authenticator->verify(link::Role::bridge, hs.station_nonce, hs.bridge_nonce,
                                        auth.tag);
}

link::LinkMessage StationLink::station_auth(const Handshake& hs) const {
  link::LinkMessage m;
  m.type = link::MessageType::auth;
  m.auth.tag = options_.authenticator->tag(link::Role::station, hs.station_nonce, hs.bridge_nonce);
  return m;
}

void StationLink::resync(const Handshake& hs) {
  // Resync by version: a display that holds exactly our mesh gets nothing again.
  if (hs.have_version != version_ || hs.have_checksum != shadow_.checksum()) full_wanted_ = true;
  hands_sent_ = false;
  status_sent_ = false;
  object_sent_valid_ = false;
  last_stroke_us_ = 0;
  live_was_active_ = false;
}

void StationLink::on_display_message(const link::LinkMessage& m) {
  const bool auth = options_.authenticator != nullptr;
  switch (m.type) {
    case link::MessageType::hello: {
      if (m.hello.role != link::Role::bridge) {
        ++counters_.refused_protocol;
        return;
      }
      // A (re)started display on this channel. With a key, the display stays
      // admitted until the new handshake proves the newcomer (a stranger on a
      // shared line displaces nobody).
      Handshake next = display_;
      const link::LinkMessage reply = begin_handshake(next, m.hello);
      if (!auth) next.admitted = true;
      display_ = next;
      (void)queue_urgent(reply);
      if (!auth) {
        ++counters_.connects;
        resync(display_);
      }
      return;
    }
    case link::MessageType::auth:
      if (!check_auth(display_, m.auth)) {
        ++counters_.refused_unauthorised;
        return;
      }
      if (!display_.admitted) ++counters_.connects;
      display_.admitted = true;
      (void)queue_urgent(station_auth(display_));
      resync(display_);
      return;
    case link::MessageType::resend_request:
      if (!display_.admitted) return;
      ++counters_.resend_requests;
      full_wanted_ = true;  // asked: the full mesh even when versions agree
      return;
    case link::MessageType::bye:
      display_.admitted = false;  // the display leaves; its socket follows
      return;
    case link::MessageType::command:
      if (!display_.admitted || command_count_ == kMaxCommands) {
        ++counters_.commands_refused;
        return;
      }
      commands_[command_count_++] = m.command;
      return;
    default:
      ++counters_.refused_protocol;  // only the station sends the other types
      return;
  }
}

session::SessionCommand session_command(const link::Command& c) {
  session::SessionCommand out;
  out.hand = 0;  // a display's command belongs to no hand
  switch (c.kind) {
    case link::CommandKind::undo:
      out.kind = session::SessionCommandKind::undo;
      break;
    case link::CommandKind::redo:
      out.kind = session::SessionCommandKind::redo;
      break;
    case link::CommandKind::next_method:
      out.kind = session::SessionCommandKind::next_method;
      break;
    case link::CommandKind::set_method:
      out.kind = session::SessionCommandKind::set_method;
      out.method = static_cast<math::WarpMethod>(c.method);
      break;
  }
  return out;
}

bool StationLink::take_command(link::Command& out) {
  if (command_count_ == 0) return false;
  out = commands_[0];
  for (std::size_t i = 1; i < command_count_; ++i) commands_[i - 1] = commands_[i];
  --command_count_;
  ++counters_.commands;
  return true;
}

void StationLink::poll_newcomer(ports::TimestampUs now_us) {
  ports::LinkNewcomers* n = options_.newcomers;
  if (n == nullptr) return;
  if (n->newcomer_id() != newcomer_id_) {
    newcomer_id_ = n->newcomer_id();
    newcomer_open_ = true;
    newcomer_ = Handshake{};
    newcomer_.since_us = now_us;
    newcomer_decoder_.clear();  // every connection starts with a fresh decoder
    ++counters_.newcomers;
  }
  if (!newcomer_open_) return;
  std::array<std::byte, kReceiveChunk> buf{};
  for (int round = 0; round < 4 && newcomer_open_; ++round) {
    const Result<std::size_t> got = n->receive_newcomer(buf);
    if (!got.ok()) {
      newcomer_open_ = false;  // it hung up
      return;
    }
    for (std::size_t i = 0; i < *got && newcomer_open_; ++i) {
      if (const auto m = newcomer_decoder_.process(buf[i]); m.ok()) on_newcomer_message(**m);
    }
    if (newcomer_open_ && newcomer_decoder_.other_version() != 0) {
      refuse_version(newcomer_decoder_);
      refuse_newcomer(link::ByeReason::protocol, nullptr);
      return;
    }
    if (*got < buf.size()) break;
  }
  if (newcomer_open_ && now_us - newcomer_.since_us > config_.handshake_timeout_us) {
    refuse_newcomer(link::ByeReason::timeout, &counters_.refused_timeout);
  }
}

void StationLink::on_newcomer_message(const link::LinkMessage& m) {
  const bool auth = options_.authenticator != nullptr;
  if (m.type == link::MessageType::hello && m.hello.role == link::Role::bridge &&
      !newcomer_.hello) {
    send_newcomer(begin_handshake(newcomer_, m.hello));
    if (!auth) admit_newcomer();
    return;
  }
  if (m.type == link::MessageType::auth && auth && newcomer_.hello) {
    if (!check_auth(newcomer_, m.auth)) {
      refuse_newcomer(link::ByeReason::unauthorised, &counters_.refused_unauthorised);
      return;
    }
    send_newcomer(station_auth(newcomer_));
    admit_newcomer();
    return;
  }
  if (m.type == link::MessageType::bye) {
    newcomer_open_ = false;
    options_.newcomers->refuse_newcomer();
    return;
  }
  // Anything else before admission breaks the handshake (and with a key, a
  // display that does not prove itself is unauthorised).
  refuse_newcomer(auth ? link::ByeReason::unauthorised : link::ByeReason::protocol,
                  auth ? &counters_.refused_unauthorised : &counters_.refused_protocol);
}

void StationLink::send_newcomer(const link::LinkMessage& m) {
  std::array<std::byte, 128> frame{};
  const Result<std::size_t> n = link::encode_frame(m, frame);
  if (!n.ok()) return;
  const Result<std::size_t> sent =
      options_.newcomers->send_newcomer(std::span<const std::byte>(frame).first(*n));
  if (!sent.ok() || *sent != *n) ++counters_.send_errors;
}

void StationLink::refuse_newcomer(link::ByeReason reason, std::uint64_t* counter) {
  if (counter != nullptr) ++*counter;
  link::LinkMessage bye;
  bye.type = link::MessageType::bye;
  bye.bye.reason = reason;
  send_newcomer(bye);
  options_.newcomers->refuse_newcomer();
  newcomer_open_ = false;
}

void StationLink::admit_newcomer() {
  if (connected_) {
    // Tell the display why it goes, at a frame boundary of its stream: a 0x00 ends
    // any frame it has half received, then the bye follows.
    if (display_.admitted) ++counters_.displaced;
    std::array<std::byte, 64> frame{};
    frame[0] = std::byte{0};
    link::LinkMessage bye;
    bye.type = link::MessageType::bye;
    bye.bye.reason = link::ByeReason::displaced;
    if (const auto n = link::encode_frame(bye, std::span<std::byte>(frame).subspan(1)); n.ok()) {
      (void)port_.send(std::span<const std::byte>(frame).first(*n + 1));
    }
  }
  options_.newcomers->admit_newcomer();
  newcomer_open_ = false;
  const Handshake admitted = newcomer_;
  lose_display();
  connected_ = true;
  display_ = admitted;
  display_.admitted = true;
  ++counters_.connects;
  resync(display_);
}

void StationLink::say_goodbye() {
  if (!connected_) return;
  link::LinkMessage bye;
  bye.type = link::MessageType::bye;
  bye.bye.reason = link::ByeReason::shutdown;
  (void)queue_urgent(bye);
  flush();
}

bool StationLink::queue(const link::LinkMessage& m) {
  const Result<std::size_t> n = link::encode_frame(m, out_.subspan(out_size_));
  if (!n.ok()) return false;
  out_size_ += *n;
  return true;
}

bool StationLink::queue_urgent(const link::LinkMessage& m) {
  const Result<std::size_t> n =
      link::encode_frame(m, std::span<std::byte>(urgent_).subspan(urgent_size_));
  if (!n.ok()) return false;
  urgent_size_ += *n;
  return true;
}

void StationLink::clear_queues() {
  // A torn frame is harmless: the next peer resyncs at 0x00.
  out_size_ = 0;
  urgent_size_ = 0;
  sending_ = Queue::none;
}

void StationLink::flush() {
  // Frames leave whole; between two frames the urgent queue goes first.
  for (int round = 0; round < 64; ++round) {
    if (sending_ == Queue::none) {
      if (urgent_size_ > 0) {
        sending_ = Queue::urgent;
      } else if (out_size_ > 0) {
        sending_ = Queue::bulk;
      } else {
        return;
      }
    }
    const bool urgent = sending_ == Queue::urgent;
    std::byte* data = urgent ? urgent_.data() : out_.data();
    std::size_t& size = urgent ? urgent_size_ : out_size_;
    // Bulk frames go out together unless urgent ones wait; urgent ones always.
    const std::size_t take =
        urgent || urgent_size_ == 0 ? size : frame_length(std::span<const std::byte>(data, size));
    const Result<std::size_t> n = port_.send(std::span<const std::byte>(data, take));
    if (!n.ok()) {
      ++counters_.send_errors;
      return;
    }
    if (*n == 0) return;
    const bool at_boundary = data[*n - 1] == std::byte{0};
    std::memmove(data, data + *n, size - *n);
    size -= *n;
    if (at_boundary) sending_ = Queue::none;
    if (*n < take) return;  // the port is full
  }
}

}  // namespace twister::station
