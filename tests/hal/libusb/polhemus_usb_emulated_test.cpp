// The station's USB tracker backend (LibusbByteStream as make_backends builds it, with
// real libusb) driven by the station's tracker session (FastrakSession, set up by
// make_station_setup with the station's own timings) against Polhemus trackers emulated
// at the kernel interface: umockdev provides each unit's sysfs entry (idVendor /
// idProduct in its descriptors) and /dev/bus/usb/001/NNN, and routes the usbdevfs
// ioctls libusb issues (SUBMITURB, REAPURB(NDELAY), DISCARDURB, claim, ...) to the
// in-process handler below. The emulated unit answers the start-up (the status record
// for `S`) and, after `C`, streams records written by core's encoders (Fastrak records
// for a FASTRAK / FASTRAK 3, Liberty-family frames for a Liberty, Patriot or Latus), with
// noise between them. Label devices. Run under umockdev's preload (CMake sets
// LD_PRELOAD) and, in CTest, a timeout.
//
// What this does not show (needs a unit): the endpoints a real FASTRAK uses (the
// emulated FASTRAKs offer 0x02 / 0x82 to show they are taken from the descriptor), the
// real units' replies to the start-up beyond the status record, their timing, and
// firmware loading itself.
#include <gtest/gtest.h>
#include <linux/ioctl.h>
#include <linux/usbdevice_fs.h>
#include <poll.h>
#include <umockdev.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <deque>
#include <memory>
#include <mutex>
#include <ostream>
#include <string>
#include <vector>

#include "backend_factory.hpp"
#include "config/station_config.hpp"
#include "fakes/fake_storage.hpp"
#include "station_assembly.hpp"
#include "station_loop.hpp"
#include "station_memory.hpp"
#include "station_setup.hpp"
#include "twister/hal/polhemus_usb.hpp"
#include "twister/tracker/fastrak_encoder.hpp"
#include "twister/tracker/fastrak_session.hpp"
#include "twister/tracker/liberty_encoder.hpp"

// ASan builds: umockdev's LD_PRELOAD library loads before the ASan runtime, which
// ASan refuses by default; the order is harmless here. Unused in other builds.
extern "C" const char* __asan_default_options() { return "verify_asan_link_order=0"; }

namespace twister::station_app {
namespace {

using Clock = std::chrono::steady_clock;
using hal::PolhemusUsbModel;

double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
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
const ModelCase kModels[] = {
    {"Fastrak", 0x0002, PolhemusUsbModel::fastrak, tracker::TrackerModel::fastrak, 0x02, 0x82},
    {"Fastrak3", 0x0003, PolhemusUsbModel::fastrak3, tracker::TrackerModel::fastrak, 0x02, 0x82},
    {"Liberty", 0xff12, PolhemusUsbModel::liberty, tracker::TrackerModel::liberty, 0x04, 0x88},
    {"Patriot", 0xef12, PolhemusUsbModel::patriot, tracker::TrackerModel::patriot, 0x04, 0x88},
    {"Latus", 0xff20, PolhemusUsbModel::latus, tracker::TrackerModel::latus, 0x04, 0x88},
};

// The emulated unit, shared by the ioctl handler (umockdev's thread) and the test.
class FakePolhemus {
 public:
  // What it streams after `C`: these poses in order, one every `period_us`, encoded for
  // `model` with `protocol` (the station's lists); `noise` bytes after every 97th.
  struct Script {
    tracker::TrackerModel model = tracker::TrackerModel::fastrak;
    tracker::FastrakConfig protocol{};
    std::vector<tracker::FastrakPose> poses;
    std::int64_t period_us = 500;
    std::string noise;
  };

