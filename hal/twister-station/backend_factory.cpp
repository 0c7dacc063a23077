// The only place that names concrete backend classes (with main.cpp). Which ones
// exist is decided by CMake (TWISTER_HAVE_* definitions on this file only).
#include "backend_factory.hpp"

#include <cstdio>

#include "twister/hal/monotonic_clock.hpp"
#include "twister/sim/builtin_scenarios.hpp"
#include "twister/sim/sim_button_source.hpp"
#include "twister/sim/sim_fastrak_stream.hpp"
#ifdef TWISTER_HAVE_HAL_GPIOD
#include "twister/hal/gpiod_button_source.hpp"
#endif
#ifdef TWISTER_HAVE_HAL_HIDAPI
#include "twister/hal/hidapi_button_source.hpp"
#endif
#ifdef TWISTER_HAVE_HAL_TERMIOS
#include "twister/hal/termios_byte_stream.hpp"
#endif
#ifdef TWISTER_HAVE_HAL_LIBUSB
#include "twister/hal/libusb_byte_stream.hpp"
#endif

namespace twister::station_app {
namespace {

// Buttons come from the tracker's stylus item: no device of their own.
class NoButtonSource final : public ports::ButtonSource, public hal::PollSource {
  Result<ports::ButtonEdge> do_poll() override { return StatusCode::unavailable; }
  std::uint8_t do_line_count() const override { return 0; }
  std::size_t do_poll_fds(std::span<pollfd>) const override { return 0; }
  Status do_reopen() override { return ok_status(); }
};

// Owns `device` through its port and keeps it as a PollSource too.
template <typename Port, typename Device>
void adopt(std::unique_ptr<Device> device, std::unique_ptr<Port>& port, hal::PollSource*& poll) {
  poll = device.get();
  port = std::move(device);
}

#if defined(TWISTER_HAVE_HAL_GPIOD) || defined(TWISTER_HAVE_HAL_HIDAPI)
// A button device that is not there (yet: `opened` is unavailable) does not stop the
// station: its backend is kept closed, the station runs without buttons and the loop
// opens it when it appears (the log and the display say so). Any other failure does.
bool stops_the_station(const Status& opened) {
  return !opened.ok() && opened.code() != StatusCode::unavailable;
}
template <typename Device>
void adopt_buttons(std::unique_ptr<Device> device, const Status& opened, std::string name,
                   Backends& out) {
  adopt(std::move(device), out.buttons, out.buttons_poll);
  out.buttons_name = std::move(name) + (opened.ok() ? "" : " (missing)");
}
#endif

hal::Expected<void> make_sim_tracker(const StationFileConfig& config, Backends& out) {
  const SimTrackerConfig& s = config.tracker.sim;
  auto loaded = s.scenario_file.empty() ? sim::load_builtin_scenario(s.scenario)
                                        : sim::load_scenario_file(s.scenario_file);
  if (!loaded) return loaded.error();
  sim::Scenario scenario = std::move(*loaded);
  out.tracker_name = "sim " + (s.scenario_file.empty() ? s.scenario : s.scenario_file);
  if (s.unplug_at_ms > 0) {
    scenario.faults.push_back(
        {s.unplug_at_ms / 1000.0, sim::FaultKind::hangup, s.replug_after_ms / 1000.0});
  }
  out.scenario_duration_s = scenario.duration_s;
  if (s.time == SimTime::virtual_time) {
    auto clock = std::make_unique<sim::VirtualClock>(1'000'000);
    out.virtual_clock = clock.get();
    out.clock = std::move(clock);
    out.tracker_name += " (virtual time)";
  } else {
    out.clock = std::make_unique<hal::MonotonicClock>();
    out.tracker_name += " (real time)";
  }
  sim::FastrakDeviceConfig device{};
  device.baud = static_cast<int>(config.tracker.serial.baud);
  // A unit whose binary format is the 16-bit packed one answers `f` with it.
  device.packed16 = config.tracker.format == RecordFormat::binary16;
  // The simulated unit is the model configured (its binary frames follow it).
  device.model = config.tracker.model == TrackerModel::liberty   ? sim::DeviceModel::liberty
                 : config.tracker.model == TrackerModel::patriot ? sim::DeviceModel::patriot
                                                                 : sim::DeviceModel::fastrak;
  // Scenario time 0 for both: the device powers up at this instant.
  const ports::TimestampUs start_us = out.clock->now_us();
  if (config.buttons.backend == ButtonBackend::sim) {
    out.buttons_name = "sim (" + std::to_string(scenario.buttons.size()) + " scripted events)";
    adopt(std::make_unique<sim::SimButtonSource>(*out.clock, scenario.buttons, start_us,
                                                 std::uint8_t{6}),
          out.buttons, out.buttons_poll);
  }
  adopt(std::make_unique<sim::SimFastrakStream>(*out.clock, device, std::move(scenario)),
        out.tracker, out.tracker_poll);
  return {};
}

#ifdef TWISTER_HAVE_HAL_TERMIOS
void make_serial_tracker(const SerialTrackerConfig& sc, Backends& out) {
  out.clock = std::make_unique<hal::MonotonicClock>();
  hal::TermiosConfig tc;
  tc.path = sc.device;
  tc.baud = static_cast<int>(sc.baud);
  tc.flow = sc.flow_control == SerialFlowControl::rtscts    ? hal::FlowControl::rts_cts
            : sc.flow_control == SerialFlowControl::xonxoff ? hal::FlowControl::xon_xoff
                                                            : hal::FlowControl::none;
  // Not opened here: the Fastrak session opens it, and keeps retrying while the
  // adapter is unplugged, so a station may start before its tracker is plugged.
  adopt(std::make_unique<hal::TermiosByteStream>(tc), out.tracker, out.tracker_poll);
  out.tracker_name = "serial " + sc.device + " at " + std::to_string(sc.baud) + " baud";
}
#endif

#ifdef TWISTER_HAVE_HAL_LIBUSB
hal::Expected<void> make_usb_tracker(const UsbTrackerConfig& uc, Backends& out) {
  out.clock = std::make_unique<hal::MonotonicClock>();
  auto stream = std::make_unique<hal::LibusbByteStream>(
      hal::LibusbConfig{uc.vendor_id, uc.product_id, uc.interface_number, uc.endpoint_in,
                        uc.endpoint_out, uc.timeout_ms});
  if (const Status st = stream->init(); !st.ok()) {
    return hal::Error{st, std::string("libusb: initialisation failed (") + st.name() +
                              ", libusb error " + std::to_string(stream->last_error()) + ")"};
  }
  // Opened by the Fastrak session, which retries while the tracker is unplugged.
  char ids[32];
  std::snprintf(ids, sizeof ids, "%04x:%04x", uc.vendor_id, uc.product_id);
  out.tracker_name = std::string("usb ") + ids + (stream->hotplug_supported() ? " (hot-plug)" : "");
  adopt(std::move(stream), out.tracker, out.tracker_poll);
  return {};
}
#endif

#ifdef TWISTER_HAVE_HAL_GPIOD
hal::Expected<void> make_gpiod_buttons(const GpiodButtonsConfig& config, Backends& out) {
  auto src = std::make_unique<hal::GpiodButtonSource>();
  hal::GpiodButtonConfig gc;
  gc.chip = config.chip;
  gc.lines = config.lines;
  gc.active_low = config.active_low;
  gc.bias = static_cast<hal::GpiodButtonConfig::Bias>(config.bias);
  const Status s = src->open(gc);
  if (stops_the_station(s)) {
    return hal::Error{s, "gpiod: cannot request lines on " + gc.chip + " (" + s.name() +
                             ", errno " + std::to_string(src->last_errno()) + ")"};
  }
  adopt_buttons(std::move(src), s, "gpiod " + gc.chip, out);
  return {};
}
#endif

#ifdef TWISTER_HAVE_HAL_HIDAPI
hal::Expected<void> make_hidapi_buttons(const HidapiButtonsConfig& config, Backends& out) {
  auto src = std::make_unique<hal::HidapiButtonSource>(*out.clock);
  hal::HidapiButtonConfig hc;
  hc.vendor_id = config.vendor_id;
  hc.product_id = config.product_id;
  hc.path = config.path;
  for (const auto& b : config.buttons) hc.buttons.push_back({b.byte, b.mask});
  const Status s = src->open(hc);
  if (stops_the_station(s)) {
    return hal::Error{s, std::string("hidapi: cannot open the button device (") + s.name() + ")"};
  }
  adopt_buttons(std::move(src), s, "hidapi", out);
  return {};
}
#endif

hal::Expected<void> make_tracker(const StationFileConfig& config, Backends& out) {
  switch (config.tracker.backend) {
    case TrackerBackend::sim:
      return make_sim_tracker(config, out);
    case TrackerBackend::serial:
#ifdef TWISTER_HAVE_HAL_TERMIOS
      make_serial_tracker(config.tracker.serial, out);
#endif
      return {};
    case TrackerBackend::usb:
#ifdef TWISTER_HAVE_HAL_LIBUSB
      return make_usb_tracker(config.tracker.usb, out);
#endif
      return {};
  }
  return {};
}

hal::Expected<void> make_buttons(const StationFileConfig& config, Backends& out) {
  switch (config.buttons.backend) {
    case ButtonBackend::sim:
      // Built with the simulated tracker (same scenario, same clock).
      if (!out.buttons) {
        return hal::make_error(StatusCode::invalid_argument,
                               "button backend \"sim\" needs tracker backend \"sim\"");
      }
      return {};
    case ButtonBackend::stylus:
      adopt(std::make_unique<NoButtonSource>(), out.buttons, out.buttons_poll);
      out.buttons_name = "stylus of receiver 1";
      return {};
    case ButtonBackend::gpiod:
#ifdef TWISTER_HAVE_HAL_GPIOD
      return make_gpiod_buttons(config.buttons.gpiod, out);
#endif
      return {};
    case ButtonBackend::hidapi:
#ifdef TWISTER_HAVE_HAL_HIDAPI
      return make_hidapi_buttons(config.buttons.hidapi, out);
#endif
      return {};
  }
  return {};
}

}  // namespace

bool tracker_backend_built(TrackerBackend b) {
  switch (b) {
    case TrackerBackend::sim:
      return true;
#ifdef TWISTER_HAVE_HAL_TERMIOS
    case TrackerBackend::serial:
      return true;
#endif
#ifdef TWISTER_HAVE_HAL_LIBUSB
    case TrackerBackend::usb:
      return true;
#endif
    default:
      return false;
  }
}

bool button_backend_built(ButtonBackend b) {
  switch (b) {
    case ButtonBackend::stylus:
    case ButtonBackend::sim:
      return true;
#ifdef TWISTER_HAVE_HAL_GPIOD
    case ButtonBackend::gpiod:
      return true;
#endif
#ifdef TWISTER_HAVE_HAL_HIDAPI
    case ButtonBackend::hidapi:
      return true;
#endif
    default:
      return false;
  }
}

hal::Expected<Backends> make_backends(const StationFileConfig& config) {
  if (!tracker_backend_built(config.tracker.backend)) {
    return hal::make_error(StatusCode::not_supported, std::string("tracker backend \"") +
                                                          to_string(config.tracker.backend) +
                                                          "\" is not built into this binary");
  }
  if (!button_backend_built(config.buttons.backend)) {
    return hal::make_error(StatusCode::not_supported, std::string("button backend \"") +
                                                          to_string(config.buttons.backend) +
                                                          "\" is not built into this binary");
  }
  Backends out;
  if (auto made = make_tracker(config, out); !made) return made.error();
  if (auto made = make_buttons(config, out); !made) return made.error();
  return out;
}

}  // namespace twister::station_app
