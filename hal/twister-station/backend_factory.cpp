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
// The models a station configured for `model` reads (a FASTRAK 3 is a fastrak).
std::uint8_t usb_models(TrackerModel model) {
  using hal::PolhemusUsbModel;
  switch (model) {
    case TrackerModel::fastrak:
      return hal::polhemus_model_bit(PolhemusUsbModel::fastrak) |
             hal::polhemus_model_bit(PolhemusUsbModel::fastrak3);
    case TrackerModel::liberty:
      return hal::polhemus_model_bit(PolhemusUsbModel::liberty);
    case TrackerModel::patriot:
      return hal::polhemus_model_bit(PolhemusUsbModel::patriot);
    case TrackerModel::latus:
      return hal::polhemus_model_bit(PolhemusUsbModel::latus);
  }
  return 0;
}

std::optional<TrackerModel> station_model(const hal::PolhemusUsbId* id) {
  if (id == nullptr) return std::nullopt;
  switch (id->model) {
    case hal::PolhemusUsbModel::fastrak:
    case hal::PolhemusUsbModel::fastrak3:
      return TrackerModel::fastrak;
    case hal::PolhemusUsbModel::liberty:
      return TrackerModel::liberty;
    case hal::PolhemusUsbModel::patriot:
      return TrackerModel::patriot;
    case hal::PolhemusUsbModel::latus:
      return TrackerModel::latus;
    case hal::PolhemusUsbModel::unsupported:
      break;
  }
  return std::nullopt;
}

hal::Expected<void> make_usb_tracker(const TrackerConfig& tc, Backends& out) {
  const UsbTrackerConfig& uc = tc.usb;
  out.clock = std::make_unique<hal::MonotonicClock>();
  hal::LibusbConfig lc;
  lc.vendor_id = uc.vendor_id;
  lc.product_id = uc.product_id;
  lc.interface_number = uc.interface_number;
  lc.endpoint_in = uc.endpoint_in;
  lc.endpoint_out = uc.endpoint_out;
  lc.timeout_ms = uc.timeout_ms;
  std::unique_ptr<hal::LibusbByteStream> stream;
  // A stream looking for `models`, searched once: the model to start the session for,
  // and the first report line. Not opened here: the tracker session opens it, and
  // keeps retrying while the tracker is unplugged.
  auto make = [&](std::uint8_t models) -> hal::Expected<void> {
    lc.models = models;
    stream = std::make_unique<hal::LibusbByteStream>(lc);
    if (const Status st = stream->init(); !st.ok()) {
      return hal::Error{st, std::string("libusb: initialisation failed (") + st.name() +
                                ", libusb error " + std::to_string(stream->last_error()) + ")"};
    }
    stream->probe().ignore();
    return {};
  };
  // With tracker.model (or a product id) that model's ids only.
  if (auto made = make(tc.model_given ? usb_models(tc.model) : hal::kAnyReadablePolhemus); !made)
    return made.error();
  if (!tc.model_given && lc.product_id == 0) {
    // From now on the model found at start only, so a unit of another model plugged
    // later is reported, not read with the wrong parser. Nothing readable at start:
    // the session starts as a FASTRAK (tracker.model's default), and only those are
    // looked for (the report says so).
    const hal::UsbTrackerFound* found = stream->found();
    out.detected_model = found != nullptr ? station_model(found->id) : std::nullopt;
    if (auto made = make(usb_models(out.detected_model.value_or(TrackerModel::fastrak))); !made)
      return made.error();
  }
  // "usb 0f44:ff12 (hot-plug)", or "usb Polhemus 0f44:* (hot-plug)" by the model's ids.
  char ids[48];
  if (lc.product_id != 0) {
    std::snprintf(ids, sizeof ids, "%04x:%04x", lc.vendor_id, lc.product_id);
  } else {
    std::snprintf(ids, sizeof ids, "Polhemus %04x:*", lc.vendor_id);
  }
  out.tracker_name = std::string("usb ") + ids + (stream->hotplug_supported() ? " (hot-plug)" : "");
  out.tracker_report = stream.get();
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
      return make_usb_tracker(config.tracker, out);
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

StationFileConfig with_detected_model(const StationFileConfig& config, const Backends& backends) {
  StationFileConfig effective = config;
  if (backends.detected_model) effective.tracker.model = *backends.detected_model;
  return effective;
}

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
