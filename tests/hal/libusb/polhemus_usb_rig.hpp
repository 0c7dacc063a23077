// PolhemusUsbTest: the station's USB tracker backend (LibusbByteStream as make_backends
// builds it, real libusb) and tracker session (FastrakSession, set up by
// make_station_setup with the station's own timings) against a FakePolhemus plugged in
// through umockdev: each unit's sysfs entry (idVendor / idProduct in its descriptors)
// and /dev/bus/usb/001/NNN. Shared by the emulated USB tests (label devices).
#pragma once

#include <gtest/gtest.h>
#include <poll.h>

#include <cmath>
#include <ostream>

#include "backend_factory.hpp"
#include "config/station_config.hpp"
#include "hal/libusb/fake_polhemus.hpp"
#include "station_setup.hpp"
#include "twister/hal/polhemus_usb.hpp"
#include "twister/station/tracker_hands.hpp"

namespace twister::station_app::usbtest {

using hal::PolhemusUsbModel;

inline std::string hex16le(std::uint16_t v) {
  char s[8];
  std::snprintf(s, sizeof s, "%02x%02x", v & 0xff, v >> 8);
  return s;
}

inline std::string hex8(std::uint8_t v) {
  char s[4];
  std::snprintf(s, sizeof s, "%02x", v);
  return s;
}

struct ModelCase {
  const char* name;
  std::uint16_t product_id;
  PolhemusUsbModel usb_model;
  tracker::TrackerModel session_model;
  std::uint8_t endpoint_out;
  std::uint8_t endpoint_in;
};

// VRPN's Liberty endpoints for the Liberty family; the FASTRAKs' are not in the sources
// (see the header comment).
inline const ModelCase kModels[] = {
    {"Fastrak", 0x0002, PolhemusUsbModel::fastrak, tracker::TrackerModel::fastrak, 0x02, 0x82},
    {"Fastrak3", 0x0003, PolhemusUsbModel::fastrak3, tracker::TrackerModel::fastrak, 0x02, 0x82},
    {"Liberty", 0xff12, PolhemusUsbModel::liberty, tracker::TrackerModel::liberty, 0x04, 0x88},
    {"Patriot", 0xef12, PolhemusUsbModel::patriot, tracker::TrackerModel::patriot, 0x04, 0x88},
    {"Latus", 0xff20, PolhemusUsbModel::latus, tracker::TrackerModel::latus, 0x04, 0x88},
};

inline void PrintTo(const ModelCase& m, std::ostream* os) { *os << m.name; }

class PolhemusUsbTest : public ::testing::Test {
 protected:
  void SetUp() override {
    testbed_ = umockdev_testbed_new();
    ASSERT_TRUE(umockdev_in_mock_environment()) << "run under umockdev's preload";
  }
  void TearDown() override {
    session_.reset();
    backends_ = {};
    if (testbed_ != nullptr) g_object_unref(testbed_);
    for (UMockdevIoctlBase* h : handlers_) g_object_unref(h);
  }

