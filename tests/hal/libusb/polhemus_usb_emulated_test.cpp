// The station's USB tracker backend (LibusbByteStream as make_backends builds it, with
// real libusb) driven by the station's tracker session (FastrakSession, set up by
// make_station_setup with the station's own timings) against Polhemus trackers emulated
// at the kernel interface: umockdev provides each unit's sysfs entry (idVendor /
// idProduct in its descriptors) and /dev/bus/usb/001/NNN, and routes the usbdevfs
// ioctls libusb issues (SUBMITURB, REAPURB(NDELAY), DISCARDURB, claim, ...) to the
// in-process handler (fake_polhemus.hpp; the rig: polhemus_usb_rig.hpp). The emulated unit answers
// the start-up (the status record for `S`) and, after `C`, streams records written by core's
// encoders (Fastrak records for a FASTRAK / FASTRAK 3, Liberty-family frames for a Liberty, Patriot
// or Latus), with noise between them. Label devices. Run under umockdev's preload (CMake sets
// LD_PRELOAD) and, in CTest, a timeout.
//
// What this does not show (needs a unit): the endpoints a real FASTRAK uses (the
// emulated FASTRAKs offer 0x02 / 0x82 to show they are taken from the descriptor), the
// real units' replies to the start-up beyond the status record, their timing, and
// firmware loading itself.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#if defined(__SANITIZE_ADDRESS__)
#include <sanitizer/lsan_interface.h>
#endif

#include "fakes/fake_storage.hpp"
#include "hal/libusb/polhemus_usb_rig.hpp"
#include "station_assembly.hpp"
#include "station_loop.hpp"
#include "station_memory.hpp"

// ASan builds: umockdev's LD_PRELOAD library loads before the ASan runtime, which
// ASan refuses by default; the order is harmless here. Unused in other builds.
extern "C" const char* __asan_default_options() { return "verify_asan_link_order=0"; }

