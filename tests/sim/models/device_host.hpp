// The device-model tests' bench: a simulated unit with a host that writes at chosen
// times and reads every byte, in virtual time (1 ms steps).
#pragma once

#include <gtest/gtest.h>

#include <cstddef>
#include <string>
#include <vector>

#include "twister/sim/fastrak_device.hpp"
#include "twister/tracker/fastrak_parser.hpp"

namespace twister::sim::test {

inline Scenario scenario(const std::string& text) {
  Scenario sc;
  std::string err;
  EXPECT_TRUE(parse_scenario(text, sc, err)) << err;
  return sc;
}

struct DeviceHost {
  FastrakDevice device;
  ports::TimestampUs now = 0;
  std::vector<std::byte> out;

  DeviceHost(const std::string& text, const FastrakDeviceConfig& dev)
      : device(dev, scenario(text), 0) {}
  void send(const std::string& s) {
    device.receive(reinterpret_cast<const std::byte*>(s.data()), s.size(), now);
  }
  void run(double seconds) {
    const auto end = now + static_cast<ports::TimestampUs>(seconds * 1e6);
    while (now < end) {
      now += 1'000;
      device.advance(now, out);
    }
  }
  std::string text() const { return {reinterpret_cast<const char*>(out.data()), out.size()}; }
  // Every event a parser configured as `c` finds in what the unit sent.
  std::vector<tracker::FastrakEvent> events(const tracker::FastrakConfig& c) const {
    tracker::FastrakParser parser(c);
    std::vector<tracker::FastrakEvent> ev;
    parser.feed(out, [&](const tracker::FastrakEvent& e) { ev.push_back(e); });
    for (auto e = parser.finish(); e.ok(); e = parser.finish()) ev.push_back(*e);
    return ev;
  }
};

}  // namespace twister::sim::test
