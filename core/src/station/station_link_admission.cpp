// LinkAdmission: the display's channel and the newcomer's, their handshakes,
// admission, displacement and refusals.
#include "twister/station/station_link_admission.hpp"

#include <array>

namespace twister::station {
namespace {

constexpr std::size_t kReceiveChunk = 256;

}  // namespace

void LinkAdmission::poll(ports::TimestampUs now_us) {
  receive(now_us);
  poll_newcomer(now_us);
}

void LinkAdmission::lose_display() {
  if (connected_) ++counters_.disconnects;
  connected_ = false;
  display_ = Handshake{};
  decoder_.clear();
  listener_.on_display_lost();
}

void LinkAdmission::receive(ports::TimestampUs now_us) {
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

void LinkAdmission::refuse_version(link::LinkDecoder& decoder) {
  refused_version_ = decoder.other_version();
  ++counters_.refused.version;
  decoder.clear();
}

link::Hello LinkAdmission::begin_handshake(Handshake& hs, const link::Hello& hello) {
  hs.hello = true;
  hs.yield = (hello.flags & link::kHelloYield) != 0;
  hs.spectator = (hello.flags & link::kHelloSpectator) != 0;
  hs.bridge_nonce = hello.nonce;
  hs.holds = MeshIdentity{hello.mesh_version, hello.mesh_checksum};
  hs.station_nonce =
      options_.authenticator != nullptr ? options_.authenticator->make_nonce() : link::Nonce{};
  const MeshIdentity offered = listener_.offered();
  return link::Hello{link::Role::station,
                     options_.authenticator != nullptr ? link::kHelloAuth : std::uint8_t{0},
                     offered.version, offered.checksum, hs.station_nonce};
}

bool LinkAdmission::check_auth(const Handshake& hs, const link::Auth& auth) const {
  return options_.authenticator != nullptr && hs.hello &&
         options_.authenticator->verify(link::Role::bridge, hs.station_nonce, hs.bridge_nonce,
                                        auth.tag);
}

link::Auth LinkAdmission::station_auth(const Handshake& hs) const {
  return link::Auth{
      options_.authenticator->tag(link::Role::station, hs.station_nonce, hs.bridge_nonce)};
}

void LinkAdmission::on_display_hello(const link::Hello& hello) {
  if (hello.role != link::Role::bridge) {
    ++counters_.refused.protocol;
    return;
  }
  // A (re)started display on this channel. With a key, the display stays admitted
  // until the new handshake proves the newcomer (a stranger on a shared line
  // displaces nobody).
  const bool auth = options_.authenticator != nullptr;
  Handshake next = display_;
  const link::Hello reply = begin_handshake(next, hello);
  if (!auth) next.admitted = true;
  display_ = next;
  (void)replies_.urgent(reply);
  if (!auth) {
    ++counters_.connects;
    listener_.on_admitted(display_.holds);
  }
}

void LinkAdmission::on_display_message(const link::LinkMessage& m) {
  if (const auto* hello = std::get_if<link::Hello>(&m)) {
    on_display_hello(*hello);
  } else if (const auto* auth = std::get_if<link::Auth>(&m)) {
    if (!check_auth(display_, *auth)) {
      ++counters_.refused.unauthorised;
      return;
    }
    if (!display_.admitted) ++counters_.connects;
    display_.admitted = true;
    (void)replies_.urgent(station_auth(display_));
    listener_.on_admitted(display_.holds);
  } else if (std::holds_alternative<link::ResendRequest>(m)) {
    if (!display_.admitted) return;
    ++counters_.resend_requests;
    listener_.on_resend_request();  // asked: the full mesh even when versions agree
  } else if (std::holds_alternative<link::Bye>(m)) {
    display_.admitted = false;  // the display leaves; its socket follows
  } else if (const auto* command = std::get_if<link::Command>(&m)) {
    if (!display_.admitted) {
      ++counters_.commands_refused;
      return;
    }
    if (display_.spectator) {
      listener_.on_spectator_command();  // a read-only display on the main channel
      return;
    }
    listener_.on_command(*command);
  } else {
    ++counters_.refused.protocol;  // only the station sends the other types
  }
}

void LinkAdmission::poll_newcomer(ports::TimestampUs now_us) {
  ports::LinkNewcomers* n = options_.newcomers;
  if (n == nullptr) return;
  if (n->newcomer_id() != newcomer_.id) {
    newcomer_.id = n->newcomer_id();
    newcomer_.open = true;
    newcomer_.handshake = Handshake{};
    newcomer_.handshake.since_us = now_us;
    newcomer_.decoder.clear();  // every connection starts with a fresh decoder
    ++counters_.newcomers;
  }
  if (!newcomer_.open) return;
  std::array<std::byte, kReceiveChunk> buf{};
  for (int round = 0; round < 4 && newcomer_.open; ++round) {
    const Result<std::size_t> got = n->receive_newcomer(buf);
    if (!got.ok()) {
      newcomer_.open = false;  // it hung up
      return;
    }
    for (std::size_t i = 0; i < *got && newcomer_.open; ++i) {
      if (const auto m = newcomer_.decoder.process(buf[i]); m.ok()) {
        on_newcomer_message(**m);
      }
    }
    if (newcomer_.open && newcomer_.decoder.other_version() != 0) {
      refuse_version(newcomer_.decoder);
      refuse_newcomer(link::ByeReason::protocol, nullptr);
      return;
    }
    if (*got < buf.size()) break;
  }
  if (newcomer_.open && now_us - newcomer_.handshake.since_us > handshake_timeout_us_) {
    refuse_newcomer(link::ByeReason::timeout, &counters_.refused.timeout);
  }
}

void LinkAdmission::on_newcomer_message(const link::LinkMessage& m) {
  const bool auth = options_.authenticator != nullptr;
  Handshake& hs = newcomer_.handshake;
  const auto* hello = std::get_if<link::Hello>(&m);
  if (hello != nullptr && hello->role == link::Role::bridge && !hs.hello) {
    const link::Hello reply = begin_handshake(hs, *hello);
    if (hs.spectator && !listener_.spectator_room()) {
      refuse_newcomer(link::ByeReason::busy, &counters_.refused.full);
      return;
    }
    if (!hs.spectator && refuse_if_busy()) return;
    send_newcomer(reply);
    if (!auth && hs.spectator) admit_spectator();
    if (!auth && !hs.spectator) admit_newcomer();
    return;
  }
  const auto* tag = std::get_if<link::Auth>(&m);
  if (tag != nullptr && auth && hs.hello) {
    if (!check_auth(hs, *tag)) {
      refuse_newcomer(link::ByeReason::unauthorised, &counters_.refused.unauthorised);
      return;
    }
    send_newcomer(station_auth(hs));
    if (hs.spectator) {
      admit_spectator();
    } else {
      admit_newcomer();
    }
    return;
  }
  if (std::holds_alternative<link::Bye>(m)) {
    newcomer_.open = false;
    options_.newcomers->refuse_newcomer();
    return;
  }
  // Anything else before admission breaks the handshake (and with a key, a
  // display that does not prove itself is unauthorised).
  refuse_newcomer(auth ? link::ByeReason::unauthorised : link::ByeReason::protocol,
                  auth ? &counters_.refused.unauthorised : &counters_.refused.protocol);
}

template <link::LinkBody M>
void LinkAdmission::send_newcomer(const M& m) {
  std::array<std::byte, 128> frame{};
  const Result<std::size_t> n = link::encode_frame(m, frame);
  if (!n.ok()) return;
  const Result<std::size_t> sent =
      options_.newcomers->send_newcomer(std::span<const std::byte>(frame).first(*n));
  if (!sent.ok() || *sent != *n) ++counters_.send_errors;
}

void LinkAdmission::refuse_newcomer(link::ByeReason reason, std::uint64_t* counter) {
  if (counter != nullptr) ++*counter;
  send_newcomer(link::Bye{reason});
  options_.newcomers->refuse_newcomer();
  newcomer_.open = false;
}

bool LinkAdmission::refuse_if_busy() {
  if (!newcomer_.handshake.yield || !admitted()) return false;
  refuse_newcomer(link::ByeReason::busy, &counters_.refused.busy);
  return true;
}

void LinkAdmission::admit_spectator() {
  // Checked again after the challenge-response: a slot may have been taken meanwhile.
  if (!listener_.on_spectator(newcomer_.handshake.holds)) {
    refuse_newcomer(link::ByeReason::busy, &counters_.refused.full);
    return;
  }
  newcomer_.open = false;  // the transport moved it into a spectator slot
  ++counters_.spectators;
}

void LinkAdmission::admit_newcomer() {
  // Checked again after the challenge-response: a display may have come meanwhile.
  if (refuse_if_busy()) return;
  if (connected_) {
    // Tell the display why it goes, at a frame boundary of its stream: a 0x00 ends
    // any frame it has half received, then the bye follows.
    if (display_.admitted) ++counters_.displaced;
    replies_.interrupt_with(link::Bye{link::ByeReason::displaced});
  }
  options_.newcomers->admit_newcomer();
  newcomer_.open = false;
  const Handshake admitted = newcomer_.handshake;
  lose_display();
  connected_ = true;
  display_ = admitted;
  display_.admitted = true;
  ++counters_.connects;
  listener_.on_admitted(display_.holds);
}

}  // namespace twister::station