  void set_script(Script script) {
    std::lock_guard lock(mutex_);
    script_ = std::move(script);
  }
  // Unplugged: every ioctl fails with ENODEV; URBs in flight are given back as shut down.
  void set_gone(bool gone) {
    std::lock_guard lock(mutex_);
    gone_ = gone;
    if (!gone) {  // a unit plugged in again starts from power-up
      streaming_ = false;
      pending_.clear();
      input_.clear();
    }
  }
  std::vector<std::string> commands() {
    std::lock_guard lock(mutex_);
    return commands_;
  }
  std::size_t sent() {
    std::lock_guard lock(mutex_);
    return next_pose_;
  }
  std::size_t noise_runs() {
    std::lock_guard lock(mutex_);
    return noise_runs_;
  }
  std::array<std::uint8_t, 2> endpoints_used() {
    std::lock_guard lock(mutex_);
    return {out_endpoint_seen_, in_endpoint_seen_};
  }

  gboolean handle(UMockdevIoctlClient* client) {
    std::lock_guard lock(mutex_);
    const auto request = static_cast<unsigned long>(umockdev_ioctl_client_get_request(client));
    UMockdevIoctlData* arg = umockdev_ioctl_client_get_arg(client);
    if (request == USBDEVFS_REAPURB || request == USBDEVFS_REAPURBNDELAY) return reap(client, arg);
    if (gone_) {
      umockdev_ioctl_client_complete(client, -1, ENODEV);
      return TRUE;
    }
    switch (request) {
      case USBDEVFS_GET_CAPABILITIES: {
        UMockdevIoctlData* d = umockdev_ioctl_data_resolve(arg, 0, sizeof(guint32), nullptr);
        *reinterpret_cast<guint32*>(d->data) =
            USBDEVFS_CAP_BULK_CONTINUATION | USBDEVFS_CAP_NO_PACKET_SIZE_LIM |
            USBDEVFS_CAP_REAP_AFTER_DISCONNECT | USBDEVFS_CAP_ZERO_PACKET;
        umockdev_ioctl_client_complete(client, 0, 0);
        umockdev_ioctl_data_unref(d);
        return TRUE;
      }
      case USBDEVFS_CLAIMINTERFACE:
      case USBDEVFS_RELEASEINTERFACE:
      case USBDEVFS_DISCONNECT_CLAIM:
      case USBDEVFS_CLEAR_HALT:
      case USBDEVFS_RESETEP:
      case USBDEVFS_SETINTERFACE:
        umockdev_ioctl_client_complete(client, 0, 0);
        return TRUE;
      case USBDEVFS_GETDRIVER:
        umockdev_ioctl_client_complete(client, -1, ENODATA);  // no kernel driver bound
        return TRUE;
      case USBDEVFS_SUBMITURB:
        return submit(client, arg);
      case USBDEVFS_DISCARDURB: {
        const auto addr = reinterpret_cast<gulong>(*reinterpret_cast<void**>(arg->data));
        for (auto it = in_flight_.begin(); it != in_flight_.end(); ++it) {
          if ((*it)->client_addr == addr) {
            discarded_.push_back(*it);
            in_flight_.erase(it);
            umockdev_ioctl_client_complete(client, 0, 0);
            return TRUE;
          }
        }
        umockdev_ioctl_client_complete(client, -1, EINVAL);
        return TRUE;
      }
      default:
        umockdev_ioctl_client_complete(client, -1, ENOTTY);
        return TRUE;
    }
  }

 private:
  gboolean submit(UMockdevIoctlClient* client, UMockdevIoctlData* arg) {
    UMockdevIoctlData* urb_data =
        umockdev_ioctl_data_resolve(arg, 0, sizeof(usbdevfs_urb), nullptr);
    auto* urb = reinterpret_cast<usbdevfs_urb*>(urb_data->data);
    UMockdevIoctlData* buffer =
        umockdev_ioctl_data_resolve(urb_data, G_STRUCT_OFFSET(usbdevfs_urb, buffer),
                                    static_cast<gsize>(urb->buffer_length), nullptr);
    if (urb->type != USBDEVFS_URB_TYPE_BULK) {
      umockdev_ioctl_client_complete(client, -1, EINVAL);
      umockdev_ioctl_data_unref(buffer);
      umockdev_ioctl_data_unref(urb_data);
      return TRUE;
    }
    if ((urb->endpoint & 0x80) == 0) {
      out_endpoint_seen_ = urb->endpoint;
      receive(reinterpret_cast<const char*>(buffer->data),
              static_cast<std::size_t>(urb->buffer_length));
      urb->actual_length = urb->buffer_length;
      urb->status = 0;
      done_.push_back(urb_data);  // the resolved reference: released when reaped
    } else {
      in_endpoint_seen_ = urb->endpoint;
      in_flight_.push_back(urb_data);
    }
    umockdev_ioctl_client_complete(client, 0, 0);
    umockdev_ioctl_data_unref(buffer);
    return TRUE;
  }

