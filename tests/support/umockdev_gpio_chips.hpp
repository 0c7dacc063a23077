// Emulated GPIO chips for tests run under umockdev's preload library (no gpio-sim
// module here): /dev/gpiochipN nodes and their sysfs entries in a umockdev testbed, and
// one ioctl handler (the GPIO v1 character-device ABI, as libgpiod 1.6 uses it) for all
// of them. Header-only; link PkgConfig::UMOCKDEV.
//
// What the handler answers, per chip (umockdev_ioctl_client_get_devnode):
// - GPIO_GET_CHIPINFO_IOCTL, GPIO_GET_LINEINFO_IOCTL (offsets beyond the chip: EINVAL);
// - GPIO_GET_LINEEVENT_IOCTL (an input line for edge events): the event fd is the read
//   end of a pipe; the test (or a wire, below) writes kernel-format gpioevent_data into
//   the write end. For a client that is another process, the pipes must exist in that
//   process: pre_make_event_pipes() before spawning it makes pipes whose read ends it
//   inherits (the write ends are close-on-exec), and the handler hands those out;
// - GPIO_GET_LINEHANDLE_IOCTL (output lines): records offsets, flags, default values and
//   the consumer label. umockdev forwards ioctls only on descriptors of emulated nodes,
//   so a separate handle fd would not reach this handler: the handle fd handed back is
//   the client's own descriptor of this chip node (found in /proc/PID/fd; PID is
//   set_output_client(), default this process). libgpiod then sends
//   GPIOHANDLE_SET_LINE_VALUES_IOCTL on that descriptor, which arrives here; releasing
//   the line closes it, and the client's later close of the chip fails with EBADF
//   (harmless: nothing else is opened in between in these tests).
// - GPIOHANDLE_SET_LINE_VALUES_IOCTL: the handle's new values (logical, as requested).
// - refuse_requests: line requests fail with EBUSY (a line held by another consumer).
//
// The wire: connect(output chip, offset, input chip, offset) joins an output line to an
// input line as a rig's cable does. A value written to the output becomes a physical
// level (inverted when the output was requested active-low), the input's logical level
// is that physical level, inverted when the input was requested active-low (the kernel
// does this for v1 edge events), and a change of it is written into the input line's
// event pipe as a rising or falling edge stamped with CLOCK_MONOTONIC now (as the
// kernel stamps events since Linux 5.7). Idle level of an unrequested line: high (the
// station's pull-up).
#pragma once

#include <dirent.h>
#include <fcntl.h>
#include <linux/gpio.h>
#include <time.h>
#include <umockdev.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <mutex>
#include <string>
#include <vector>

namespace twister::test {

class UmockdevGpioChips {
 public:
  static constexpr std::uint32_t kChipLines = 32;

  struct EventRequest {  // an input line requested for edge events
    std::uint32_t offset = 0;
    std::uint32_t handle_flags = 0;
    std::uint32_t event_flags = 0;
    std::string consumer;
    int read_fd = -1;
    int write_fd = -1;
    bool pre_made = false;  // from pre_make_event_pipes: this process closes its read end
  };
  struct HandleRequest {  // output lines requested together
    std::vector<std::uint32_t> offsets;
    std::uint32_t flags = 0;
    std::vector<std::uint8_t> defaults;
    std::string consumer;
    int fd = -1;  // the handle fd handed out (the client's chip descriptor)
  };
  struct Chip {
    std::string name;
    std::vector<EventRequest> events;
    std::vector<HandleRequest> handles;
    std::vector<std::vector<std::uint8_t>> value_writes;  // every SET_LINE_VALUES
    std::map<std::uint32_t, bool> physical;               // output lines' levels
    std::map<std::uint32_t, bool> input_level;            // input lines' logical levels
    bool refuse_requests = false;
  };
  struct Wire {
    std::string out_chip;
    std::uint32_t out_offset;
    std::string in_chip;
    std::uint32_t in_offset;
  };

