// LinkAdmission: who the display is. Reads the display's channel and, on a
// listening transport (ports::LinkNewcomers), the newcomer's; runs each one's
// handshake (hello, and the pre-shared-key challenge-response when an
// authenticator is given); admits, displaces (bye: displaced) and refuses
// (unauthorised, protocol, another version, timeout; busy: a displaced display's
// yielding hello while another display holds the link, or a spectator while every
// spectator slot is taken); a newcomer whose hello carries kHelloSpectator is
// authenticated the same way and then handed to the listener as a spectator: it
// displaces nobody (issue 25). A fresh decoder per
// connection. An admitted display's other requests (resend, commands) go to the
// listener, and so do admission and loss. Replies to the display go on the urgent
// queue; the newcomer's are sent straight to it. No heap. Not thread-safe.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "twister/link/link_authenticator.hpp"
#include "twister/link/link_codec.hpp"
#include "twister/ports/clock.hpp"
#include "twister/ports/link_newcomers.hpp"
#include "twister/ports/link_port.hpp"
#include "twister/ports/link_spectators.hpp"
#include "twister/station/station_link_queues.hpp"

namespace twister::station {

// Optional capabilities: newcomer admission (listening transports) and the
// pre-shared-key handshake. Both must outlive the link.
struct StationLinkOptions {
  ports::LinkNewcomers* newcomers = nullptr;
  link::LinkAuthenticator* authenticator = nullptr;
  // Spectators (issue 25): read-only displays in up to max_spectators slots of a
  // transport that offers them (with newcomers). spectator_queues: every slot's bulk
  // queue (split evenly, at least 4 * link::kMaxFrameBytes each); spectator_staging:
  // where a commit's change set is encoded for them when the main display was not
  // sent it (empty: a full send instead). A spectator that takes no byte for
  // spectator_stall_us is dropped.
  ports::LinkSpectators* spectators = nullptr;
  std::size_t max_spectators = 0;
  std::span<std::byte> spectator_queues{};
  std::span<std::byte> spectator_staging{};
  ports::TimestampUs spectator_stall_us = 5'000'000;
};

// The mesh a peer holds (or the station offers): version and checksum.
struct MeshIdentity {
  std::uint32_t version = 0;
  std::uint64_t checksum = 0;
  bool operator==(const MeshIdentity&) const = default;
};

// Peers the handshake turned away, by why (busy is no error: a displaced display
// asked while another held the link).
struct LinkRefusals {
  std::uint64_t unauthorised = 0;  // wrong or missing tag
  std::uint64_t protocol = 0;      // wrong role, order or message
  std::uint64_t version = 0;       // another protocol version
  std::uint64_t timeout = 0;       // handshake not finished in time
  std::uint64_t busy = 0;          // a yielding display while another holds the link
  std::uint64_t full = 0;          // a spectator while every spectator slot is taken
  // The refusals that are errors (all but busy and full).
  std::uint64_t errors() const { return unauthorised + protocol + version + timeout; }
};

struct AdmissionCounters {
  std::uint64_t connects = 0;         // displays admitted
  std::uint64_t disconnects = 0;      // display channel lost
  std::uint64_t resend_requests = 0;  // from the admitted display
  std::uint64_t newcomers = 0;        // peers that arrived on the newcomer channel
  std::uint64_t displaced = 0;        // displays told "displaced" by an admitted newcomer
  std::uint64_t spectators = 0;       // newcomers admitted as spectators
  LinkRefusals refused{};
  std::uint64_t commands_refused = 0;  // a command from a peer not admitted
  std::uint64_t send_errors = 0;       // newcomer replies the port did not take
};

// What the admitted display asks for, and when it comes and goes.
class AdmissionListener {
 public:
  // A display was admitted holding `holds` (resync by version).
  virtual void on_admitted(const MeshIdentity& holds) = 0;
  // The display's channel closed or another display took it: drop what was queued.
  virtual void on_display_lost() = 0;
  virtual void on_resend_request() = 0;
  virtual void on_command(const link::Command& command) = 0;
  // The mesh the station offers, for its hello (asked only when a hello arrives).
  virtual MeshIdentity offered() = 0;
  // Spectators (issue 25): is a slot free; the authenticated newcomer holding
  // `holds` becomes a spectator (false: it could not, it is refused); the display on
  // the main channel said kHelloSpectator and sent a command (refused).
  virtual bool spectator_room() { return false; }
  virtual bool on_spectator(const MeshIdentity& holds) {
    (void)holds;
    return false;
  }
  virtual void on_spectator_command() {}