namespace twister::station_app {
namespace {

#if defined(__SANITIZE_ADDRESS__)
void lsan_disable() { __lsan_disable(); }
void lsan_enable() { __lsan_enable(); }
#else
void lsan_disable() {}
void lsan_enable() {}
#endif

using namespace usbtest;  // NOLINT(google-build-using-namespace): the rig's names

class PolhemusUsbModels : public PolhemusUsbTest,
                          public ::testing::WithParamInterface<ModelCase> {};

std::string case_name(const ::testing::TestParamInfo<ModelCase>& info) { return info.param.name; }

// Enumeration by id: the model is detected from the product id alone (no tracker.model),
// a device of another vendor next to it is ignored, and the search's report names the
// unit and where it is.
TEST_P(PolhemusUsbModels, FoundByProductIdAndTheModelDetected) {
  const ModelCase& m = GetParam();
  plug(0x1d6b, 0x0002, 2);  // a hub of another vendor
  plug(hal::kPolhemusVendorId, m.product_id, 5, m.endpoint_out, m.endpoint_in);
  start_station("");
  ASSERT_TRUE(backends_.detected_model.has_value());
  EXPECT_EQ(session_config_.model, m.session_model);
  const std::string text = backends_.tracker_report->text();
  EXPECT_EQ(backends_.tracker_report->level(), hal::DeviceReport::Level::info) << text;
  char ids[16];
  std::snprintf(ids, sizeof ids, "(0f44:%04x)", m.product_id);
  EXPECT_NE(text.find(ids), std::string::npos) << text;
  EXPECT_NE(text.find("on bus 001 device 005"), std::string::npos) << text;
  EXPECT_NE(text.find(hal::polhemus_model_name(m.usb_model)), std::string::npos) << text;
}

// ≥ 1,000 records (two receivers, the stylus on 1) through the station's backend and
// session: every pose equals the encoder's, in order, as floats; noise after every 97th
// record is resynced; the start-up exchange reached the unit on the descriptor's
// endpoints.
TEST_P(PolhemusUsbModels, StreamsRecordsEqualToTheEncoderThroughNoise) {
  const ModelCase& m = GetParam();
  plug(hal::kPolhemusVendorId, m.product_id, 3, m.endpoint_out, m.endpoint_in);
  start_station("");
  const FakePolhemus::Script script = script_for(m, 1100);
  fake_.set_script(script);
  const bool got = run_until(20.0, [&] { return poses_.size() >= 1050; });
  std::fprintf(stderr, "%s: %zu poses received of %zu sent, %zu noise runs\n", m.name,
               poses_.size(), fake_.sent(), fake_.noise_runs());
  ASSERT_TRUE(got) << "poses " << poses_.size() << ", session state "
                   << tracker::session_state_name(session_->state()) << ", report "
                   << backends_.tracker_report->text();
  EXPECT_GE(poses_.size(), 1000u);
  EXPECT_EQ(count_poses_skipped(script.poses), 0u);
  // Noise: resynced, no pose lost to it (the noise starts no record).
  EXPECT_GE(fake_.noise_runs(), 10u);
  const std::uint64_t resyncs = m.session_model == tracker::TrackerModel::fastrak
                                    ? session_->parser_counters().resyncs
                                    : session_->liberty_parser_counters().resyncs;
  EXPECT_GE(resyncs, fake_.noise_runs() - 1);
  EXPECT_EQ(session_->counters().streams_started, 1u);
  // The start-up the serial path sends. A FASTRAK: ladder `c`, `S`, station enables,
  // lists, hemispheres, e1,0, units, binary, `S` again, then `C`. The Liberty family
  // (docs/liberty-protocol.md §9): ladder CR F0 CR P (the Latus without the first CR),
  // WhoAmI, lists in the model's codes, hemispheres, (`@B0` on a Latus), U0, F1, C.
  const std::vector<std::string> cmds = fake_.commands();
  std::vector<std::string> want;
  if (m.session_model == tracker::TrackerModel::fastrak) {
    want = {"c",         "S",        "l1,1", "O1,2,11,16,1", "H1,1,0,0", "l2,1",
            "O2,2,11,1", "H2,1,0,0", "l3,0", "l4,0",         "e1,0",     "U",
            "f",         "S",        "C"};
  } else {
    want = {"F0", "P", "^V", "O1,2,7,10,1", "H1,1,0,0", "O2,2,7,1", "H2,1,0,0", "U0", "F1", "C"};
    if (m.session_model == tracker::TrackerModel::latus) want.insert(want.end() - 3, "@B0");
  }
  EXPECT_EQ(cmds, want);
  EXPECT_EQ(fake_.endpoints_used(), (std::array<std::uint8_t, 2>{m.endpoint_out, m.endpoint_in}));
}

// The unit vanishes mid-stream (its ioctls fail with ENODEV, URBs in flight come back
// shut down, udev says remove) and comes back 3.2 s later at a new address: the hot-plug
// arrival ends the session's back-off at once, it starts the unit up again with the
// station's own timings, and poses flow within 2 s of its return.
TEST_P(PolhemusUsbModels, UnplugAndReplugRecoverWithinTwoSeconds) {
  const ModelCase& m = GetParam();
  const std::string sys =
      plug(hal::kPolhemusVendorId, m.product_id, 4, m.endpoint_out, m.endpoint_in);
  start_station("");
  const FakePolhemus::Script script = script_for(m, 100000);
  fake_.set_script(script);
  ASSERT_TRUE(run_until(10.0, [&] { return poses_.size() >= 300; }));
  unplug(sys);
  const std::size_t sent_before = fake_.sent();
  // Gone for 3.2 s: the session's back-off (1 s, then 2 s, then 4 s) would next try at
  // 7 s; the hot-plug arrival must cut it short.
  run_until(3.2, [] { return false; });
  // Only what the unit sent before it went: the records the host had already taken
  // (the session's and the backend's buffers; at most kMaxPosesPerPoll a pass are read).
  EXPECT_LE(poses_.size(), sent_before) << "poses after the unplug";
  EXPECT_GE(session_->counters().io_errors, 1u);
  const auto lost_report = reports_;
  fake_.set_gone(false);
  fake_.set_script(script);
  const auto back = Clock::now();
  plug(hal::kPolhemusVendorId, m.product_id, 7, m.endpoint_out, m.endpoint_in);
  const std::size_t at_return = poses_.size();
  ASSERT_TRUE(run_until(5.0, [&] { return poses_.size() >= at_return + 50; }))
      << "no poses after the replug; state " << tracker::session_state_name(session_->state())
      << describe();
  const double recovery_s = std::chrono::duration<double>(pose_times_[at_return] - back).count();
  std::fprintf(stderr, "%s: first pose %.3f s after the unit's return\n", m.name, recovery_s);
  EXPECT_LT(recovery_s, 2.0);
  EXPECT_EQ(session_->counters().streams_started, 2u);
  const std::vector<std::string> cmds = fake_.commands();  // the whole start-up again
  const bool fastrak = m.session_model == tracker::TrackerModel::fastrak;
  EXPECT_EQ(std::count(cmds.begin(), cmds.end(), fastrak ? "S" : "^V"), fastrak ? 4 : 2)
      << describe();
  EXPECT_EQ(std::count(cmds.begin(), cmds.end(), "C"), 2) << describe();
  // The log's lines: found, then not found (while gone), then found at the new address.
  ASSERT_GE(reports_.size(), 2u);
  EXPECT_NE(reports_.back().second.find("device 007"), std::string::npos) << reports_.back().second;
  bool said_missing = false;
  for (const auto& [level, text] : reports_)
    said_missing = said_missing || text.find("device 004 is gone") != std::string::npos;
  EXPECT_TRUE(said_missing);
}

INSTANTIATE_TEST_SUITE_P(Usb, PolhemusUsbModels, ::testing::ValuesIn(kModels), case_name);

// The IN transfer's cancellation never comes back (the unit loses discarded URBs): the
// backend's close() gives up after its wait and the next reopen() still streams, with a
// fresh transfer (libusb keeps the lost one flagged in flight: submitting it again would
// fail with LIBUSB_ERROR_BUSY at every reopen).
TEST_F(PolhemusUsbTest, ReopenAfterACancellationThatNeverCameBack) {
  plug(hal::kPolhemusVendorId, 0xff12, 3);
  start_station("");
  fake_.set_script(script_for(kModels[2], 100000));
  // libusb never frees the URB array (56 bytes) of a transfer whose handle closed while it
  // was in flight; it is allocated at the transfer's last submission, in this window.
  lsan_disable();
  ASSERT_TRUE(run_until(10.0, [&] { return poses_.size() >= 50; }));
  fake_.set_discard_lost(true);
  const Status reopened = backends_.tracker->reopen();
  lsan_enable();
  ASSERT_TRUE(reopened.ok()) << backends_.tracker_report->text();
  fake_.set_discard_lost(false);
  std::vector<std::byte> buf(64);
  bool got = false;
  for (const auto start = Clock::now(); !got && seconds_since(start) < 5.0;) {
    const auto n = backends_.tracker->read(buf);
    ASSERT_TRUE(n.ok()) << backends_.tracker_report->text();
    got = *n > 0;
  }
  EXPECT_TRUE(got) << "no bytes after the reopen";
}

// A Liberty still waiting for its firmware (0f44:ff11): one error, however often the
// session searches again, naming fxload, the firmware file and the udev rule; nothing
// is opened. After the firmware (it re-enumerates as ff12) it streams.
TEST_F(PolhemusUsbTest, FirmwarelessIdGivesOneErrorNamingTheFix) {
  plug(hal::kPolhemusVendorId, 0xff11, 2);
  start_station("model = \"liberty\"\nreconnect_interval_ms = 100");
  run_until(2.0, [] { return false; });
  EXPECT_GE(session_->counters().io_errors, 3u) << "searched again and again";
  ASSERT_EQ(reports_.size(), 1u);
  EXPECT_EQ(reports_[0].first, hal::DeviceReport::Level::error);
  const std::string& text = reports_[0].second;
  for (const char* part : {"Liberty (0f44:ff11)", "firmware", "fxload", "LbtyUsb.hex",
                           "99-twister.rules", "0f44:ff12"}) {
    EXPECT_NE(text.find(part), std::string::npos) << part << " in: " << text;
  }
  EXPECT_TRUE(fake_.commands().empty());
  EXPECT_TRUE(poses_.empty());

  fake_.set_script(script_for(kModels[2], 400));
  plug(hal::kPolhemusVendorId, 0xff12, 3);
  ASSERT_TRUE(run_until(10.0, [&] { return poses_.size() >= 100; }));
  EXPECT_EQ(reports_.back().first, hal::DeviceReport::Level::info);
}

// tracker.model given: a unit of another model is reported (one error), not read.
TEST_F(PolhemusUsbTest, AnotherModelThanConfiguredIsReportedNotRead) {
  plug(hal::kPolhemusVendorId, 0xef12, 2);  // a Patriot
  start_station("model = \"liberty\"\nreconnect_interval_ms = 100");
  EXPECT_FALSE(backends_.detected_model.has_value());
  run_until(1.0, [] { return false; });
  ASSERT_EQ(reports_.size(), 1u);
  EXPECT_EQ(reports_[0].first, hal::DeviceReport::Level::error);
  EXPECT_NE(reports_[0].second.find("Patriot (0f44:ef12)"), std::string::npos)
      << reports_[0].second;
  EXPECT_NE(reports_[0].second.find("Liberty (0f44:ff12) only"), std::string::npos)
      << reports_[0].second;
  EXPECT_TRUE(fake_.commands().empty());
}

// No tracker: the one line says what was looked for.
TEST_F(PolhemusUsbTest, NothingPluggedSaysWhatWasLookedFor) {
  plug(0x1d6b, 0x0002, 2);
  start_station("");
  run_until(0.5, [] { return false; });
  ASSERT_EQ(reports_.size(), 1u);
  EXPECT_EQ(reports_[0].first, hal::DeviceReport::Level::warning);
  EXPECT_NE(reports_[0].second.find("no tracker found; looked for FASTRAK (0f44:0002), FASTRAK 3 "
                                    "(0f44:0003)"),
            std::string::npos)
      << reports_[0].second;
}

// The station's own loop and log (StationLoop over the Station core, as main runs
// them) with a Liberty still waiting for its firmware: exactly one error line over many
// searches, naming the fix; replugged with its firmware, the found line and the
// streaming line, and no second error.
class PolhemusUsbStationLoop : public PolhemusUsbTest {
 protected:
  void TearDown() override {
    loop_.reset();
    core_.reset();
    PolhemusUsbTest::TearDown();
    std::fclose(log_file_);
  }
  void start_loop(const std::string& tracker_lines) {
    const std::string text =
        "[station]\njournal = \"/tmp/j.bin\"\nmesh = \"m.obj\"\n[tracker]\nbackend = \"usb\"\n" +
        tracker_lines + "\n[buttons]\nbackend = \"stylus\"\n";
    const ConfigParseResult parsed = parse_station_config(text, "usb.toml");
    ASSERT_TRUE(parsed.ok()) << parsed.errors.front().to_string();
    auto backends = make_backends(parsed.config);
    ASSERT_TRUE(backends) << backends.error().message;
    backends_ = std::move(*backends);
    const StationFileConfig config = with_detected_model(parsed.config, backends_);
    auto setup = make_station_setup(config);
    ASSERT_TRUE(setup) << setup.error().message;
    session_config_ = setup->session;  // the lists the emulated unit encodes with
    model_ = std::move(*load_station_mesh(TWISTER_DEPLOY_DIR "/sim_sphere.obj", 0));
    work_ = std::make_unique<WorkMemory>(model_->mesh().vertex_capacity());
    core_ =
        std::make_unique<station::Station>(*backends_.tracker, *backends_.buttons, *backends_.clock,
                                           storage_, model_->mesh(), work_->storage(), *setup);
    ASSERT_TRUE(core_->start().ok());
    loop_ = std::make_unique<StationLoop>(*core_, backends_, display_, log_,
                                          make_loop_config(config, 600.0, backends_));
    ASSERT_TRUE(loop_->start());
  }
  void run_s(double seconds) {
    const auto start = Clock::now();
    while (seconds_since(start) < seconds) {
      ASSERT_TRUE(loop_->step()) << stop_reason_name(loop_->stop_reason());
    }
  }
  std::string log_text() {
    std::fflush(log_file_);
    std::rewind(log_file_);
    std::string text;
    for (int c = std::fgetc(log_file_); c != EOF; c = std::fgetc(log_file_)) {
      text += static_cast<char>(c);
    }
    return text;
  }
  static int occurrences(const std::string& text, const std::string& what) {
    int n = 0;
    for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
  }