  UmockdevGpioChips() : output_client_(::getpid()) {
    testbed_ = umockdev_testbed_new();
    handler_ = static_cast<UMockdevIoctlBase*>(g_object_new(UMOCKDEV_TYPE_IOCTL_BASE, nullptr));
    g_signal_connect(handler_, "handle-ioctl", G_CALLBACK(&UmockdevGpioChips::on_ioctl), this);
  }
  ~UmockdevGpioChips() {
    std::lock_guard lock(mutex_);
    for (auto& [name, chip] : chips_) {
      for (EventRequest& e : chip.events) {
        if (e.write_fd >= 0) ::close(e.write_fd);
        if (e.pre_made) ::close(e.read_fd);
      }
    }
    for (auto& p : pool_) {
      ::close(p[0]);
      ::close(p[1]);
    }
    g_object_unref(testbed_);
    g_object_unref(handler_);
  }
  UmockdevGpioChips(const UmockdevGpioChips&) = delete;
  UmockdevGpioChips& operator=(const UmockdevGpioChips&) = delete;

  UMockdevTestbed* testbed() { return testbed_; }

  // Adds /dev/NAME (a plain-file node: the readlink of a client's fd names it) and its
  // sysfs entry with major:minor 254:MINOR. false: umockdev refused (message in error).
  bool add_chip(const std::string& name, int minor, std::string& error) {
    {
      std::lock_guard lock(mutex_);
      chips_[name].name = name;
    }
    const std::string text = "P: /devices/platform/gpio-sim.0/" + name + "\nN: " + name +
                             "=00\nE: SUBSYSTEM=gpio\nE: DEVNAME=/dev/" + name +
                             "\nA: dev=254:" + std::to_string(minor) + "\\n\n";
    GError* e = nullptr;
    // libgpiod compares sysfs "dev" with the node's major:minor after dropping the last
    // character, hence the literal \n.
    if (!umockdev_testbed_add_from_string(testbed_, text.c_str(), &e) ||
        !umockdev_testbed_attach_ioctl(testbed_, ("/dev/" + name).c_str(), handler_, &e)) {
      error = e != nullptr ? e->message : "umockdev failed";
      if (e != nullptr) g_error_free(e);
      return false;
    }
    return true;
  }

  void connect(const std::string& out_chip, std::uint32_t out_offset, const std::string& in_chip,
               std::uint32_t in_offset) {
    std::lock_guard lock(mutex_);
    wires_.push_back({out_chip, out_offset, in_chip, in_offset});
  }
  void refuse_requests(const std::string& chip, bool refuse) {
    std::lock_guard lock(mutex_);
    chips_[chip].refuse_requests = refuse;
  }
  // The process whose chip descriptor becomes its output handle (default: this one;
  // -1: one about to be spawned, line-handle requests wait until it is set).
  void set_output_client(pid_t pid) {
    std::lock_guard lock(mutex_);
    output_client_ = pid;
    changed_.notify_all();
  }
  // Makes n pipes for a child's edge-event requests (see above); call before spawning it.
  void pre_make_event_pipes(std::size_t n) {
    std::lock_guard lock(mutex_);
    for (std::size_t i = 0; i < n; ++i) {
      std::array<int, 2> p{};
      if (::pipe(p.data()) != 0) return;
      ::fcntl(p[1], F_SETFD, FD_CLOEXEC);
      pool_.push_back(p);
    }
  }

  // A copy of a chip's state, under the lock.
  Chip chip(const std::string& name) {
    std::lock_guard lock(mutex_);
    return chips_[name];
  }
  // Waits until `name` has at least n edge-event requests; false at the timeout.
  bool wait_for_event_requests(const std::string& name, std::size_t n, std::chrono::seconds t) {
    std::unique_lock lock(mutex_);
    return changed_.wait_for(lock, t, [&] { return chips_[name].events.size() >= n; });
  }
  // Writes one edge into the latest event request of `offset` on `chip`.
  bool emit(const std::string& chip, std::uint32_t offset, bool rising) {
    std::lock_guard lock(mutex_);
    return emit_locked(chips_[chip], offset, rising);
  }
  std::uint64_t wire_edges() {
    std::lock_guard lock(mutex_);
    return wire_edges_;
  }

