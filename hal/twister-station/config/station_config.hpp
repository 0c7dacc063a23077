// StationFileConfig: everything twister-station reads from its TOML file, already
// validated. parse_station_config() checks every key, type and value and reports
// each problem with file, line, the key's dotted name and the expected form; a
// config with any error is refused as a whole (the station never guesses).
// The messages are documented in docs/hardware.md ("Config errors").
// Init-time code: allocates freely, never throws.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace twister::station_app {

enum class TrackerBackend : std::uint8_t { serial, usb, sim };
enum class ButtonBackend : std::uint8_t { gpiod, hidapi, stylus, sim };
enum class SerialFlowControl : std::uint8_t { none, rtscts, xonxoff };
enum class GpioBias : std::uint8_t { as_is, disable, pull_up, pull_down };
enum class RecordFormat : std::uint8_t { binary, ascii, binary16 };
// The Polhemus unit on the line: its binary records are Fastrak records (FASTRAK,
// FASTRAK 3) or Liberty / Patriot / Latus frames (docs/liberty-protocol.md).
enum class TrackerModel : std::uint8_t { fastrak, liberty, patriot, latus };
enum class SimTime : std::uint8_t { virtual_time, real_time };

struct SerialTrackerConfig {
  std::string device;           // e.g. /dev/twister-fastrak (udev symlink)
  std::uint32_t baud = 115200;  // one of 2400 ... 115200
  SerialFlowControl flow_control = SerialFlowControl::none;
};

// [tracker.usb], optional: without it the station finds any Polhemus tracker of the
// model (tracker.model, else any) by its product id (docs/hardware.md, "USB trackers").
struct UsbTrackerConfig {
  std::uint16_t vendor_id = 0x0f44;  // Polhemus
  std::uint16_t product_id = 0;      // 0: by the model's ids
  std::uint8_t interface_number = 0;
  std::uint8_t endpoint_in = 0;    // bulk IN (bit 7 set); 0: the interface's first
  std::uint8_t endpoint_out = 0;   // bulk OUT (bit 7 clear); 0: the interface's first
  std::uint32_t timeout_ms = 100;  // per bulk transfer
};

struct SimTrackerConfig {
  std::string scenario = "stroke";  // built-in scenario name
  std::string scenario_file;        // scenario text file (sim/ format); wins when set
  SimTime time = SimTime::virtual_time;
  std::uint32_t unplug_at_ms = 0;     // 0 = never; else simulated unplug at this time
  std::uint32_t replug_after_ms = 0;  // how long the simulated tracker stays unplugged
};

// The unit's adaptive filter (`x` position, `v` attitude): left as the unit has it, off,
// or the four parameters (the defaults are the manual's "medium").
struct FilterConfig {
  enum class Mode : std::uint8_t { unit, off, set };
  Mode mode = Mode::unit;
  double f = 0.2;
  double flow = 0.2;
  double fhigh = 0.8;
  double factor = 0.95;
};

// The rigid transform from the transmitter frame to the model's frame, in transmitter
// coordinates (metres): the model's origin and its +X and +Y directions (+Z = X x Y is
// the model's up). y_axis is made exactly perpendicular to x_axis (Gram-Schmidt).
struct WorkFrameConfig {
  std::array<double, 3> origin{};
  std::array<double, 3> x_axis{1.0, 0.0, 0.0};
  std::array<double, 3> y_axis{0.0, 1.0, 0.0};
};
// How far from perpendicular x_axis and y_axis may be (typed or measured values).
inline constexpr double kMaxWorkFrameSkewDeg = 2.0;

// The hands' working volume (an axis-aligned box in the model's frame, metres): what
// the kiosk and offscreen cameras frame (sent to the display in the link's
// `workspace` message). Absent: 0.6 x 0.6 m by 0.4 m high above the origin with a work
// frame; without one, the tracker's range in the hemisphere's half-space.
struct WorkVolumeConfig {
  std::array<double, 3> min{};
  std::array<double, 3> max{};
};

// [tracker.calibration]: applied to both hands' receivers (the tip offset to receiver 1,
// the stylus).
struct CalibrationConfig {
  std::array<int, 3> hemisphere{1, 0, 0};  // `H` direction, transmitter frame
  bool boresight = false;                  // orientations relative to boresight_deg
  std::array<double, 3> boresight_deg{};   // az, el, roll that read as the reference
  std::array<double, 3> boresight_reference_deg{};
  std::array<double, 3> tip_offset_m{};  // receiver 1, receiver coordinates
  FilterConfig position_filter;
  FilterConfig attitude_filter;
  bool has_work_frame = false;
  WorkFrameConfig work_frame;
  bool has_work_volume = false;
  WorkVolumeConfig work_volume;
};