  // Plugs a unit in as bus 1 device `devnum`: its ioctls go to the fake; its sysfs entry
  // carries the device and configuration descriptors (one interface, two bulk
  // endpoints) that libusb reads. Returns the sysfs path.
  std::string plug(std::uint16_t vendor, std::uint16_t product, int devnum,
                   std::uint8_t ep_out = 0x04, std::uint8_t ep_in = 0x88) {
    char dev[64];
    std::snprintf(dev, sizeof dev, "/dev/bus/usb/001/%03d", devnum);
    GError* error = nullptr;
    // A handler of its own per node (docs/hardware.md, "the asan hang"): one handler
    // attached to the unplugged node and the new one served both from one thread, and a
    // request on the new node could wait behind the old node's connection for ever.
    auto* handler =
        static_cast<UMockdevIoctlBase*>(g_object_new(UMOCKDEV_TYPE_IOCTL_BASE, nullptr));
    g_signal_connect(handler, "handle-ioctl", G_CALLBACK(on_ioctl), &fake_);
    handlers_.push_back(handler);
    EXPECT_TRUE(umockdev_testbed_attach_ioctl(testbed_, dev, handler, &error))
        << (error != nullptr ? error->message : "");
    const std::string descriptors =
        "12010002000000"
        "40" +
        hex16le(vendor) + hex16le(product) +
        "0001"
        "000000"
        "01" +  // device
        "09022000010100"
        "80"
        "32" +                  // configuration, 32 bytes in all
        "0904000002ffffff00" +  // interface 0, two endpoints
        "0705" +
        hex8(ep_out) +
        "02"
        "0002"
        "00" +  // bulk OUT, 512 bytes
        "0705" +
        hex8(ep_in) +
        "02"
        "0002"
        "00";  // bulk IN, 512 bytes
    char sys[64];
    std::snprintf(sys, sizeof sys, "/devices/pci0000:00/usb1/1-%d", devnum);
    char text[1024];
    std::snprintf(text, sizeof text,
                  "P: %s\nN: bus/usb/001/%03d\nE: SUBSYSTEM=usb\nE: DRIVER=usb\n"
                  "E: BUSNUM=001\nE: DEVNUM=%03d\nE: DEVNAME=%s\nE: DEVTYPE=usb_device\n"
                  "A: bConfigurationValue=1\\n\nA: busnum=1\\n\nA: devnum=%d\\n\n"
                  "A: speed=480\\n\nH: descriptors=%s\n",
                  sys, devnum, devnum, dev, devnum, descriptors.c_str());
    EXPECT_TRUE(umockdev_testbed_add_from_string(testbed_, text, &error))
        << (error != nullptr ? error->message : "");
    return std::string("/sys") + sys;
  }
  void unplug(const std::string& sys_path) {
    fake_.set_gone(true);
    umockdev_testbed_uevent(testbed_, sys_path.c_str(), "remove");
  }

  // The station's backends and tracker session for `toml_tracker` lines.
  void start_station(const std::string& tracker_lines) {
    const std::string text =
        "[station]\njournal = \"/tmp/j.bin\"\nmesh = \"m.obj\"\n[tracker]\nbackend = \"usb\"\n" +
        tracker_lines + "\n[buttons]\nbackend = \"stylus\"\n";
    const ConfigParseResult parsed = parse_station_config(text, "usb.toml");
    ASSERT_TRUE(parsed.ok()) << parsed.errors.front().to_string();
    auto backends = make_backends(parsed.config);
    ASSERT_TRUE(backends) << backends.error().message;
    backends_ = std::move(*backends);
    ASSERT_NE(backends_.tracker_report, nullptr);
    auto setup = make_station_setup(with_detected_model(parsed.config, backends_));
    ASSERT_TRUE(setup) << setup.error().message;
    session_config_ = setup->session;
    session_ = std::make_unique<tracker::FastrakSession>(*backends_.tracker, *backends_.clock,
                                                         session_config_);
  }

  // Polls as the station's loop does (poll(2) on the backend's descriptors, 1 ms at
  // most; at most kMaxPosesPerPoll poses a pass, as TrackerHands::drain) until `done`
  // or `seconds` pass; poses go to poses_.
  // The bound matters (docs/hardware.md, "the asan replug failures"): a pass that drains
  // until the session has nothing never ends while the emulated unit (2,000 records/s)
  // always has a record due when the host reads again, as under ASan, where the host
  // reads at just the unit's rate. The replug cases then spent their first phase
  // draining the whole script (100,000 records, 50 s), and the unit had nothing left
  // to send after the replug.
  template <typename Done>
  bool run_until(double seconds, Done done) {
    const auto start = Clock::now();
    while (seconds_since(start) < seconds) {
      std::array<pollfd, 8> fds{};
      const std::size_t n = backends_.tracker_poll->poll_fds(fds);
      ::poll(fds.data(), n, 1);
      for (std::size_t i = 0; i < station::kMaxPosesPerPoll; ++i) {
        auto p = session_->poll();
        if (!p.ok()) break;
        poses_.push_back(*p);
        pose_times_.push_back(Clock::now());
      }
      note_report();
      if (done()) return true;
    }
    return false;
  }
  void note_report() {
    const hal::DeviceReport& r = *backends_.tracker_report;
    if (r.changes() == report_seen_) return;
    report_seen_ = r.changes();
    reports_.push_back({r.level(), r.text()});
  }