 protected:
  ~AdmissionListener() = default;
};

class LinkAdmission {
 public:
  LinkAdmission(ports::LinkPort& port, FrameQueues& replies, AdmissionListener& listener,
                const StationLinkOptions& options, ports::TimestampUs handshake_timeout_us)
      : port_(port),
        replies_(replies),
        listener_(listener),
        options_(options),
        handshake_timeout_us_(handshake_timeout_us) {}

  // Reads both channels (never blocks).
  void poll(ports::TimestampUs now_us);

  bool connected() const { return connected_; }
  bool admitted() const { return connected_ && display_.admitted; }
  const AdmissionCounters& counters() const { return counters_; }
  link::DecoderCounters decoder_counters() const { return decoder_.counters(); }
  // The version byte of the last peer refused for speaking another protocol (0: none).
  std::uint8_t refused_version() const { return refused_version_; }

 private:
  // One connection's handshake (display channel or newcomer channel).
  struct Handshake {
    bool hello = false;      // the bridge's hello arrived
    bool admitted = false;   // hello (and auth) done: it is the display
    bool yield = false;      // its hello said kHelloYield
    bool spectator = false;  // its hello said kHelloSpectator: read-only
    link::Nonce station_nonce{};
    link::Nonce bridge_nonce{};
    MeshIdentity holds{};
    ports::TimestampUs since_us = 0;
  };
  // The newcomer channel: its own decoder and handshake.
  struct Newcomer {
    link::LinkDecoder decoder;
    Handshake handshake{};
    std::uint64_t id = 0;
    bool open = false;
  };

  void receive(ports::TimestampUs now_us);
  void lose_display();
  void on_display_message(const link::LinkMessage& m);
  void on_display_hello(const link::Hello& hello);
  void poll_newcomer(ports::TimestampUs now_us);
  void on_newcomer_message(const link::LinkMessage& m);
  // Tells the newcomer why (bye) and closes it; `counter` (may be null) counts it.
  void refuse_newcomer(link::ByeReason reason, std::uint64_t* counter);
  void admit_newcomer();
  // The authenticated newcomer becomes a spectator (or is refused: no slot).
  void admit_spectator();
  // A yielding newcomer while an admitted display holds the link: bye: busy.
  bool refuse_if_busy();
  // Starts a handshake on `hello`; returns the station's hello to send back.
  link::Hello begin_handshake(Handshake& hs, const link::Hello& hello);
  bool check_auth(const Handshake& hs, const link::Auth& auth) const;
  link::Auth station_auth(const Handshake& hs) const;
  // Encodes `m` and hands it straight to the newcomer (small handshake frames).
  template <link::LinkBody M>
  void send_newcomer(const M& m);
  void refuse_version(link::LinkDecoder& decoder);

  ports::LinkPort& port_;
  FrameQueues& replies_;
  AdmissionListener& listener_;
  StationLinkOptions options_;
  ports::TimestampUs handshake_timeout_us_;
  link::LinkDecoder decoder_;  // the display channel's
  Handshake display_{};
  bool connected_ = false;
  Newcomer newcomer_{};
  std::uint8_t refused_version_ = 0;
  AdmissionCounters counters_{};
};

}  // namespace twister::station
