// BridgeApp: the display's side of the link handshake (docs/link-protocol.md):
// hello on every connection and again while the station is silent, the
// challenge-response with a pre-shared key, yielding with back-off when another
// display took the link, and backing off for good when the station says
// unauthorised or speaks another protocol version.
#include <algorithm>

#include "bridge_app.hpp"

namespace twister::bridge {

using ports::LogLevel;

void BridgeApp::on_connect() {
  connected_ = true;
  station_stopped_ = false;
  ++counters_.connects;
  decoder_.clear();  // a fresh decoder per connection: no stale partial frame
  replica_.reconnected();
  send_hello();
  log_.write(LogLevel::notice, "link", "connected (holding mesh version %u)", {replica_.version()});
}

void BridgeApp::send_hello() {
  station_hello_ = false;
  ready_ = false;
  bridge_nonce_ =
      options_.authenticator != nullptr ? options_.authenticator->make_nonce() : link::Nonce{};
  const auto flags = static_cast<std::uint8_t>(
      (options_.authenticator != nullptr ? link::kHelloAuth : 0) |
      (yield_.active ? link::kHelloYield : 0) | (options_.spectator ? link::kHelloSpectator : 0));
  const link::Hello mine{link::Role::bridge, flags, replica_.version(), replica_.checksum(),
                         bridge_nonce_};
  send(mine);
  ++counters_.hellos_sent;
  hello_sent_ms_ = now_ms();
  last_frame_ms_ = hello_sent_ms_;
}

void BridgeApp::keep_alive() {
  // Resync by version after a silent station (restarted behind a serial line, or
  // our hello was lost): a new hello starts a new session.
  const std::int64_t now = now_ms();
  if (!station_hello_ && now - hello_sent_ms_ >= options_.hello_retry_ms) {
    send_hello();
  } else if (station_hello_ && now - last_frame_ms_ >= options_.silence_ms) {
    log_.write(LogLevel::warning, "link", "station silent for %lld ms; saying hello again",
               {static_cast<long long>(now - last_frame_ms_)});
    send_hello();
  }
}

void BridgeApp::on_station_hello(const link::Hello& hello) {
  if (hello.role != link::Role::station) return;
  station_hello_ = true;
  station_nonce_ = hello.nonce;
  const bool station_auth = (hello.flags & link::kHelloAuth) != 0;
  if (station_auth && options_.authenticator == nullptr) {
    log_.write(LogLevel::error, "link", "the station requires a pre-shared key (--link-key FILE)",
               {});
    stop(BridgeStop::unauthorised);
    return;
  }
  if (!station_auth && options_.authenticator != nullptr) {
    log_.write(LogLevel::error, "link",
               "the station does not authenticate but a key was given; not trusting it", {});
    stop(BridgeStop::unauthorised);
    return;
  }
  if (!station_auth) {
    admitted();
    return;
  }
  send(link::Auth{options_.authenticator->tag(link::Role::bridge, station_nonce_, bridge_nonce_)});
}

void BridgeApp::on_station_auth(const link::Auth& auth) {
  if (options_.authenticator == nullptr || !station_hello_ || ready_) return;
  if (!options_.authenticator->verify(link::Role::station, station_nonce_, bridge_nonce_,
                                      auth.tag)) {
    log_.write(LogLevel::error, "link", "the station failed authentication (wrong key?)", {});
    stop(BridgeStop::unauthorised);
    return;
  }
  log_.write(LogLevel::notice, "link", "station authenticated", {});
  admitted();
}

void BridgeApp::admitted() {
  ready_ = true;
  if (!yield_.active) return;
  yield_ = Yield{};
  log_.write(LogLevel::notice, "link", "the link was free again: this display has it back", {});
}

void BridgeApp::yield_link() {
  yield_.backoff_ms = yield_.active ? std::min(2 * yield_.backoff_ms, options_.yield_max_ms)
                                    : options_.yield_first_ms;
  yield_.active = true;
  yield_.retry_at_ms = now_ms() + yield_.backoff_ms;
  // The station closes this connection after its bye; the next try connects anew.
  connected_ = false;
  ready_ = false;
  out_.clear();
}

void BridgeApp::on_bye(const link::Bye& bye) {
  switch (bye.reason) {
    case link::ByeReason::displaced:
      ++counters_.displaced;
      yield_link();
      log_.write(LogLevel::warning, "link",
                 "displaced by another display; trying again in %lld s, taking the link only "
                 "when it is free (restart to take it back now)",
                 {static_cast<long long>(yield_.backoff_ms / 1000)});
      return;
    case link::ByeReason::busy:
      ++counters_.busy;
      yield_link();
      log_.write(LogLevel::info, "link", "another display holds the link; next try in %lld s",
                 {static_cast<long long>(yield_.backoff_ms / 1000)});
      return;
    case link::ByeReason::unauthorised:
      log_.write(LogLevel::error, "link", "the station refused this display: unauthorised", {});
      stop(BridgeStop::unauthorised);
      return;
    case link::ByeReason::shutdown:
      // The station is gone (on a serial line no hang-up follows): a disconnect.
      log_.write(LogLevel::notice, "link", "the station is shutting down", {});
      if (connected_) ++counters_.disconnects;
      connected_ = false;
      ready_ = false;
      station_stopped_ = true;
      return;
    case link::ByeReason::protocol:
    case link::ByeReason::timeout:
      log_.write(LogLevel::warning, "link", "the station ended the handshake (%s)",
                 {bye.reason == link::ByeReason::protocol ? "protocol" : "timeout"});
      return;
  }
}

void BridgeApp::stop(BridgeStop why) {
  stop_ = why;
  ready_ = false;
  out_.clear();
}

}  // namespace twister::bridge
