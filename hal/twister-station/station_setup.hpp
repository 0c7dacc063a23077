// Translation of the validated station.toml (hal::StationFileConfig) into the core's
// station::StationConfig: Fastrak protocol (enabled receivers, output lists incl.
// the stylus item when it is the button source), session timings, pose
// conversion, debounce, and the stylus-to-button-line binding. Init-time only.
#pragma once

#include "config/station_config.hpp"
#include "twister/hal/expected.hpp"
#include "twister/link/link_message.hpp"
#include "twister/station/station.hpp"

namespace twister::station_app {

// invalid_argument: the combination cannot run (the message says why).
hal::Expected<station::StationConfig> make_station_setup(const StationFileConfig& config);

// The work frame as the pose conversion's world transform: model = R^T (p - origin),
// R's columns the unit x_axis, y_axis (made perpendicular to x) and x_axis x y_axis.
void apply_work_frame(const WorkFrameConfig& wf, tracker::PoseConversion& conv);

// What the display frames (link `workspace`): [tracker.calibration.work_volume] when
// given; else with a work frame 0.6 x 0.6 m around the origin, 0.4 m high (+Z up);
// else the tracker's range (the Fastrak's specified 0.76 m) in the hemisphere's
// half-space of the transmitter frame (up -Z).
link::Workspace workspace_of(const CalibrationConfig& cal);

}  // namespace twister::station_app