  void give_back(UMockdevIoctlClient* client, UMockdevIoctlData* arg, UMockdevIoctlData* urb) {
    // The client's pointer to its URB; the URB goes back on completion (released after).
    UMockdevIoctlData* ptr = umockdev_ioctl_data_resolve(arg, 0, sizeof(gpointer), nullptr);
    umockdev_ioctl_data_set_ptr(ptr, 0, urb);
    umockdev_ioctl_client_complete(client, 0, 0);
    umockdev_ioctl_data_unref(ptr);
    umockdev_ioctl_data_unref(urb);
  }

  gboolean reap(UMockdevIoctlClient* client, UMockdevIoctlData* arg) {
    UMockdevIoctlData* urb_data = nullptr;
    if (!discarded_.empty()) {
      urb_data = discarded_.front();
      discarded_.pop_front();
      reinterpret_cast<usbdevfs_urb*>(urb_data->data)->status = -ENOENT;
    } else if (!done_.empty()) {
      urb_data = done_.front();
      done_.pop_front();
      if (gone_) reinterpret_cast<usbdevfs_urb*>(urb_data->data)->status = -ESHUTDOWN;
    } else if (!in_flight_.empty() && gone_) {
      urb_data = in_flight_.front();
      in_flight_.pop_front();
      auto* urb = reinterpret_cast<usbdevfs_urb*>(urb_data->data);
      urb->actual_length = 0;
      urb->status = -ESHUTDOWN;  // what the kernel gives back on disconnect
    } else if (!in_flight_.empty() && fill_pending()) {
      urb_data = in_flight_.front();
      in_flight_.pop_front();
      auto* urb = reinterpret_cast<usbdevfs_urb*>(urb_data->data);
      const std::size_t n = std::min(pending_.size(), static_cast<std::size_t>(urb->buffer_length));
      // Same address space: the client's buffer is written in place (as libusb's own
      // umockdev test does).
      auto* dest = static_cast<unsigned char*>(urb->buffer);
      for (std::size_t i = 0; i < n; ++i) dest[i] = pending_[i];
      pending_.erase(pending_.begin(), pending_.begin() + static_cast<std::ptrdiff_t>(n));
      urb->actual_length = static_cast<int>(n);
      urb->status = 0;
    }
    if (urb_data == nullptr) {
      umockdev_ioctl_client_complete(client, -1, gone_ ? ENODEV : EAGAIN);
      return TRUE;
    }
    give_back(client, arg, urb_data);
    return TRUE;
  }

  // Bytes to send now: replies, then the records that are due. false: nothing.
  bool fill_pending() {
    if (streaming_) {
      const auto due = static_cast<std::size_t>(
          std::chrono::duration_cast<std::chrono::microseconds>(Clock::now() - stream_start_)
              .count() /
          script_.period_us);
      while (next_pose_ < std::min(due + 1, script_.poses.size()) && pending_.size() < 4096) {
        append_record(script_.poses[next_pose_++]);
        if (next_pose_ % 97 == 0 && !script_.noise.empty()) {
          pending_.insert(pending_.end(), script_.noise.begin(), script_.noise.end());
          ++noise_runs_;
        }
      }
    }
    return !pending_.empty();
  }

