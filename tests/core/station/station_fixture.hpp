// The Station tests' fixture: a scripted Fastrak responder on a FakeByteStream (answers
// `S`, streams records after `C`), the test configuration, a grid mesh and StationTest
// (scripted button edges, FakeStorage, virtual time).
#pragma once

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <memory>
#include <numbers>
#include <vector>

#include "fakes/fake_button_source.hpp"
#include "fakes/fake_byte_stream.hpp"
#include "fakes/fake_clock.hpp"
#include "fakes/fake_storage.hpp"
#include "support/allocation_counter.hpp"
#include "twister/journal/journal_reader.hpp"
#include "twister/station/station.hpp"
#include "twister/tracker/fastrak_encoder.hpp"

namespace twister::station {
namespace test_fixture {

using session::SessionEvent;
using session::SessionEventKind;
using tracker::Item;
constexpr double kInch = 0.0254;

// The device side: answers every `S` with a status reply matching the configuration
// and streams one record per receiver per tick once `C` has been seen.
class FastrakResponder {
 public:
  FastrakResponder(test::FakeByteStream& stream, const tracker::FastrakConfig& config)
      : stream_(stream), config_(config) {}

  void service() {
    const auto tx = stream_.tx();
    for (; seen_ < tx.size(); ++seen_) {
      const char c = tx[seen_];
      if (c == 'S') {
        std::array<std::byte, 64> buf{};
        tracker::FastrakStatus st{1, 0, config_.format == tracker::Format::binary, false, false};
        auto n = tracker::encode_status(st, buf);
        stream_.push_rx(std::span<const std::byte>(buf.data(), *n));
      } else if (c == 'C') {
        streaming_ = true;
      } else if (c == 'c') {
        streaming_ = false;
      }
    }
  }
  void emit(std::uint8_t station, std::array<float, 3> position_in, bool stylus = false,
            std::array<float, 4> quaternion = {1.0f, 0.0f, 0.0f, 0.0f}) {
    if (!streaming_ || !stream_.connected()) return;
    tracker::FastrakPose p{};
    p.station = station;
    p.has_position = true;
    p.position = position_in;
    p.has.quaternion = true;
    p.quaternion = quaternion;
    p.has_button = station == 1;
    p.button = stylus;
    std::array<std::byte, 256> buf{};
    auto n = tracker::encode_record(p, config_, buf);
    stream_.push_rx(std::span<const std::byte>(buf.data(), *n));
  }
  void unplugged() {
    streaming_ = false;
    seen_ = 0;
    stream_.clear_tx();
  }
  bool streaming() const { return streaming_; }

