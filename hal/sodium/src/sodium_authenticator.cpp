#include "twister/hal/sodium_authenticator.hpp"

#include <fcntl.h>
#include <sodium.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace twister::hal {
namespace {

constexpr char kLabel[] = "twister-link-2";
constexpr std::size_t kMaxKeyFile = 4096;

// The MAC's input: label, prover role, station nonce, bridge nonce.
using Transcript = std::array<std::uint8_t, sizeof kLabel - 1 + 1 + 2 * link::kNonceBytes>;

Transcript transcript(link::Role prover, const link::Nonce& s, const link::Nonce& b) {
  Transcript t{};
  std::size_t n = 0;
  for (std::size_t i = 0; i + 1 < sizeof kLabel; ++i) t[n++] = static_cast<std::uint8_t>(kLabel[i]);
  t[n++] = static_cast<std::uint8_t>(prover);
  for (const std::uint8_t x : s) t[n++] = x;
  for (const std::uint8_t x : b) t[n++] = x;
  return t;
}

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

Expected<std::string> read_private_file(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOCTTY | O_NONBLOCK);
  if (fd < 0) {
    return make_error(StatusCode::io_error,
                      "link key " + path + ": cannot open (" + std::strerror(errno) + ")");
  }
  struct stat st {};
  std::string error;
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    error = "is not a regular file";
  } else if ((st.st_mode & 077) != 0) {
    char mode[8];
    std::snprintf(mode, sizeof mode, "%04o", static_cast<unsigned>(st.st_mode & 07777));
    error = std::string("is accessible by group or others (mode ") + mode + "); chmod 600 it";
  } else if (st.st_size > static_cast<off_t>(kMaxKeyFile)) {
    error = "is larger than 4 KiB";
  }
  std::string text;
  if (error.empty()) {
    char buf[kMaxKeyFile + 1];
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n < 0) error = std::string("cannot be read (") + std::strerror(errno) + ")";
    if (n > 0) text.assign(buf, static_cast<std::size_t>(n));
  }
  ::close(fd);
  if (!error.empty())
    return make_error(StatusCode::failed_precondition, "link key " + path + " " + error);
  return text;
}

}  // namespace

Expected<LinkKey> load_link_key(const std::string& path) {
  Expected<std::string> text = read_private_file(path);
  if (!text) return text.error();
  std::string& t = *text;
  while (!t.empty() && (t.back() == '\n' || t.back() == '\r')) t.pop_back();
  LinkKey key{};
  bool hex = t.size() == 2 * kLinkKeyBytes;
  for (std::size_t i = 0; hex && i < kLinkKeyBytes; ++i) {
    const int hi = hex_value(t[2 * i]);
    const int lo = hex_value(t[2 * i + 1]);
    hex = hi >= 0 && lo >= 0;
    key[i] = static_cast<std::uint8_t>(hex ? hi * 16 + lo : 0);
  }
  sodium_memzero(t.data(), t.size());
  if (!hex) {
    return make_error(StatusCode::invalid_argument,
                      "link key " + path + " must hold 64 hex digits (32 bytes)");
  }
  return key;
}

Expected<void> SodiumAuthenticator::init() {
  if (sodium_init() < 0) return make_error(StatusCode::io_error, "libsodium failed to start");
  return {};
}

SodiumAuthenticator::SodiumAuthenticator(const LinkKey& key) : key_(key) {
  static_assert(crypto_auth_KEYBYTES == kLinkKeyBytes);
  static_assert(crypto_auth_BYTES == link::kAuthTagBytes);
}

SodiumAuthenticator::~SodiumAuthenticator() { sodium_memzero(key_.data(), key_.size()); }

link::Nonce SodiumAuthenticator::do_make_nonce() {
  link::Nonce n{};
  randombytes_buf(n.data(), n.size());
  return n;
}

link::AuthTag SodiumAuthenticator::do_tag(link::Role prover, const link::Nonce& station_nonce,
                                          const link::Nonce& bridge_nonce) const {
  const Transcript t = transcript(prover, station_nonce, bridge_nonce);
  link::AuthTag tag{};
  crypto_auth(tag.data(), t.data(), t.size(), key_.data());
  return tag;
}

bool SodiumAuthenticator::do_verify(link::Role prover, const link::Nonce& station_nonce,
                                    const link::Nonce& bridge_nonce,
                                    const link::AuthTag& tag) const {
  const Transcript t = transcript(prover, station_nonce, bridge_nonce);
  return crypto_auth_verify(tag.data(), t.data(), t.size(), key_.data()) == 0;
}

}  // namespace twister::hal