  void append_record(const tracker::FastrakPose& pose) {
    std::array<std::byte, tracker::kLibertyMaxFrameBytes> buf{};
    Result<std::size_t> n = StatusCode::invalid_argument;
    if (script_.model == tracker::TrackerModel::fastrak) {
      n = tracker::encode_record(pose, script_.protocol, buf);
    } else {
      const tracker::LibertyModel family =
          script_.model == tracker::TrackerModel::patriot ? tracker::LibertyModel::patriot
          : script_.model == tracker::TrackerModel::latus ? tracker::LibertyModel::latus
                                                          : tracker::LibertyModel::liberty;
      tracker::LibertyConfig frames;
      if (tracker::to_liberty_config(script_.protocol, family, frames).ok())
        n = tracker::encode_liberty_frame(pose, frames, buf);
    }
    if (!n.ok()) return;  // the test then misses a pose and fails
    for (std::size_t i = 0; i < *n; ++i) pending_.push_back(static_cast<unsigned char>(buf[i]));
  }

  // The unit's command interpreter: single-letter commands at once, the others up to CR.
  void receive(const char* data, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) {
      const char c = data[i];
      if (input_.empty() && std::strchr("cCPSfFuU\x19\r", c) != nullptr && c != '\0') {
        if (c == '\r') continue;
        commands_.emplace_back(1, c);
        command(c);
        continue;
      }
      if (c == '\r') {
        commands_.push_back(input_);
        input_.clear();
      } else {
        input_ += c;
      }
    }
  }

  void command(char c) {
    switch (c) {
      case 'c':
        streaming_ = false;
        break;
      case 'C':  // the motion goes on from where it was: the next record is due now
        streaming_ = true;
        stream_start_ =
            Clock::now() -
            std::chrono::microseconds(static_cast<std::int64_t>(next_pose_) * script_.period_us);
        break;
      case 'f':
        binary_ = true;
        break;
      case 'F':
        binary_ = false;
        break;
      case 'u':
        centimetres_ = true;
        break;
      case 'U':
        centimetres_ = false;
        break;
      case 'S': {
        std::array<std::byte, tracker::kStatusReplyBytes> reply{};
        tracker::FastrakStatus status{};
        status.station = 1;
        status.binary = binary_;
        status.centimetres = centimetres_;
        const auto n = tracker::encode_status(status, reply);
        for (std::size_t i = 0; n.ok() && i < *n; ++i)
          pending_.push_back(static_cast<unsigned char>(reply[i]));
        break;
      }
      default:
        break;
    }
  }

  std::mutex mutex_;
  Script script_;
  bool gone_ = false;
  bool streaming_ = false;
  bool binary_ = false;
  bool centimetres_ = false;
  Clock::time_point stream_start_{};
  std::size_t next_pose_ = 0;
  std::size_t noise_runs_ = 0;
  std::string input_;
  std::vector<std::string> commands_;
  std::deque<unsigned char> pending_;
  std::deque<UMockdevIoctlData*> in_flight_;
  std::deque<UMockdevIoctlData*> done_;
  std::deque<UMockdevIoctlData*> discarded_;
  std::uint8_t out_endpoint_seen_ = 0;
  std::uint8_t in_endpoint_seen_ = 0;
};

gboolean on_ioctl(UMockdevIoctlBase*, UMockdevIoctlClient* client, gpointer fake) {
  return static_cast<FakePolhemus*>(fake)->handle(client);
}

std::string hex16le(std::uint16_t v) {
  char s[8];
  std::snprintf(s, sizeof s, "%02x%02x", v & 0xff, v >> 8);
  return s;
}

std::string hex8(std::uint8_t v) {
  char s[4];
  std::snprintf(s, sizeof s, "%02x", v);
  return s;
}

class PolhemusUsbTest : public ::testing::Test {
 protected:
  void SetUp() override {
    testbed_ = umockdev_testbed_new();
    ASSERT_TRUE(umockdev_in_mock_environment()) << "run under umockdev's preload";
    handler_ = static_cast<UMockdevIoctlBase*>(g_object_new(UMOCKDEV_TYPE_IOCTL_BASE, nullptr));
    g_signal_connect(handler_, "handle-ioctl", G_CALLBACK(on_ioctl), &fake_);
  }
  void TearDown() override {
    session_.reset();
    backends_ = {};
    if (testbed_ != nullptr) g_object_unref(testbed_);
    if (handler_ != nullptr) g_object_unref(handler_);
  }

