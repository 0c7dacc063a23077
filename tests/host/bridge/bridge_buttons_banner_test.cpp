// Issue 23: the display says when the station's button device is missing. A status
// (protocol 4) with buttons_state missing, encoded and decoded by the link codec,
// applied to the replica: the HUD shows the "BUTTONS MISSING" banner and says so in
// the tracker line; it goes when the buttons are back; a lost tracker or link is
// more urgent (label devices).
#include <gtest/gtest.h>

#include <vector>

#include "hud_model.hpp"
#include "twister/link/link_codec.hpp"

namespace twister::bridge {
namespace {

// The status as the bridge receives it: through a frame of the link codec.
link::LinkMessage over_the_wire(const link::StatusReport& s) {
  std::vector<std::byte> frame(link::kMaxFrameBytes);
  const auto n = link::encode_frame(s, frame);
  EXPECT_TRUE(n.ok());
  std::vector<std::byte> buffer(link::kMaxFrameBytes);
  link::FrameDecoder decoder(buffer);
  link::LinkMessage m;
  for (std::size_t i = 0; i < *n; ++i) {
    if (const auto payload = decoder.process(frame[i]); payload.ok()) {
      EXPECT_TRUE(link::decode_payload(*payload, m).ok());
    }
  }
  return m;
}

link::StatusReport status(link::TrackerState tracker, link::ButtonsState buttons) {
  link::StatusReport s;
  s.tracker_state = static_cast<std::uint8_t>(tracker);
  s.buttons_state = static_cast<std::uint8_t>(buttons);
  s.vertex_count = 10;
  s.vertex_capacity = 100;
  return s;
}

bool has_line(const HudText& t, const std::string& what) {
  for (const std::string& l : t.lines) {
    if (l.find(what) != std::string::npos) return true;
  }
  return false;
}

TEST(ButtonsBanner, AMissingButtonDeviceShowsTheBannerUntilItIsBack) {
  SceneReplica r;
  HudModel hud;
  HudInput in;
  in.link = LinkView::connected;
  in.ready = true;
  (void)r.apply(over_the_wire(status(link::TrackerState::streaming, link::ButtonsState::present)));
  HudText t = hud.update(r, in);
  EXPECT_EQ(t.banner, "");
  EXPECT_TRUE(has_line(t, "buttons: present"));

  (void)r.apply(over_the_wire(status(link::TrackerState::streaming, link::ButtonsState::missing)));
  t = hud.update(r, in);
  EXPECT_EQ(t.banner, "BUTTONS MISSING");
  EXPECT_NE(t.detail.find("picks it up"), std::string::npos) << t.detail;
  EXPECT_TRUE(has_line(t, "buttons: MISSING"));

  (void)r.apply(over_the_wire(status(link::TrackerState::lost, link::ButtonsState::missing)));
  EXPECT_EQ(hud.update(r, in).banner, "TRACKER LOST");  // more urgent
  in.link = LinkView::lost;
  EXPECT_EQ(hud.update(r, in).banner, "LINK LOST");
  in.link = LinkView::connected;

  (void)r.apply(over_the_wire(status(link::TrackerState::streaming, link::ButtonsState::present)));
  t = hud.update(r, in);
  EXPECT_EQ(t.banner, "");
  EXPECT_TRUE(has_line(t, "buttons: present"));
}

TEST(ButtonsBanner, AnUnknownButtonsStateMakesTheStatusInvalid) {
  link::StatusReport s = status(link::TrackerState::streaming, link::ButtonsState::present);
  s.buttons_state = 2;
  std::vector<std::byte> frame(link::kMaxFrameBytes);
  const auto n = link::encode_frame(s, frame);
  ASSERT_TRUE(n.ok());
  std::vector<std::byte> buffer(link::kMaxFrameBytes);
  link::FrameDecoder decoder(buffer);
  link::LinkMessage m;
  bool refused = false;
  for (std::size_t i = 0; i < *n; ++i) {
    if (const auto payload = decoder.process(frame[i]); payload.ok()) {
      refused = !link::decode_payload(*payload, m).ok();
    }
  }
  EXPECT_TRUE(refused);
}

}  // namespace
}  // namespace twister::bridge