  // Poses that move a little per record (within the session's continuity limits), both
  // hands, the stylus pressed for a while; values exactly representable as floats.
  std::vector<tracker::FastrakPose> script_poses(std::size_t count) const {
    std::vector<tracker::FastrakPose> poses;
    for (std::size_t i = 0; i < count; ++i) {
      tracker::FastrakPose p{};
      p.station = static_cast<std::uint8_t>(1 + i % 2);
      p.has_position = true;
      const float t = static_cast<float>(i / 2) / 256.0f;
      p.position = {10.0f + t, -5.0f + 0.5f * t, 3.0f - 0.25f * t};
      if (p.station == 2) p.position[0] = -p.position[0];
      p.has.quaternion = true;
      const float a = 0.0005f * static_cast<float>(i / 2);
      p.quaternion = {std::cos(a), std::sin(a), 0.0f, 0.0f};
      if (p.station == 1) {
        p.has_button = true;
        p.button = (i / 200) % 2 == 1;
      }
      poses.push_back(p);
    }
    return poses;
  }

  FakePolhemus::Script script_for(const ModelCase& m, std::size_t count) const {
    FakePolhemus::Script s;
    s.model = m.session_model;
    s.protocol = session_config_.protocol;
    s.poses = script_poses(count);
    // Bytes that cannot start a record or a frame of any of the models.
    s.noise = std::string("\x7f\xee noise \xa5", 10);
    return s;
  }

  // Every pose received is one the unit sent after the previous one, as floats;
  // returns how many the unit sent in between that were not received.
  std::size_t count_poses_skipped(const std::vector<tracker::FastrakPose>& sent) {
    std::size_t j = 0;
    std::size_t skipped = 0;
    for (std::size_t i = 0; i < poses_.size(); ++i) {
      while (j < sent.size() && !same_pose(sent[j], poses_[i])) {
        ++j;
        ++skipped;
      }
      EXPECT_LT(j, sent.size()) << "pose " << i << " (station " << int(poses_[i].station)
                                << ") is none the unit sent after the previous one";
      if (j >= sent.size()) return sent.size();
      ++j;
    }
    return skipped;
  }
  static bool same_pose(const tracker::FastrakPose& a, const tracker::FastrakPose& b) {
    return a.station == b.station && a.position == b.position && a.quaternion == b.quaternion &&
           a.button == b.button;
  }

  // The session's counters, the commands the unit saw and the reports, for a failure.
  std::string describe() {
    const auto& c = session_->counters();
    std::string out = "\nunit sent " + std::to_string(fake_.sent()) + " records, " +
                      std::to_string(fake_.reaped()) + " IN URBs given back\ninits " +
                      std::to_string(c.inits) + ", streams " + std::to_string(c.streams_started) +
                      ", io errors " + std::to_string(c.io_errors) + ", status timeouts " +
                      std::to_string(c.status_timeouts) + ", mismatches " +
                      std::to_string(c.status_mismatch) + ", silence " +
                      std::to_string(c.silence_faults) + ", garbage " +
                      std::to_string(c.garbage_faults) + "\ncommands:";
    for (const std::string& cmd : fake_.commands()) out += " [" + cmd + "]";
    for (const auto& r : reports_) out += "\nreport: " + r.second;
    return out;
  }

  UMockdevTestbed* testbed_ = nullptr;
  std::vector<UMockdevIoctlBase*> handlers_;  // one per node plugged
  FakePolhemus fake_;
  Backends backends_;
  tracker::FastrakSessionConfig session_config_;
  std::unique_ptr<tracker::FastrakSession> session_;
  std::vector<tracker::FastrakPose> poses_;
  std::vector<Clock::time_point> pose_times_;
  std::uint32_t report_seen_ = 0;
  std::vector<std::pair<hal::DeviceReport::Level, std::string>> reports_;
};

}  // namespace twister::station_app::usbtest