  // Plugs a unit in as bus 1 device `devnum`: its ioctls go to the fake; its sysfs entry
  // carries the device and configuration descriptors (one interface, two bulk
  // endpoints) that libusb reads. Returns the sysfs path.
  std::string plug(std::uint16_t vendor, std::uint16_t product, int devnum,
                   std::uint8_t ep_out = 0x04, std::uint8_t ep_in = 0x88) {
    char dev[64];
    std::snprintf(dev, sizeof dev, "/dev/bus/usb/001/%03d", devnum);
    GError* error = nullptr;
    EXPECT_TRUE(umockdev_testbed_attach_ioctl(testbed_, dev, handler_, &error))
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
  // most) until `done` or `seconds` pass; poses go to poses_.
  template <typename Done>
  bool run_until(double seconds, Done done) {
    const auto start = Clock::now();
    while (seconds_since(start) < seconds) {
      std::array<pollfd, 8> fds{};
      const std::size_t n = backends_.tracker_poll->poll_fds(fds);
      ::poll(fds.data(), n, 1);
      for (auto p = session_->poll(); p.ok(); p = session_->poll()) {
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
    std::string out =
        "\ninits " + std::to_string(c.inits) + ", streams " + std::to_string(c.streams_started) +
        ", io errors " + std::to_string(c.io_errors) + ", status timeouts " +
        std::to_string(c.status_timeouts) + ", mismatches " + std::to_string(c.status_mismatch) +
        ", silence " + std::to_string(c.silence_faults) + ", garbage " +
        std::to_string(c.garbage_faults) + "\ncommands:";
    for (const std::string& cmd : fake_.commands()) out += " [" + cmd + "]";
    for (const auto& r : reports_) out += "\nreport: " + r.second;
    return out;
  }

  UMockdevTestbed* testbed_ = nullptr;
  UMockdevIoctlBase* handler_ = nullptr;
  FakePolhemus fake_;
  Backends backends_;
  tracker::FastrakSessionConfig session_config_;
  std::unique_ptr<tracker::FastrakSession> session_;
  std::vector<tracker::FastrakPose> poses_;
  std::vector<Clock::time_point> pose_times_;
  std::uint32_t report_seen_ = 0;
  std::vector<std::pair<hal::DeviceReport::Level, std::string>> reports_;
};

class PolhemusUsbModels : public PolhemusUsbTest,
                          public ::testing::WithParamInterface<ModelCase> {};

std::string case_name(const ::testing::TestParamInfo<ModelCase>& info) { return info.param.name; }

void PrintTo(const ModelCase& m, std::ostream* os) { *os << m.name; }

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
  // The start-up the serial path sends: ladder `c`, `S`, station enables, lists in the
  // model's codes, hemispheres, e1,0, units, binary, `S` again, then `C`.
  const std::vector<std::string> cmds = fake_.commands();
  const std::vector<std::string> want =
      m.session_model == tracker::TrackerModel::fastrak
          ? std::vector<std::string>{"c",        "S",    "l1,1",      "O1,2,11,16,1",
                                     "H1,1,0,0", "l2,1", "O2,2,11,1", "H2,1,0,0",
                                     "l3,0",     "l4,0", "e1,0",      "U",
                                     "f",        "S",    "C"}
          : std::vector<std::string>{"c",    "S",        "l1,1",     "O1,2,7,10,1", "H1,1,0,0",
                                     "l2,1", "O2,2,7,1", "H2,1,0,0", "l3,0",        "l4,0",
                                     "e1,0", "U",        "f",        "S",           "C"};
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
  const std::size_t before = poses_.size();
  // Gone for 3.2 s: the session's back-off (1 s, then 2 s, then 4 s) would next try at
  // 7 s; the hot-plug arrival must cut it short.
  run_until(3.2, [] { return false; });
  EXPECT_LE(poses_.size(), before + 8) << "poses after the unplug";  // those already read
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
  EXPECT_EQ(std::count(cmds.begin(), cmds.end(), "S"), 4) << describe();
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