struct TrackerConfig {
  TrackerBackend backend = TrackerBackend::serial;
  TrackerModel model = TrackerModel::fastrak;
  bool model_given = false;       // tracker.model written (else usb detects it at start)
  std::uint8_t left_station = 1;  // Fastrak receiver (1..4) held in the left hand
  std::uint8_t right_station = 2;
  RecordFormat format = RecordFormat::binary;
  std::uint32_t reconnect_interval_ms = 1000;
  std::uint32_t silence_timeout_ms = 500;  // no record for this long = tracker lost
  SerialTrackerConfig serial;
  UsbTrackerConfig usb;
  SimTrackerConfig sim;
  CalibrationConfig calibration;
};

struct HidButtonBit {
  std::uint8_t byte = 0;  // index into the input report (0 = report id if numbered)
  std::uint8_t mask = 0;  // bit(s) that mean "pressed"
};

struct GpiodButtonsConfig {
  std::string chip = "gpiochip0";    // name, number or /dev path
  std::vector<std::uint32_t> lines;  // line offsets; button i = lines[i]
  bool active_low = true;
  GpioBias bias = GpioBias::as_is;
};

struct HidapiButtonsConfig {
  std::uint16_t vendor_id = 0;
  std::uint16_t product_id = 0;
  std::string path;                   // hidraw path; overrides the ids when set
  std::vector<HidButtonBit> buttons;  // button i = buttons[i]
};

struct ButtonsConfig {
  ButtonBackend backend = ButtonBackend::gpiod;
  std::uint32_t debounce_ms = 10;
  GpiodButtonsConfig gpiod;
  HidapiButtonsConfig hidapi;
};

struct StationSection {
  std::string journal;  // append-only stroke journal (fsynced per stroke)
  std::string mesh;     // initial model (OBJ, metres); relative = to the config file
  // Extra mesh capacity beyond the OBJ's vertices (and twice as many triangles):
  // refinement's room. Default: session::kDefaultSpareVertices (a test checks).
  std::uint32_t spare_vertices = 100'000;
  std::uint32_t loop_timeout_ms = 10;       // poll() timeout of the event loop
  std::uint32_t checkpoint_interval = 256;  // journal records between checkpoints (0: at stop)
};

enum class SculptMethod : std::uint8_t { twister, rottran, scodef };
enum class TurnTrackingMode : std::uint8_t { unwrapped, minimal };

// What a button of [sculpt.buttons.left/right] does (the key names).
enum class SculptAction : std::uint8_t {
  grab,
  radius,
  freeze,
  move_object,
  undo,
  redo,
  method_cycle,
  symmetry_cycle,
};
inline constexpr std::size_t kSculptActionCount = 8;
// The key of an action: "grab", "radius", "freeze", "move_object", "undo", "redo",
// "method_cycle", "symmetry_cycle".
const char* to_string(SculptAction a);

// Button lines: line i is buttons.gpiod.lines[i] or buttons.hidapi.buttons[i];
// 0..15 for the simulator's scripted buttons.
inline constexpr std::uint8_t kMaxSculptButtonLines = 16;
inline constexpr std::size_t kMaxSculptChordLines = 3;
inline constexpr std::size_t kMaxSculptChords = 8;

struct ButtonBindingConfig {
  SculptAction action = SculptAction::grab;
  std::uint8_t hand = 0;  // 0 left, 1 right
  // One line, or a chord: the lines to hold, then the one to press (the trigger).
  std::vector<std::uint8_t> lines;
  std::uint32_t file_line = 0;  // where it is written (for messages)
};

// [sculpt] symmetry (docs/math.md §11): every stroke mirrored in coordinate planes of
// the object frame, or repeated n times about one of its axes (optionally with the
// mirrors through that axis).
enum class SymmetryMode : std::uint8_t { none, mirrors, rotation };

inline constexpr std::size_t kMaxSymmetryCycle = 8;  // session::kMaxSymmetryCycle

struct SymmetryConfig {
  SymmetryMode mode = SymmetryMode::none;
  std::uint8_t mirrors = 0;  // mirrors: bit 0 the plane x = 0, bit 1 y = 0, bit 2 z = 0
  std::uint8_t axis = 2;     // rotation: 0 x, 1 y, 2 z (symmetry_axis)
  std::uint8_t order = 6;    // rotation: n = 2..12 (symmetry_order)
  bool mirror = false;       // rotation: also the n mirrors through the axis
};

struct SculptConfig {
  SculptMethod method = SculptMethod::twister;
  double radius_m = 0.25;  // start radius of the influence ball
  double radius_min_m = 0.02;
  double radius_max_m = 2.0;
  bool radius_gesture = true;  // both radius buttons + hands apart/together scale it
  TurnTrackingMode turn_tracking = TurnTrackingMode::unwrapped;
  double turn_limit_deg = 330.0;        // one stroke turns at most this far (unwrapped)
  std::uint32_t lost_timeout_ms = 500;  // a stroke with tracking lost longer is cancelled
  // Adaptive refinement at commit into station.spare_vertices (docs/refinement.md).
  bool refine = true;
  // Largest midpoint error an edge keeps (absolute). Default:
  // session::kDefaultRefineThresholdM (a test checks).
  double refine_threshold_m = 0.0005;
  SymmetryConfig symmetry{};
  // symmetry_cycle: the groups the symmetry_cycle chord / a display's key step through
  // ("rot" entries use symmetry_axis/order/mirror); empty: none and `symmetry`.
  std::vector<SymmetryConfig> symmetry_cycle;
  bool buttons_configured = false;  // [sculpt.buttons] given (else the paper's map)
  std::vector<ButtonBindingConfig> buttons;
};

