// The link's byte budget (issue 14, label display): a two-hand live update fits
// 128 bytes on the wire, and the station->display stream of a two-hand drag fits a
// 230 400-baud serial line.
#include <gtest/gtest.h>

#include <cstdio>

#include "twister/link/link_codec.hpp"

namespace twister::link {
namespace {

// Issue 14: a two-hand live update is at most 128 bytes on the wire, and the whole
// stream of a two-hand drag fits a 230 400-baud line (8N1: 23 040 bytes/s).
TEST(LinkCodec, TwoHandLiveUpdateFitsTheBudget) {
  Hands m;
  m.sequence = 0xffff;
  m.stroke = 0xffff;
  m.flags = kHandSample0 | kHandSample1 | kHandTracked0 | kHandTracked1 | kStrokeActive;
  m.buttons = 0xff;
  m.radius_m = 0.25F;
  for (auto& h : m.hands) {
    h.position = {0.55F, -0.123F, 0.1F};
    h.rotation = {0.7071068F, 0.0F, -0.7071068F, 0.0F};
  }
  const std::size_t bytes = frame_size(m);
  std::printf("two-hand live update: %zu bytes on the wire\n", bytes);
  EXPECT_LE(bytes, 128u);
  EXPECT_EQ(bytes, kHandsFrameBytes);
  const StatusReport status;
  StrokeBegin stroke;
  stroke.hand_mask = 3;
  stroke.radius_m = 0.25;
  // 120 updates/s, status and the stroke repeat once a second.
  const double per_second = 120.0 * static_cast<double>(bytes) +
                            static_cast<double>(frame_size(status) + frame_size(stroke));
  std::printf("two-hand drag stream: %.0f bytes/s of 23040 at 230400 baud (%.0f %%)\n", per_second,
              100.0 * per_second / 23040.0);
  EXPECT_LT(per_second, 23040.0);
}

}  // namespace
}  // namespace twister::link