 private:
  static gboolean on_ioctl(UMockdevIoctlBase*, UMockdevIoctlClient* client, gpointer self) {
    return static_cast<UmockdevGpioChips*>(self)->handle(client);
  }

  template <typename T>
  static T* resolve(UMockdevIoctlClient* client) {
    GError* error = nullptr;
    UMockdevIoctlData* d =
        umockdev_ioctl_data_resolve(umockdev_ioctl_client_get_arg(client), 0, sizeof(T), &error);
    if (error != nullptr) {
      g_error_free(error);
      return nullptr;
    }
    return reinterpret_cast<T*>(d->data);
  }

  static void done(UMockdevIoctlClient* client, int errno_value) {
    umockdev_ioctl_client_complete(client, errno_value == 0 ? 0 : -1, errno_value);
  }

  gboolean handle(UMockdevIoctlClient* client) {
    const gulong request = umockdev_ioctl_client_get_request(client);
    const std::string node = umockdev_ioctl_client_get_devnode(client);
    const std::string name = node.substr(node.rfind('/') + 1);
    std::unique_lock lock(mutex_);
    Chip& chip = chips_[name];
    if (request == GPIO_GET_CHIPINFO_IOCTL) {
      auto* info = resolve<gpiochip_info>(client);
      if (info == nullptr) return FALSE;
      std::snprintf(info->name, sizeof info->name, "%s", name.c_str());
      std::snprintf(info->label, sizeof info->label, "twister-fake");
      info->lines = kChipLines;
    } else if (request == GPIO_GET_LINEINFO_IOCTL) {
      auto* info = resolve<gpioline_info>(client);
      if (info == nullptr) return FALSE;
      if (info->line_offset >= kChipLines) {
        done(client, EINVAL);
        return TRUE;
      }
      info->flags = 0;
      std::snprintf(info->name, sizeof info->name, "line%u", info->line_offset);
    } else if (request == GPIO_GET_LINEEVENT_IOCTL) {
      auto* req = resolve<gpioevent_request>(client);
      if (req == nullptr) return FALSE;
      if (chip.refuse_requests || req->lineoffset >= kChipLines) {
        done(client, chip.refuse_requests ? EBUSY : EINVAL);
        return TRUE;
      }
      std::array<int, 2> p{};
      const bool pre_made = !pool_.empty();
      if (pre_made) {
        p = pool_.front();
        pool_.erase(pool_.begin());
      } else if (::pipe(p.data()) != 0) {
        done(client, EMFILE);
        return TRUE;
      }
      chip.events.push_back({req->lineoffset, req->handleflags, req->eventflags,
                             req->consumer_label, p[0], p[1], pre_made});
      req->fd = p[0];
      changed_.notify_all();
    } else if (request == GPIO_GET_LINEHANDLE_IOCTL) {
      auto* req = resolve<gpiohandle_request>(client);
      if (req == nullptr) return FALSE;
      if (chip.refuse_requests) {
        done(client, EBUSY);
        return TRUE;
      }
      HandleRequest h;
      for (std::uint32_t i = 0; i < req->lines && i < GPIOHANDLES_MAX; ++i) {
        if (req->lineoffsets[i] >= kChipLines) {
          done(client, EINVAL);
          return TRUE;
        }
        h.offsets.push_back(req->lineoffsets[i]);
        h.defaults.push_back(req->default_values[i]);
      }
      h.flags = req->flags;
      h.consumer = req->consumer_label;
      // The client process may still be starting when its first request arrives.
      changed_.wait_for(lock, std::chrono::seconds(5), [&] { return output_client_ > 0; });
      h.fd = output_client_ > 0 ? client_chip_fd(output_client_, name) : -1;
      if (h.fd < 0) {
        done(client, ENODEV);
        return TRUE;
      }
      req->fd = h.fd;
      chip.handles.push_back(h);
      write_outputs(chip, h, h.defaults);
    } else if (request == GPIOHANDLE_SET_LINE_VALUES_IOCTL) {
      auto* data = resolve<gpiohandle_data>(client);
      if (data == nullptr || chip.handles.empty()) {
        done(client, EBADF);
        return TRUE;
      }
      const HandleRequest& h = chip.handles.back();
      std::vector<std::uint8_t> values(data->values, data->values + h.offsets.size());
      chip.value_writes.push_back(values);
      write_outputs(chip, h, values);
    } else {
      done(client, ENOTTY);
      return TRUE;
    }
    done(client, 0);
    return TRUE;
  }

