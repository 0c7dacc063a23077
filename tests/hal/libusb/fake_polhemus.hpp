// FakePolhemus: a Polhemus tracker emulated at usbdevfs (umockdev routes libusb's
// SUBMITURB, REAPURB(NDELAY), DISCARDURB, claim, ... on its node to handle(), on
// umockdev's thread). It answers the start-up and, after `C`, streams a script (poses
// by core's encoders, noise between them) or what a sim::FastrakDevice (twister-sim's
// device model, then reading the host's commands itself) sends.
#pragma once

#include <linux/ioctl.h>
#include <linux/usbdevice_fs.h>
#include <umockdev.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <deque>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "twister/sim/fastrak_device.hpp"
#include "twister/tracker/fastrak_encoder.hpp"
#include "twister/tracker/fastrak_session.hpp"
#include "twister/tracker/liberty_encoder.hpp"
#include "twister/tracker/liberty_startup.hpp"

namespace twister::station_app::usbtest {

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

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
    liberty_lines_ = script.model != tracker::TrackerModel::fastrak;
    script_ = std::move(script);
  }
  // From now on the unit is this device model, powered up now: the host's bytes go to
  // it and it sends what its line delivers, on the real clock (microseconds since now).
  void set_device(const sim::FastrakDeviceConfig& config, sim::Scenario scenario) {
    std::lock_guard lock(mutex_);
    device_epoch_ = Clock::now();
    liberty_lines_ = config.model != sim::DeviceModel::fastrak;
    device_ = std::make_unique<sim::FastrakDevice>(config, std::move(scenario), 0);
  }
  const sim::FastrakDevice* device() {
    std::lock_guard lock(mutex_);
    return device_.get();
  }
  // A unit whose URBs never come back when discarded (DISCARDURB succeeds, REAPURB never
  // returns them): a wedged device, or a host controller that loses the cancellation.
  void set_discard_lost(bool lost) {
    std::lock_guard lock(mutex_);
    discard_lost_ = lost;
  }
  // Unplugged: every ioctl fails with ENODEV; URBs in flight are given back as shut down.
  void set_gone(bool gone) {
    std::lock_guard lock(mutex_);
    gone_ = gone;
    if (!gone) {  // a unit plugged in again starts from power-up
      streaming_ = false;
      pending_.clear();
      input_.clear();
      // URBs of the unplugged node's connection (closed by the host) are not the new
      // node's: never given back on it.
      for (auto* queue : {&in_flight_, &done_, &discarded_}) {
        for (UMockdevIoctlData* urb : *queue) umockdev_ioctl_data_unref(urb);
        queue->clear();
      }
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
  std::size_t reaped() {
    std::lock_guard lock(mutex_);
    return reaped_;
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
            if (discard_lost_) {
              umockdev_ioctl_data_unref(*it);
            } else {
              discarded_.push_back(*it);
            }
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
      ++reaped_;
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
    if (device_ != nullptr) {
      std::vector<std::byte> out;
      device_->advance(device_now_us(), out);
      for (const std::byte b : out) pending_.push_back(static_cast<unsigned char>(b));
      return !pending_.empty();
    }
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
    if (device_ != nullptr) {
      device_->receive(reinterpret_cast<const std::byte*>(data), n, device_now_us());
    }
    for (std::size_t i = 0; i < n; ++i) {
      const char c = data[i];
      if (liberty_lines_) {
        liberty_byte(c);
        continue;
      }
      if (input_.empty() && std::strchr("cCPSfFuU\x19\r", c) != nullptr && c != '\0') {
        if (c == '\r') continue;
        commands_.emplace_back(1, c);
        if (device_ == nullptr) command(c);
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

  // A Liberty's command lines (docs/liberty-protocol.md §9): all end with CR but `P`;
  // logged with ^V and ^Y spelled out.
  void liberty_byte(char c) {
    if (input_.empty() && c == tracker::kLibertyPoll) {
      commands_.emplace_back(1, c);
      return;
    }
    if (c != '\r') {
      input_ += c;
      return;
    }
    if (input_.empty()) return;
    std::string logged;
    for (const char k : input_)
      logged += k == tracker::kCtrlV ? "^V" : k == 0x19 ? "^Y" : std::string(1, k);
    commands_.push_back(logged);
    if (device_ == nullptr) liberty_line(input_);
    input_.clear();
  }
  void liberty_line(const std::string& line) {
    if (line == "F1" || line == "F0") binary_ = line == "F1";
    if (line == "U1" || line == "U0") centimetres_ = line == "U1";
    if (line == "C") command('C');
    if (line == std::string(1, tracker::kCtrlV)) {
      const std::string reply = "0 Polhemus (emulated)\r\n";
      pending_.insert(pending_.end(), reply.begin(), reply.end());
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

  std::int64_t device_now_us() const {
    return std::chrono::duration_cast<std::chrono::microseconds>(Clock::now() - device_epoch_)
        .count();
  }

  std::mutex mutex_;
  std::unique_ptr<sim::FastrakDevice> device_;  // the unit, when a device model plays it
  std::size_t reaped_ = 0;                      // IN URBs given back with data
  bool liberty_lines_ = false;                  // the unit reads the Liberty dialect
  Clock::time_point device_epoch_{};
  Script script_;
  bool gone_ = false;
  bool discard_lost_ = false;
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

inline gboolean on_ioctl(UMockdevIoctlBase*, UMockdevIoctlClient* client, gpointer fake) {
  return static_cast<FakePolhemus*>(fake)->handle(client);
}

}  // namespace twister::station_app::usbtest