  test::FakeStorage storage_;
  std::unique_ptr<meshio::MeshBuffer> model_;
  std::unique_ptr<WorkMemory> work_;
  std::unique_ptr<station::Station> core_;
  DisplayLink display_;  // not opened
  std::FILE* log_file_ = std::tmpfile();
  hal::Logger log_{{"twister-station", hal::LogLevel::info, false, ::fileno(log_file_)}};
  std::unique_ptr<StationLoop> loop_;
};

TEST_F(PolhemusUsbStationLoop, FirmwarelessUnitIsOneErrorLineThenFoundWhenItsFirmwareIsIn) {
  plug(hal::kPolhemusVendorId, 0xff11, 2);
  start_loop("model = \"liberty\"\nreconnect_interval_ms = 100");
  run_s(2.5);
  std::string log = log_text();
  EXPECT_EQ(occurrences(log,
                        "error: tracker: USB: found a Polhemus Liberty (0f44:ff11) on bus "
                        "001 device 002 still waiting for its firmware: install Debian's "
                        "fxload"),
            1)
      << log;
  EXPECT_EQ(occurrences(log, "error:"), 1) << log;
  EXPECT_EQ(occurrences(log, "tracker:"), 1) << log;  // nothing else about the tracker
  EXPECT_GE(core_->tracker_session().counters().io_errors, 5u) << "searched again and again";

  fake_.set_script(script_for(kModels[2], 100000));
  plug(hal::kPolhemusVendorId, 0xff12, 3);
  run_s(2.5);
  log = log_text();
  EXPECT_EQ(occurrences(log, "tracker: USB: found Liberty (0f44:ff12) on bus 001 device 003"), 1)
      << log;
  EXPECT_EQ(occurrences(log, "tracker: streaming (start-up #"), 1) << log;
  EXPECT_EQ(occurrences(log, "error:"), 1) << log;
  EXPECT_EQ(occurrences(log, "tracker: lost"), 0) << log;
  EXPECT_GE(core_->tracker_session().counters().poses, 1000u);
  std::fprintf(stderr, "station log:\n%s", log.c_str());
}

}  // namespace
}  // namespace twister::station_app
