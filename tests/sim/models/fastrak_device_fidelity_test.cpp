// The device model where it fails or behaves like a real unit (issue 15), in virtual
// time: adaptive filters (lag against the manual's equation E-2, read-back record,
// macros, `x1`), command processing times (early commands lost), the 16-bit packed
// format, status letters, in-record corruption, the drop budget's expiry and a host
// at the wrong baud.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "device_host.hpp"

namespace twister::sim {
namespace {

using tracker::EventKind;
using tracker::FastrakEvent;
using tracker::Format;
using tracker::Item;
using tracker::OutputList;

// The unit with a host that writes commands at given times and reads every byte.
struct Bench : test::DeviceHost {
  explicit Bench(const std::string& text, const FastrakDeviceConfig& dev = instant_device())
      : DeviceHost(text, dev) {}
  static FastrakDeviceConfig instant_device() {
    FastrakDeviceConfig d;
    d.reset_time_us = 0;
    d.command_time_us = instant_commands();  // commands in one write (timing: its own test)
    return d;
  }
};

tracker::FastrakConfig one_station(Format f, OutputList l) {
  tracker::FastrakConfig c;
  c.format = f;
  c.stations[0] = {true, l};
  return c;
}

const OutputList kPosQuat = OutputList::of({Item::position, Item::quaternion, Item::crlf});

// x ramps at 6 in/s from t = 1 s; one receiver: 120 records per second.
constexpr const char* kRamp = "receivers 1\nkey 1 1 10 0 0 0 0 0\nkey 11 1 70 0 0 0 0 0\n";

// x of record k of a run with `filter` (binary, one receiver, kRamp).
std::vector<double> ramp_run(const std::string& filter, double seconds = 5.0) {
  Bench b(kRamp);
  b.send("O1,2,11,1\r" + filter + "fC");
  b.run(seconds);
  std::vector<double> x;
  for (const auto& e : b.events(one_station(Format::binary, kPosQuat))) {
    EXPECT_EQ(e.kind, EventKind::pose);
    x.push_back(e.pose.position[0]);
  }
  return x;
}

// Mean lag (unfiltered - filtered) over records [from, to) of the ramp.
double mean_lag(const std::vector<double>& off, const std::vector<double>& on, std::size_t from,
                std::size_t to) {
  double sum = 0.0;
  for (std::size_t k = from; k < to; ++k) sum += off[k] - on[k];
  return sum / static_cast<double>(to - from);
}

TEST(FastrakDeviceFilter, RampLagMatchesTheManualsSteadyStateEquation) {
  const auto off = ramp_run("x,1\r");
  // FLOW 0.25 .. FHIGH 0.26 pins the pole a: lag = v T (1 - a) / a (manual E-2).
  const auto on = ramp_run("x0.5,0.25,0.26,0.9\r");
  ASSERT_EQ(off.size(), on.size());
  ASSERT_GT(off.size(), 590u);
  const double v_t = 6.0 / 120.0;  // inches per record
  const double lag = mean_lag(off, on, 300, 580);
  std::printf(
      "[filter] ramp 6 in/s at 120 Hz, a in [0.25, 0.26]: lag %.4f in (%.1f ms); "
      "E-2: %.4f..%.4f in\n",
      lag, lag / 6.0 * 1000.0, v_t * 0.74 / 0.26, v_t * 0.75 / 0.25);
  EXPECT_GT(lag, v_t * 0.74 / 0.26 - 0.001);
  EXPECT_LT(lag, v_t * 0.75 / 0.25 + 0.001);
  // Before the ramp both runs sit still and agree.
  EXPECT_NEAR(mean_lag(off, on, 10, 100), 0.0, 1e-6);
}

TEST(FastrakDeviceFilter, MacrosLagInOrderAndOffHasNone) {
  const auto off = ramp_run("x,1\r");
  const double low = mean_lag(off, ramp_run("x3\r"), 300, 580);
  const double medium = mean_lag(off, ramp_run("x4\r"), 300, 580);
  const double heavy = mean_lag(off, ramp_run("x5\r"), 300, 580);
  std::printf("[filter] lag at 6 in/s: low %.4f, medium %.4f, heavy %.4f in\n", low, medium, heavy);
  EXPECT_GT(low, 0.0);
  EXPECT_GT(medium, low);
  EXPECT_GT(heavy, medium);
}

TEST(FastrakDeviceFilter, QueryFormsAndBadValuesGetTheirReplies) {
  Bench b("receivers 1\n");
  b.send("x\r");
  b.run(0.01);
  // '2', blank, 'x', four bSx.xxx fields (the power-up state: FLOW 1 = off), CR LF.
  EXPECT_EQ(b.text(), "2 x  0.200  1.000  0.800  0.950\r\n");
  b.out.clear();
  b.send("x.2,.2,.8,.95\rv4\rv\rx1\rx0.5,0.9,0.8\r");
  b.run(0.05);
  const std::string t = b.text();
  EXPECT_NE(t.find("2 v  0.200  0.200  0.800  0.950\r\n"), std::string::npos) << t;
  EXPECT_NE(t.find("2 E*ERROR* x1 *ERROR* EC -3"), std::string::npos) << t;  // neither macro nor F
  EXPECT_NE(t.find("2 E*ERROR* x0.5,0.9,0.8 *ERROR* EC -3"), std::string::npos)
      << t;                                         // FLOW > FHIGH
  EXPECT_EQ(b.device.position_filter().flow, 0.2);  // v4 set both; the bad x changed nothing
}

TEST(FastrakDeviceTiming, CommandsSentTooEarlyAreLost) {
  FastrakDeviceConfig dev = Bench::instant_device();
  dev.command_time_us = default_command_times();
  dev.input_buffer_bytes = 0;  // a unit without an input buffer (the default has one)
  Bench b("receivers 1\n", dev);
  // Back to back: the read-back arrives while `O` is processed and is lost.
  b.send("O1,2,11,1\rO1\r");
  b.run(0.2);
  EXPECT_EQ(b.text(), "");
  EXPECT_EQ(b.device.counters().input_lost, 3u);
  // After 40 ms it is heard; `x` keeps the unit busy 500 ms, and its reply waits.
  b.send("O1\r");
  b.run(0.05);
  EXPECT_EQ(b.text(), "21O 211 1\r\n");  // one 2-character field per item
  b.out.clear();
  b.send("x\r");
  b.run(0.49);
  EXPECT_EQ(b.text(), "");
  b.run(0.02);
  EXPECT_EQ(b.text().substr(0, 3), "2 x");
}

TEST(FastrakDevicePacked16, SmallFSelectsThePackedFormatOnAnIsotrakStyleUnit) {
  FastrakDeviceConfig dev = Bench::instant_device();
  dev.packed16 = true;
  Bench b(kRamp, dev);
  b.send("O1,2,11\rfSC");
  b.run(1.0);
  const auto ev =
      b.events(one_station(Format::binary16, OutputList::of({Item::position, Item::quaternion})));
  ASSERT_GT(ev.size(), 100u);
  EXPECT_EQ(ev[0].kind, EventKind::status);
  EXPECT_TRUE(ev[0].status.binary);
  for (std::size_t k = 1; k < ev.size(); ++k) {
    ASSERT_EQ(ev[k].kind, EventKind::pose) << k;
    EXPECT_NEAR(ev[k].pose.position[0], 10.0, 0.002);
  }
  EXPECT_EQ(b.out.size() - 55, 20u * (ev.size() - 1));  // 20 wire bytes per record
}

TEST(FastrakDeviceStatus, EnvelopeAndScriptedLettersSetTheStatusByte) {
  Bench b("receivers 2\nkey 0 1 10 0 0 30 0 0\nkey 0 2 10 5 0 0 0 0\nstatus 0.5 2 E 0.5\n");
  b.send("O1,2,4,1\rO2,2,4,1\rQ1,20,90,180,-180,-90,-180\rC");  // az max 20: station 1 is out
  b.run(1.5);
  tracker::FastrakConfig c = one_station(
      Format::ascii, tracker::OutputList::of({Item::position, Item::euler, Item::crlf}));
  c.stations[1] = c.stations[0];
  int y = 0, e_inside = 0, e_outside = 0, poses = 0;
  const auto ev = b.events(c);
  for (std::size_t k = 0; k < ev.size(); ++k) {
    ASSERT_EQ(ev[k].kind, EventKind::pose);
    ++poses;
    const char s = ev[k].pose.status;
    if (ev[k].pose.station == 1) y += s == 'y';
    if (ev[k].pose.station == 2 && s == 'E') ++e_inside;
    if (ev[k].pose.station == 2 && s != 'E' && s != ' ') ++e_outside;
  }
  EXPECT_NEAR(y, poses / 2, 1);  // every station-1 record
  EXPECT_NEAR(e_inside, 30, 1);  // 0.5 s at 60 Hz
  EXPECT_EQ(e_outside, 0);
}

TEST(FastrakDeviceCorruption, CorruptedRecordsKeepTheirFraming) {
  for (const Format f : {Format::ascii, Format::binary, Format::binary16}) {
    FastrakDeviceConfig dev = Bench::instant_device();
    dev.packed16 = f == Format::binary16;
    // A still hand with no zero value (a sign flip of 0 would change nothing).
    Bench b("receivers 1\nkey 0 1 10 -4 2 30 20 10\nfault 0.5 corrupt 100\n", dev);
    b.send(f == Format::ascii ? "O1,2,11,1\rC" : "O1,2,11,1\rfC");
    b.run(2.0);
    tracker::FastrakConfig c = one_station(f, kPosQuat);
    const auto ev = b.events(c);
    ASSERT_GT(ev.size(), 10u);
    ASSERT_EQ(ev[0].kind, EventKind::pose);
    const tracker::FastrakPose clean = ev[0].pose;  // before the fault
    int poses = 0, errors = 0, wrong = 0;
    for (const auto& e : ev) {
      ASSERT_NE(e.kind, EventKind::resync) << "framing noticed corruption";
      errors += e.kind == EventKind::error;
      if (e.kind == EventKind::pose) {
        ++poses;
        wrong += e.pose.position != clean.position || e.pose.quaternion != clean.quaternion;
      }
    }
    std::printf(
        "[corrupt %d] 100 corrupted of %d records: plausibility rejects %d, "
        "plausible but wrong %d, framing 0\n",
        static_cast<int>(f), poses + errors, errors, wrong);
    EXPECT_EQ(b.device.counters().corrupted_records, 100u);
    EXPECT_EQ(errors + wrong, 100);
  }
}

TEST(FastrakDeviceDrop, BudgetExpiresWhenTheHostStopsTheStreamOrResets) {
  Bench b("receivers 1\nfault 0.5 drop 100000\n");
  b.send("C");
  b.run(1.0);
  const auto eaten = b.device.counters().dropped_bytes;
  EXPECT_GT(eaten, 1000u);
  b.send("c");  // the host stops the stream, as a session does on silence
  b.run(0.1);
  b.out.clear();
  b.send("S");
  b.run(0.1);
  EXPECT_EQ(b.text().size(), 55u);  // the status reply is not eaten
  EXPECT_EQ(b.device.counters().drop_expired, 100000u - eaten);
  // A budget also expires by itself a second after its bytes' transmission time.
  Bench idle("receivers 1\nfault 0.1 drop 50\n");
  idle.run(1.5);
  idle.send("S");
  idle.run(0.1);
  EXPECT_EQ(idle.text().size(), 55u);
}

TEST(FastrakDeviceBaud, MismatchIsMostlySilenceWithNothingParseable) {
  Bench b("receivers 2\n");
  b.device.set_host_baud(19200);
  b.send("C");  // garbled: most bytes of a command vanish; the unit stays polled
  b.device.set_host_baud(115200);
  b.send("C");
  b.run(0.5);
  const auto sent = b.out.size();
  b.out.clear();
  b.device.set_host_baud(19200);
  b.run(2.0);
  const auto& c = b.device.counters();
  std::printf("[baud] 2 s at 19200 vs 115200: %zu junk bytes of %llu sent (%.1f%%)\n", b.out.size(),
              static_cast<unsigned long long>(c.misclock_lost + c.misclock_junk),
              100.0 * static_cast<double>(b.out.size()) /
                  static_cast<double>(c.misclock_lost + c.misclock_junk));
  EXPECT_GT(sent, 0u);
  EXPECT_GT(b.out.size(), 0u);
  EXPECT_LT(b.out.size() * 8, c.misclock_lost);  // mostly silence
  tracker::FastrakConfig pc =
      one_station(Format::ascii, OutputList::of({Item::position, Item::euler, Item::crlf}));
  pc.stations[1] = pc.stations[0];
  for (const auto& e : b.events(pc)) EXPECT_EQ(e.kind, EventKind::resync);
}

}  // namespace
}  // namespace twister::sim