enum class LinkListen : std::uint8_t { loopback, network };

// [link]: the display link (docs/hardware.md "Display link"). --link overrides
// the address.
struct LinkSection {
  std::string address;               // unix:PATH | tcp:A.B.C.D:PORT | serial:DEVICE; "" = none
  std::uint32_t socket_mode = 0660;  // the Unix socket file's mode, whatever the umask
  std::string socket_group;          // its group ("" = the service user's)
  LinkListen listen = LinkListen::loopback;  // network: TCP beyond loopback (needs psk_file)
  std::string psk_file;                      // pre-shared key file (64 hex digits, mode 0600)
  // A TCP link without psk_file lets any local user take the display: refused at
  // start unless this is set (Unix sockets with a group are the keyless default).
  bool allow_unauthenticated_tcp = false;
  std::uint32_t baud = 230400;  // serial: addresses
  // Spectators (issue 25): read-only displays beside the main one, each authenticated
  // like it (unix:/tcp: only; 0 = none). One that takes no byte for
  // spectator_stall_seconds is dropped.
  std::uint32_t max_spectators = 4;
  double spectator_stall_seconds = 5.0;
};

struct SystemdConfig {
  bool notify = true;    // READY=1 / STOPPING=1 via sd_notify (no-op without systemd)
  bool watchdog = true;  // WATCHDOG=1 at half of WATCHDOG_USEC when the unit sets it
};

// [exhibit] (issue 25; docs/hardware.md): exhibit mode, off by default.
struct ExhibitSection {
  bool enabled = false;
  std::string archive_dir;                        // REQUIRED when enabled; created when missing
  double idle_seconds = 90.0;                     // no grab, no hand motion: the sculpture ends
  double grace_seconds = 6.0;                     // the end can be undone (model kept) this long
  std::vector<std::uint8_t> new_sculpture_chord;  // lines held together; empty: none
  double chord_hold_seconds = 1.5;
  double motion_threshold_m = 0.02;      // a hand moving less is idle
  double retry_seconds = 5.0;            // a failed archive is tried again after
  std::uint32_t keep_archives = 500;     // retention: archives kept (count) ...
  std::uint64_t keep_archive_mb = 2048;  // ... and MiB
};

// [health]: the fleet metrics (hal/health; docs/exhibit.md "Fleet health").
struct HealthSection {
  // Prometheus text for node_exporter's textfile collector ("" = none); relative to
  // the config file's folder. Refused at start when a file there is not ours.
  std::string metrics_file;
  double period_s = 15.0;  // between writes of the file and of systemd STATUS=
  std::string
      archive_path;    // whose file system's free space is reported ("" = the journal's folder)
  bool status = true;  // systemd STATUS= (with [systemd] notify)
};

struct StationFileConfig {
  StationSection station;
  TrackerConfig tracker;
  ButtonsConfig buttons;
  SculptConfig sculpt;
  SystemdConfig systemd;
  LinkSection link;
  ExhibitSection exhibit;
  HealthSection health;
};

// One problem in a config file. to_string(): "FILE:LINE: KEY: MESSAGE".
struct ConfigError {
  std::string file;
  std::uint32_t line = 0;  // 1-based; 0 when the file could not be read at all
  std::string key;         // dotted name ("tracker.serial.baud"); empty for syntax errors
  std::string message;     // what was wrong and the expected form
  std::string to_string() const;
};

struct ConfigParseResult {
  StationFileConfig config;
  std::vector<ConfigError> errors;  // empty = valid
  bool ok() const { return errors.empty(); }
};

// Parses TOML text. file_name only labels the messages.
ConfigParseResult parse_station_config(std::string_view text, std::string_view file_name);

// Longest config file read (a station config is a few KiB).
inline constexpr std::size_t kMaxConfigBytes = std::size_t{1} << 20;

// Reads and parses a file; an unreadable file, one that is not a regular file (FIFO,
// device, directory) or one larger than kMaxConfigBytes is one error with line 0.
ConfigParseResult load_station_config(const std::string& path);

// How many button lines the configured button backend provides: gpiod lines, hidapi
// buttons, 16 scripted simulator lines, 1 for the stylus.
std::size_t button_line_count(const StationFileConfig& config);

// Short names used in logs and messages ("serial", "gpiod", ...).
const char* to_string(TrackerBackend b);
const char* to_string(ButtonBackend b);

}  // namespace twister::station_app
