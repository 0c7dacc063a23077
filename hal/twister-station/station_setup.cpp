#include "station_setup.hpp"

#include <algorithm>

namespace twister::station_app {
namespace {

input::ButtonRole role_of(SculptAction a) {
  switch (a) {
    case SculptAction::grab:
      return input::ButtonRole::grab;
    case SculptAction::radius:
      return input::ButtonRole::radius;
    case SculptAction::freeze:
      return input::ButtonRole::freeze;
    case SculptAction::move_object:
      return input::ButtonRole::move_object;
    case SculptAction::undo:
      return input::ButtonRole::undo;
    case SculptAction::redo:
      return input::ButtonRole::redo;
    case SculptAction::method_cycle:
      return input::ButtonRole::method_cycle;
    case SculptAction::symmetry_cycle:
      return input::ButtonRole::symmetry_cycle;
  }
  return input::ButtonRole::none;
}

math::WarpMethod method_of(SculptMethod m) {
  switch (m) {
    case SculptMethod::twister:
      return math::WarpMethod::twister;
    case SculptMethod::rottran:
      return math::WarpMethod::rottran;
    case SculptMethod::scodef:
      return math::WarpMethod::scodef;
  }
  return math::WarpMethod::twister;
}

math::SymmetrySpec symmetry_of(const SymmetryConfig& c) {
  switch (c.mode) {
    case SymmetryMode::none:
      return {};
    case SymmetryMode::mirrors:
      return {math::SymmetryKind::mirrors, c.mirrors, 0, 0};
    case SymmetryMode::rotation:
      return {c.mirror ? math::SymmetryKind::rotation_mirror : math::SymmetryKind::rotation, 0,
              c.axis, c.order};
  }
  return {};
}

// [sculpt]: method, radius, turns, lost-tracking timeout and the button map (the
// paper's map unless [sculpt.buttons] is given).
void set_sculpt(const StationFileConfig& config, session::SculptSessionConfig& s,
                std::string& error) {
  const SculptConfig& sc = config.sculpt;
  s.method = method_of(sc.method);
  s.interaction.initial_radius_m = static_cast<float>(sc.radius_m);
  s.interaction.radius_min_m = static_cast<float>(sc.radius_min_m);
  s.interaction.radius_max_m = static_cast<float>(sc.radius_max_m);
  s.interaction.radius_gesture = sc.radius_gesture;
  s.interaction.lost_timeout_us = static_cast<ports::TimestampUs>(sc.lost_timeout_ms) * 1000;
  s.turns.tracking = sc.turn_tracking == TurnTrackingMode::unwrapped
                         ? session::TurnTracking::unwrapped
                         : session::TurnTracking::minimal;
  s.turns.limit_rad = sc.turn_limit_deg * session::kDegree;
  s.refine.enabled = sc.refine;
  s.refine.threshold_m = sc.refine_threshold_m;
  s.symmetry = symmetry_of(sc.symmetry);
  s.symmetry_cycle = {};
  for (const SymmetryConfig& g : sc.symmetry_cycle) {
    if (!s.symmetry_cycle.push(symmetry_of(g)).ok() && error.empty()) {
      error = "sculpt.symmetry_cycle: not a symmetry group";
    }
  }
  if (!sc.buttons_configured) return;
  s.buttons = input::ButtonMap{};
  for (const ButtonBindingConfig& b : sc.buttons) {
    const Status bound = b.lines.size() == 1
                             ? s.buttons.bind(b.lines[0], b.hand, role_of(b.action))
                             : s.buttons.bind_chord(b.lines, b.hand, role_of(b.action));
    if (!bound.ok() && error.empty()) {
      error = std::string("sculpt.buttons: cannot bind ") + to_string(b.action) + " (" +
              bound.name() + ")";
    }
  }
}

// The line a hand's grab is on (-1: none): the stylus drives it.
int grab_line(const StationFileConfig& config, std::uint8_t hand) {
  if (!config.sculpt.buttons_configured) return hand == 0 ? 0 : 3;  // the paper's map
  for (const ButtonBindingConfig& b : config.sculpt.buttons) {
    if (b.action == SculptAction::grab && b.hand == hand && b.lines.size() == 1) return b.lines[0];
  }
  return -1;
}

tracker::FilterSetting filter_of(const FilterConfig& f) {
  tracker::FilterSetting out;
  out.mode = f.mode == FilterConfig::Mode::unit  ? tracker::FilterSetting::Mode::leave
             : f.mode == FilterConfig::Mode::off ? tracker::FilterSetting::Mode::off
                                                 : tracker::FilterSetting::Mode::set;
  out.f = static_cast<float>(f.f);
  out.flow = static_cast<float>(f.flow);
  out.fhigh = static_cast<float>(f.fhigh);
  out.factor = static_cast<float>(f.factor);
  return out;
}

glm::dvec3 vec(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }

}  // namespace

void apply_work_frame(const WorkFrameConfig& wf, tracker::PoseConversion& conv) {
  const glm::dvec3 x = glm::normalize(vec(wf.x_axis));
  const glm::dvec3 y = glm::normalize(vec(wf.y_axis) - glm::dot(vec(wf.y_axis), x) * x);
  const glm::dmat3 axes(x, y, glm::cross(x, y));  // columns: the model's axes
  conv.world_rotation = glm::transpose(axes);
  conv.world_translation_m = -(conv.world_rotation * vec(wf.origin));
}

link::Workspace workspace_of(const CalibrationConfig& cal) {
  link::Workspace w;
  if (cal.has_work_frame) {
    w.flags = link::kWorkspaceCalibrated;
    w.up = {0.0F, 0.0F, 1.0F};
    w.min = {-0.30F, -0.30F, 0.0F};
    w.max = {0.30F, 0.30F, 0.40F};
  } else {
    // The Fastrak's specified range (30 in) on the hemisphere's side of the transmitter.
    constexpr float kRange = 0.76F;
    const glm::vec3 h =
        glm::normalize(glm::vec3(cal.hemisphere[0], cal.hemisphere[1], cal.hemisphere[2]));
    const glm::vec3 centre = 0.5F * (kRange + 0.10F) * h;
    const glm::vec3 half(0.5F * (kRange - 0.10F));
    w.up = {0.0F, 0.0F, -1.0F};
    w.min = centre - half;
    w.max = centre + half;
  }
  if (cal.has_work_volume) {
    w.flags = static_cast<std::uint8_t>(w.flags | link::kWorkspaceConfigured);
    w.min = glm::vec3(vec(cal.work_volume.min));
    w.max = glm::vec3(vec(cal.work_volume.max));
  }
  return w;
}

namespace {

// [tracker.calibration]: the unit's hemisphere and filters (sent by the session), and
// host-side: hemisphere (again, so a unit that ignored `H` is still mirrored), boresight,
// the stylus tip offset and the work frame (pose_conversion.hpp).
void set_calibration(const StationFileConfig& config, station::StationConfig& c) {
  const CalibrationConfig& cal = config.tracker.calibration;
  for (const std::uint8_t s : c.hand_station) {
    const auto i = static_cast<std::size_t>(s - 1);
    c.session.hemisphere[i] = cal.hemisphere;
    c.conversion.hemisphere[i] =
        glm::dvec3(cal.hemisphere[0], cal.hemisphere[1], cal.hemisphere[2]);
    c.conversion.boresight[i] = cal.boresight;
    if (cal.boresight) {
      c.conversion.boresight_rotation[i] = tracker::rotation_from_euler_deg(
          cal.boresight_deg[0], cal.boresight_deg[1], cal.boresight_deg[2]);
      c.conversion.boresight_reference_deg[i] = vec(cal.boresight_reference_deg);
    }
  }
  c.conversion.tool_offset_m[0] = vec(cal.tip_offset_m);
  c.session.position_filter = filter_of(cal.position_filter);
  c.session.attitude_filter = filter_of(cal.attitude_filter);
  if (cal.has_work_frame) apply_work_frame(cal.work_frame, c.conversion);
}

// [tracker]: receivers, output lists (the stylus item where it exists), timings.
void set_tracker(const StationFileConfig& config, station::StationConfig& c) {
  using tracker::Item;
  const TrackerConfig& t = config.tracker;
  auto& proto = c.session.protocol;
  // binary16: the 16-bit packed records, selected with `f` like binary (on a unit
  // whose binary format they are).
  proto.format = t.format == RecordFormat::binary  ? tracker::Format::binary
                 : t.format == RecordFormat::ascii ? tracker::Format::ascii
                                                   : tracker::Format::binary16;
  proto.units = tracker::Units::inches;
  // A Liberty / Patriot: the same commands and lists; its frames are read with the
  // Liberty parser (to_liberty_config of these lists). The config allows binary only.
  c.session.model = t.model == TrackerModel::liberty   ? tracker::TrackerModel::liberty
                    : t.model == TrackerModel::patriot ? tracker::TrackerModel::patriot
                    : t.model == TrackerModel::latus   ? tracker::TrackerModel::latus
                                                       : tracker::TrackerModel::fastrak;
  c.hand_station = {t.left_station, t.right_station};
  const bool stylus = config.buttons.backend == ButtonBackend::stylus;
  for (const std::uint8_t s : c.hand_station) {
    auto& st = proto.stations[static_cast<std::size_t>(s - 1)];
    st.enabled = true;
    // Quaternion: shortest orientation item; the stylus item only where it exists.
    st.list =
        stylus && s == 1
            ? tracker::OutputList::of({Item::position, Item::quaternion, Item::stylus, Item::crlf})
            : tracker::OutputList::of({Item::position, Item::quaternion, Item::crlf});
  }
  // USB: 50 ms between configuration commands, as VRPN's Liberty HS driver waits after
  // its `O` (a bulk OUT transfer completes only once the unit has taken the bytes, so
  // the pause covers processing alone); the serial line keeps the Fastrak's 100 ms.
  // Assumed, untried on a unit (docs/hardware.md, "USB trackers").
  if (t.backend == TrackerBackend::usb) c.session.command_pause_us = 50'000;
  c.session.silence_timeout_us = static_cast<std::int64_t>(t.silence_timeout_ms) * 1000;
  c.session.backoff.initial_us = static_cast<std::int64_t>(t.reconnect_interval_ms) * 1000;
  c.session.backoff.max_us = std::max<std::int64_t>(c.session.backoff.initial_us, 8'000'000);
  c.conversion.units = proto.units;
  c.conversion.format = proto.format;
  c.pose_stale_us = std::max<std::int64_t>(200'000, c.session.silence_timeout_us / 2);
}

// The stylus is the grab of the hand that holds receiver 1; "" or the problem.
std::string set_stylus(const StationFileConfig& config, station::StationConfig& c) {
  const TrackerConfig& t = config.tracker;
  const int hand = t.left_station == 1 ? 0 : t.right_station == 1 ? 1 : -1;
  if (hand < 0) {
    return "buttons.backend = \"stylus\" needs receiver 1 (the stylus) in a hand: set "
           "tracker.left_station or tracker.right_station to 1";
  }
  const int line = grab_line(config, static_cast<std::uint8_t>(hand));
  if (line < 0) {
    return std::string(
               "buttons.backend = \"stylus\" drives the grab of the hand holding receiver 1: "
               "set sculpt.buttons.") +
           (hand == 0 ? "left" : "right") + ".grab";
  }
  c.stylus_line[0] = static_cast<std::int8_t>(line);
  return {};
}

}  // namespace

// [exhibit] -> the station's exhibit mode (seconds to microseconds, lines to a mask).
void set_exhibit(const ExhibitSection& x, station::ExhibitConfig& c) {
  const auto us = [](double s) { return static_cast<ports::TimestampUs>(s * 1e6); };
  c.visitor.enabled = x.enabled;
  c.visitor.idle_us = us(x.idle_seconds);
  c.visitor.grace_us = us(x.grace_seconds);
  c.visitor.chord_hold_us = us(x.chord_hold_seconds);
  c.visitor.retry_us = us(x.retry_seconds);
  c.visitor.motion_threshold_m = x.motion_threshold_m;
  c.chord_lines = 0;
  for (const std::uint8_t l : x.new_sculpture_chord) {
    c.chord_lines = static_cast<std::uint16_t>(c.chord_lines | (1u << l));
  }
}

hal::Expected<station::StationConfig> make_station_setup(const StationFileConfig& config) {
  station::StationConfig c;
  set_tracker(config, c);
  set_calibration(config, c);
  c.checkpoint_interval = config.station.checkpoint_interval;
  set_exhibit(config.exhibit, c.exhibit);
  c.sculpt.debounce.interval_us.fill(static_cast<ports::TimestampUs>(config.buttons.debounce_ms) *
                                     1000);
  std::string error;
  set_sculpt(config, c.sculpt, error);
  // Every line the map may use reaches the debouncer (at least the paper's six).
  std::size_t lines = std::max<std::size_t>(6, button_line_count(config));
  for (const ButtonBindingConfig& b : config.sculpt.buttons) {
    for (const std::uint8_t l : b.lines) lines = std::max<std::size_t>(lines, l + 1u);
  }
  c.sculpt.debounce.line_count =
      static_cast<std::uint8_t>(std::min<std::size_t>(lines, input::kMaxButtonLines));
  if (config.buttons.backend == ButtonBackend::stylus && error.empty()) {
    error = set_stylus(config, c);
  }
  if (!error.empty()) return hal::make_error(StatusCode::invalid_argument, error);
  return c;
}

}  // namespace twister::station_app
