// SodiumAuthenticator: link::LinkAuthenticator with libsodium: crypto_auth
// (HMAC-SHA-512-256, 32-byte key and tag, constant-time verify) and
// randombytes_buf for the nonces. The key comes from a file (load_link_key) and
// is never part of a config. No allocation after construction.
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "twister/hal/expected.hpp"
#include "twister/link/link_authenticator.hpp"

namespace twister::hal {

inline constexpr std::size_t kLinkKeyBytes = 32;
using LinkKey = std::array<std::uint8_t, kLinkKeyBytes>;

// Reads a link key file: 64 hex digits (32 bytes), optional trailing newline
// (make one with `openssl rand -hex 32 > FILE` or `od -An -tx1 -N32 /dev/urandom |
// tr -d ' \n' > FILE`). Refused: not a regular file, readable or writable by group
// or others (chmod 600), larger than 4 KiB, or not 64 hex digits. Errors name the
// path and say which rule failed.
Expected<LinkKey> load_link_key(const std::string& path);

class SodiumAuthenticator final : public link::LinkAuthenticator {
 public:
  explicit SodiumAuthenticator(const LinkKey& key);
  ~SodiumAuthenticator() override;

  // sodium_init(); io_error when libsodium cannot start (no entropy source).
  static Expected<void> init();

 private:
  link::Nonce do_make_nonce() override;
  link::AuthTag do_tag(link::Role prover, const link::Nonce& station_nonce,
                       const link::Nonce& bridge_nonce) const override;
  bool do_verify(link::Role prover, const link::Nonce& station_nonce,
                 const link::Nonce& bridge_nonce, const link::AuthTag& tag) const override;

  LinkKey key_;
};

}  // namespace twister::hal
