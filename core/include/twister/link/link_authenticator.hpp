// LinkAuthenticator: the pre-shared-key challenge-response of the link handshake
// (docs/link-protocol.md "Authentication"). Each side sends a fresh nonce in its
// hello; the bridge proves it holds the key with tag(bridge, Ns, Nb), then the
// station with tag(station, Ns, Nb); the role byte in the MAC's input keeps a tag
// from being reflected. The MAC and the random numbers come from a vetted library
// behind this interface (hal/sodium: libsodium crypto_auth, HMAC-SHA-512-256), so
// core holds no cryptography. Implementations must not allocate after construction.
#pragma once

#include <array>
#include <cstdint>

#include "twister/link/link_message.hpp"

namespace twister::link {

using Nonce = std::array<std::uint8_t, kNonceBytes>;
using AuthTag = std::array<std::uint8_t, kAuthTagBytes>;

class LinkAuthenticator {
 public:
  virtual ~LinkAuthenticator() = default;

  // A fresh unpredictable nonce (one per handshake).
  Nonce make_nonce() { return do_make_nonce(); }
  // MAC(key, "twister-link-2" || prover || station nonce || bridge nonce).
  AuthTag tag(Role prover, const Nonce& station_nonce, const Nonce& bridge_nonce) const {
    return do_tag(prover, station_nonce, bridge_nonce);
  }
  // Constant-time check of a tag the peer sent.
  bool verify(Role prover, const Nonce& station_nonce, const Nonce& bridge_nonce,
              const AuthTag& tag) const {
    return do_verify(prover, station_nonce, bridge_nonce, tag);
  }

 private:
  virtual Nonce do_make_nonce() = 0;
  virtual AuthTag do_tag(Role prover, const Nonce& station_nonce,
                         const Nonce& bridge_nonce) const = 0;
  virtual bool do_verify(Role prover, const Nonce& station_nonce, const Nonce& bridge_nonce,
                         const AuthTag& tag) const = 0;
};

}  // namespace twister::link