  // The descriptor of /dev/CHIP (its testbed file) that process `pid` holds open.
  int client_chip_fd(pid_t pid, const std::string& name) const {
    const std::string want = std::string(umockdev_testbed_get_root_dir(testbed_)) + "/dev/" + name;
    const std::string dir = "/proc/" + std::to_string(pid) + "/fd";
    DIR* d = ::opendir(dir.c_str());
    if (d == nullptr) return -1;
    int found = -1;
    while (dirent* entry = ::readdir(d)) {
      std::array<char, 4096> target{};
      const std::string link = dir + "/" + entry->d_name;
      const ssize_t n = ::readlink(link.c_str(), target.data(), target.size() - 1);
      if (n > 0 && want == std::string(target.data(), static_cast<std::size_t>(n))) {
        found = std::atoi(entry->d_name);
      }
    }
    ::closedir(d);
    return found;
  }

  // New logical values of handle h's lines: the wire carries their physical levels.
  void write_outputs(Chip& chip, const HandleRequest& h, const std::vector<std::uint8_t>& values) {
    const bool active_low = (h.flags & GPIOHANDLE_REQUEST_ACTIVE_LOW) != 0;
    for (std::size_t i = 0; i < h.offsets.size() && i < values.size(); ++i) {
      const bool physical = (values[i] != 0) != active_low;
      chip.physical[h.offsets[i]] = physical;
      for (const Wire& w : wires_) {
        if (w.out_chip != chip.name || w.out_offset != h.offsets[i]) continue;
        Chip& in = chips_[w.in_chip];
        const EventRequest* req = latest(in, w.in_offset);
        const bool in_active_low =
            req != nullptr && (req->handle_flags & GPIOHANDLE_REQUEST_ACTIVE_LOW) != 0;
        const bool logical = physical != in_active_low;
        // Before any write the input rests at the pull-up's high level.
        const auto it = in.input_level.try_emplace(w.in_offset, !in_active_low).first;
        if (it->second == logical) continue;  // no edge
        it->second = logical;
        if (req != nullptr && emit_locked(in, w.in_offset, logical)) ++wire_edges_;
      }
    }
  }

  static const EventRequest* latest(const Chip& chip, std::uint32_t offset) {
    for (std::size_t i = chip.events.size(); i-- > 0;) {
      if (chip.events[i].offset == offset) return &chip.events[i];
    }
    return nullptr;
  }

  static bool emit_locked(Chip& chip, std::uint32_t offset, bool rising) {
    const EventRequest* req = latest(chip, offset);
    if (req == nullptr || req->write_fd < 0) return false;
    timespec now{};
    ::clock_gettime(CLOCK_MONOTONIC, &now);
    gpioevent_data ev{};
    ev.timestamp =
        static_cast<__u64>(now.tv_sec) * 1'000'000'000ull + static_cast<__u64>(now.tv_nsec);
    ev.id = rising ? GPIOEVENT_EVENT_RISING_EDGE : GPIOEVENT_EVENT_FALLING_EDGE;
    return ::write(req->write_fd, &ev, sizeof ev) == static_cast<ssize_t>(sizeof ev);
  }

  UMockdevTestbed* testbed_ = nullptr;
  UMockdevIoctlBase* handler_ = nullptr;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::map<std::string, Chip> chips_;
  std::vector<Wire> wires_;
  std::vector<std::array<int, 2>> pool_;  // pre-made event pipes for a child process
  pid_t output_client_;
  std::uint64_t wire_edges_ = 0;
};

}  // namespace twister::test
