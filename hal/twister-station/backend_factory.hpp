// Backend factory of twister-station (composition root only): builds the clock,
// tracker ByteStream and ButtonSource named in the config, or says which backend
// is not built into this binary / failed to open. Init-time; allocates.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "config/station_config.hpp"
#include "twister/hal/device_report.hpp"
#include "twister/hal/expected.hpp"
#include "twister/hal/poll_source.hpp"
#include "twister/ports/button_source.hpp"
#include "twister/ports/byte_stream.hpp"
#include "twister/ports/clock.hpp"
#include "twister/sim/virtual_clock.hpp"

namespace twister::station_app {

// Each device backend is owned through its port; `*_poll` is the same object seen
// as a PollSource (the loop's descriptors, and reopen after a failure).
struct Backends {
  std::unique_ptr<ports::Clock> clock;
  sim::VirtualClock* virtual_clock = nullptr;  // set when the simulator runs in virtual time
  std::unique_ptr<ports::ByteStream> tracker;
  hal::PollSource* tracker_poll = nullptr;  // never null after make_backends
  std::unique_ptr<ports::ButtonSource> buttons;
  hal::PollSource* buttons_poll = nullptr;  // never null after make_backends
  double scenario_duration_s = 0.0;         // simulator: the scenario's length (0 = none)
  std::string tracker_name;                 // for the log: "serial /dev/...", "sim stroke", ...
  std::string buttons_name;
  // A tracker backend that searches for its device (usb): what it found, logged by the
  // loop at start and on every change. nullptr for the others.
  const hal::DeviceReport* tracker_report = nullptr;
  // usb without tracker.model: the model of the tracker found at start, if one was.
  std::optional<TrackerModel> detected_model;
};

// The configuration the station runs with: `config` with the tracker model the
// backends detected (usb without tracker.model) in place of the default.
StationFileConfig with_detected_model(const StationFileConfig& config, const Backends& backends);

// Builds every backend. usb: the tracker is searched for once (the model found decides
// tracker.model when it is not given; a unit of another model than the one given is an
// error). Errors name the backend: not_supported ("tracker backend
// \"usb\" is not built into this binary"), invalid_argument (a combination or
// scenario that cannot run), or the status of the device that failed to open. A
// button device that is not there (unavailable) is no error: its backend is built
// closed (connected() false) and the loop opens it when it appears.
hal::Expected<Backends> make_backends(const StationFileConfig& config);

// Which backends this binary was built with (for --check and --help).
bool tracker_backend_built(TrackerBackend b);
bool button_backend_built(ButtonBackend b);

}  // namespace twister::station_app
