// hal/sodium: the link key file is refused unless it is a private regular file of
// 64 hex digits; tags verify only with the same key, role and nonces.
#include "twister/hal/sodium_authenticator.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fstream>
#include <string>

namespace twister::hal {
namespace {

std::string write_key(const char* name, const std::string& text, mode_t mode) {
  const std::string path = "/tmp/twister_key_" + std::to_string(::getpid()) + "_" + name;
  { std::ofstream(path) << text; }
  ::chmod(path.c_str(), mode);
  return path;
}

const std::string kHex = "00112233445566778899aabbccddeeff00112233445566778899AABBCCDDEEFF";

TEST(LinkKey, PrivateHexFileLoadsAndEverythingElseIsRefused) {
  const std::string good = write_key("good", kHex + "\n", 0600);
  const auto key = load_link_key(good);
  ASSERT_TRUE(key) << key.error().message;
  EXPECT_EQ((*key)[1], 0x11);
  EXPECT_EQ((*key)[31], 0xff);
  const std::string shared = write_key("shared", kHex, 0640);
  const auto open_key = load_link_key(shared);
  ASSERT_FALSE(open_key);
  EXPECT_NE(open_key.error().message.find("chmod 600"), std::string::npos)
      << open_key.error().message;
  const std::string short_key = write_key("short", "abcd\n", 0600);
  EXPECT_FALSE(load_link_key(short_key));
  const std::string not_hex = write_key("nothex", std::string(64, 'g'), 0600);
  EXPECT_FALSE(load_link_key(not_hex));
  EXPECT_FALSE(load_link_key("/tmp"));                  // not a regular file
  EXPECT_FALSE(load_link_key("/nonexistent/key.hex"));  // missing
  for (const auto& p : {good, shared, short_key, not_hex}) ::unlink(p.c_str());
}

TEST(LinkKey, TagsVerifyOnlyWithTheSameKeyRoleAndNonces) {
  ASSERT_TRUE(SodiumAuthenticator::init());
  LinkKey k1{};
  LinkKey k2{};
  k2[0] = 1;
  SodiumAuthenticator a(k1);
  SodiumAuthenticator b(k1);
  SodiumAuthenticator other(k2);
  const link::Nonce ns = a.make_nonce();
  const link::Nonce nb = b.make_nonce();
  EXPECT_NE(ns, nb);
  const link::AuthTag tag = a.tag(link::Role::bridge, ns, nb);
  EXPECT_TRUE(b.verify(link::Role::bridge, ns, nb, tag));
  EXPECT_FALSE(b.verify(link::Role::station, ns, nb, tag));  // no reflection
  EXPECT_FALSE(b.verify(link::Role::bridge, nb, ns, tag));
  EXPECT_FALSE(other.verify(link::Role::bridge, ns, nb, tag));
}

}  // namespace
}  // namespace twister::hal