 private:
  test::FakeByteStream& stream_;
  tracker::FastrakConfig config_;
  std::size_t seen_ = 0;
  bool streaming_ = false;
};

StationConfig test_config() {
  StationConfig c{};
  auto& p = c.session.protocol;
  p.format = tracker::Format::binary;
  p.units = tracker::Units::inches;
  for (int s : {0, 1}) {
    p.stations[static_cast<std::size_t>(s)].enabled = true;
    p.stations[static_cast<std::size_t>(s)].list =
        tracker::OutputList::of({Item::position, Item::quaternion, Item::crlf});
  }
  p.stations[0].list =
      tracker::OutputList::of({Item::position, Item::quaternion, Item::stylus, Item::crlf});
  c.session.ladder_char_pause_us = 1'000;
  c.session.reset_wait_us = 1'000;
  c.session.settle_us = 1'000;
  c.session.reply_timeout_us = 50'000;
  c.session.command_pause_us = 1'000;
  c.session.silence_timeout_us = 100'000;
  c.session.backoff.initial_us = 10'000;
  c.session.backoff.max_us = 40'000;
  c.conversion.units = tracker::Units::inches;
  c.conversion.format = tracker::Format::binary;
  c.sculpt.debounce.interval_us.fill(5'000);
  return c;
}

// The paper map's lines the exhibit tests' new-sculpture chord holds.
constexpr std::uint8_t kLeftRadius = 1, kRightFreeze = 5;

// Exhibit mode as the exhibit tests run it: idle 20 s, grace 3 s, the chord (left
// radius + right freeze) held 1 s, a failed archive retried every 2 s.
inline StationConfig exhibit_test_config() {
  constexpr ports::TimestampUs kSecond = 1'000'000;
  StationConfig c = test_config();
  c.exhibit.visitor.enabled = true;
  c.exhibit.visitor.idle_us = 20 * kSecond;
  c.exhibit.visitor.grace_us = 3 * kSecond;
  c.exhibit.visitor.chord_hold_us = kSecond;
  c.exhibit.visitor.retry_us = 2 * kSecond;
  c.exhibit.chord_lines = (1u << kLeftRadius) | (1u << kRightFreeze);
  return c;
}

// 21 x 21 vertices over x in [0.1, 0.7] m, y in [-0.5, 0.1] m at z = 0.127 m (5 in):
// around the hands of the tests.
constexpr std::size_t kGridN = 21;
void make_grid(mesh::Mesh& m) {
  m.clear();
  for (std::size_t j = 0; j < kGridN; ++j) {
    for (std::size_t i = 0; i < kGridN; ++i) {
      const float x = 0.1f + 0.6f * static_cast<float>(i) / (kGridN - 1);
      const float y = -0.5f + 0.6f * static_cast<float>(j) / (kGridN - 1);
      ASSERT_TRUE(m.add_vertex({x, y, 0.127f}).ok());
    }
  }
  for (std::uint32_t j = 0; j + 1 < kGridN; ++j) {
    for (std::uint32_t i = 0; i + 1 < kGridN; ++i) {
      const std::uint32_t a = j * kGridN + i;
      ASSERT_TRUE(m.add_triangle(a, a + 1, a + kGridN).ok());
      ASSERT_TRUE(m.add_triangle(a + 1, a + kGridN + 1, a + kGridN).ok());
    }
  }
}

using TestMesh = mesh::MeshWithStorage<kGridN * kGridN, 2 * kGridN * kGridN>;
using TestWork = session::SculptStorageArrays<kGridN * kGridN, kGridN * kGridN, 8192, 16>;

class StationTest : public ::testing::Test {
 protected:
  StationTest()
      : config_(test_config()),
        responder_(stream_, config_.session.protocol),
        mesh_(initial_mesh()),
        station_(stream_, buttons_, clock_, storage_, *mesh_, work_->spans(), config_) {}

  static std::unique_ptr<TestMesh> initial_mesh() {
    auto m = std::make_unique<TestMesh>();
    make_grid(*m);
    return m;
  }

  // Advances virtual time in 8.33 ms ticks (the Fastrak cycle), emitting both hands.
  void run_ticks(int n) {
    for (int i = 0; i < n; ++i) {
      responder_.service();
      responder_.emit(1, left_in_, stylus_);
      responder_.emit(2, right_in_, false, right_q_);
      ASSERT_TRUE(station_.poll().ok());
      responder_.service();
      clock_.advance_us(8'333);
    }
  }
  void run_until_streaming() {
    for (int i = 0; i < 500 && !station_.tracker_session().streaming(); ++i) run_ticks(1);
    ASSERT_TRUE(station_.tracker_session().streaming());
    run_ticks(3);
  }
  std::vector<SessionEvent> events() {
    std::vector<SessionEvent> out;
    for (auto e = station_.next_event(); e.ok(); e = station_.next_event()) out.push_back(*e);
    return out;
  }
  std::vector<journal::JournalRecord> journal_records() {
    journal::JournalReader reader(storage_);
    EXPECT_TRUE(reader.open().ok());
    std::vector<journal::JournalRecord> out;
    for (auto r = reader.next(); r.ok(); r = reader.next()) out.push_back(*r);
    return out;
  }
  // Right hand (hand 1, paper default: line 3 = grab) drags from `from` to `to`.
  void right_stroke(std::array<float, 3> from, std::array<float, 3> to) {
    right_in_ = from;
    run_ticks(2);
    buttons_.press(3, true, clock_.now_us());
    run_ticks(3);  // debounce (5 ms) then grab_begin
    right_in_ = to;
    run_ticks(3);
    buttons_.press(3, false, clock_.now_us());
    run_ticks(3);
  }

  StationConfig config_;
  test::FakeByteStream stream_;
  test::FakeClock clock_{1'000'000};
  test::FakeStorageWithStorage<> storage_;
  test::FakeButtonSource buttons_;
  FastrakResponder responder_;
  std::unique_ptr<TestMesh> mesh_;
  std::unique_ptr<TestWork> work_ = std::make_unique<TestWork>();
  Station station_;
  bool stylus_ = false;
  std::array<float, 3> left_in_{-10.0f, 0.0f, 5.0f};
  std::array<float, 3> right_in_{10.0f, 0.0f, 5.0f};
  std::array<float, 4> right_q_{1.0f, 0.0f, 0.0f, 0.0f};  // w, x, y, z
};

}  // namespace test_fixture
}  // namespace twister::station
