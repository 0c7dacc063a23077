// Schema of station.toml (documented key by key in hal/twister-station/deploy/station.toml).
// Every section is read through a ConfigReader, so each key is type/range checked
// and unknown keys are reported; cross-key rules (left != right receiver, backend
// needs its section) are checked here.
#include "config/station_config.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>

#include "calibration_config.hpp"
#include "config_reader.hpp"
#include "exhibit_config.hpp"
#include "health_config.hpp"
#include "link_config.hpp"
#include "sculpt_config.hpp"

namespace twister::station_app {
namespace {

using internal::ConfigReader;

template <typename T>
void read_u(ConfigReader& r, std::string_view key, bool required, std::int64_t min,
            std::int64_t max, T& out) {
  std::int64_t v = 0;
  if (r.integer(key, required, min, max, v)) out = static_cast<T>(v);
}

void read_tracker(ConfigReader& root, StationFileConfig& cfg) {
  ConfigReader t = root.table("tracker", true);
  TrackerConfig& tc = cfg.tracker;
  std::string backend;
  if (t.string("backend", t.present(), backend, {"serial", "usb", "sim"})) {
    tc.backend = backend == "serial" ? TrackerBackend::serial
                 : backend == "usb"  ? TrackerBackend::usb
                                     : TrackerBackend::sim;
  }
  read_u(t, "left_station", false, 1, 4, tc.left_station);
  read_u(t, "right_station", false, 1, 4, tc.right_station);
  if (tc.left_station == tc.right_station) {
    t.error(t.node("right_station"), "right_station",
            "expected a receiver different from tracker.left_station (both are " +
                std::to_string(tc.left_station) + ")");
  }
  std::string format;
  if (t.string("format", false, format, {"binary", "ascii", "binary16"})) {
    tc.format = format == "binary"  ? RecordFormat::binary
                : format == "ascii" ? RecordFormat::ascii
                                    : RecordFormat::binary16;
  }
  std::string model;
  if (t.string("model", false, model, {"fastrak", "liberty", "patriot", "latus"})) {
    tc.model = model == "fastrak"   ? TrackerModel::fastrak
               : model == "liberty" ? TrackerModel::liberty
               : model == "patriot" ? TrackerModel::patriot
                                    : TrackerModel::latus;
    tc.model_given = true;
  }
  // The simulator models the FASTRAK, Liberty and Patriot (twister-sim --model).
  if (tc.model == TrackerModel::latus && t.present() && backend == "sim") {
    t.error(t.node("model"), "model",
            "expected \"fastrak\", \"liberty\" or \"patriot\" with tracker.backend = \"sim\" "
            "(the simulator has no Latus), got \"latus\"");
  }
  // A Liberty's or Patriot's records are parsed as binary frames only.
  if (tc.model != TrackerModel::fastrak && tc.format != RecordFormat::binary) {
    t.error(t.node("format"), "format",
            "expected \"binary\" with tracker.model = \"" + model +
                "\" (its frames are "
                "read in binary only), got \"" +
                format + "\"");
  }
  read_u(t, "reconnect_interval_ms", false, 100, 60000, tc.reconnect_interval_ms);
  read_u(t, "silence_timeout_ms", false, 50, 10000, tc.silence_timeout_ms);

  const bool need_serial = t.present() && backend == "serial";
  ConfigReader s = t.table("serial", need_serial);
  s.string("device", s.present(), tc.serial.device);
  std::int64_t baud = 0;
  if (s.integer("baud", false, 1, 1'000'000, baud)) {
    constexpr std::int64_t kBauds[] = {2400, 4800, 9600, 19200, 38400, 57600, 115200};
    if (std::find(std::begin(kBauds), std::end(kBauds), baud) == std::end(kBauds)) {
      s.error(
          s.node("baud"), "baud",
          "expected one of 2400 4800 9600 19200 38400 57600 115200, got " + std::to_string(baud));
    } else {
      tc.serial.baud = static_cast<std::uint32_t>(baud);
    }
  }
  std::string flow;
  if (s.string("flow_control", false, flow, {"none", "rtscts", "xonxoff"})) {
    tc.serial.flow_control = flow == "none"     ? SerialFlowControl::none
                             : flow == "rtscts" ? SerialFlowControl::rtscts
                                                : SerialFlowControl::xonxoff;
  }
  s.finish();

  // Optional: the Polhemus vendor and the model's product ids by default.
  ConfigReader u = t.table("usb", false);
  read_u(u, "vendor_id", false, 1, 0xffff, tc.usb.vendor_id);
  read_u(u, "product_id", false, 0, 0xffff, tc.usb.product_id);
  read_u(u, "interface", false, 0, 255, tc.usb.interface_number);
  read_u(u, "endpoint_in", false, 0x81, 0x8f, tc.usb.endpoint_in);
  read_u(u, "endpoint_out", false, 0x01, 0x0f, tc.usb.endpoint_out);
  read_u(u, "timeout_ms", false, 1, 10000, tc.usb.timeout_ms);
  u.finish();

  ConfigReader m = t.table("sim", false);
  m.string("scenario", false, tc.sim.scenario, {"stroke", "idle", "unplug"});
  m.string("scenario_file", false, tc.sim.scenario_file);
  std::string time;
  if (m.string("time", false, time, {"virtual", "real"})) {
    tc.sim.time = time == "virtual" ? SimTime::virtual_time : SimTime::real_time;
  }
  read_u(m, "unplug_at_ms", false, 0, 3'600'000, tc.sim.unplug_at_ms);
  read_u(m, "replug_after_ms", false, 0, 3'600'000, tc.sim.replug_after_ms);
  m.finish();
  internal::read_calibration(t, tc);
  t.finish();
}

void read_gpiod(ConfigReader& b, ButtonsConfig& bc, bool required) {
  ConfigReader g = b.table("gpiod", required);
  g.string("chip", false, bc.gpiod.chip);
  if (const toml::array* lines = g.array("lines", g.present())) {
    if (lines->empty() || lines->size() > 8) {
      g.error(lines, "lines", "expected 1 to 8 line offsets, got " + std::to_string(lines->size()));
    }
    for (std::size_t i = 0; i < lines->size(); ++i) {
      const toml::node& n = *lines->get(i);
      const auto* v = n.as_integer();
      if (v == nullptr || v->get() < 0 || v->get() > 1023) {
        g.error(&n, "lines", "expected line offsets from 0 to 1023, got " + internal::describe(n));
        continue;
      }
      const auto off = static_cast<std::uint32_t>(v->get());
      if (std::find(bc.gpiod.lines.begin(), bc.gpiod.lines.end(), off) != bc.gpiod.lines.end()) {
        g.error(&n, "lines",
                "expected each line offset once, got " + std::to_string(off) + " twice");
        continue;
      }
      bc.gpiod.lines.push_back(off);
    }
  }
  g.boolean("active_low", bc.gpiod.active_low);
  std::string bias;
  if (g.string("bias", false, bias, {"as-is", "disable", "pull-up", "pull-down"})) {
    bc.gpiod.bias = bias == "as-is"     ? GpioBias::as_is
                    : bias == "disable" ? GpioBias::disable
                    : bias == "pull-up" ? GpioBias::pull_up
                                        : GpioBias::pull_down;
  }
  g.finish();
}

void read_hidapi(ConfigReader& b, ButtonsConfig& bc, bool required) {
  ConfigReader h = b.table("hidapi", required);
  h.string("path", false, bc.hidapi.path);
  const bool ids_required = h.present() && !h.has("path");
  read_u(h, "vendor_id", ids_required, 1, 0xffff, bc.hidapi.vendor_id);
  read_u(h, "product_id", ids_required, 0, 0xffff, bc.hidapi.product_id);
  if (const toml::array* buttons = h.array("buttons", h.present())) {
    if (buttons->empty() || buttons->size() > 8) {
      h.error(buttons, "buttons",
              "expected 1 to 8 buttons, got " + std::to_string(buttons->size()));
    }
    for (std::size_t i = 0; i < buttons->size(); ++i) {
      const toml::node& n = *buttons->get(i);
      const std::string key = "buttons[" + std::to_string(i) + "]";
      const toml::table* t = n.as_table();
      if (t == nullptr) {
        h.error(&n, key,
                "expected an inline table { byte = N, mask = M }, got " + internal::type_name(n));
        continue;
      }
      ConfigReader e = h.element(t, key);
      HidButtonBit bit;
      read_u(e, "byte", true, 0, 63, bit.byte);
      read_u(e, "mask", true, 1, 255, bit.mask);
      e.finish();
      bc.hidapi.buttons.push_back(bit);
    }
  }
  h.finish();
}

void read_buttons(ConfigReader& root, StationFileConfig& cfg) {
  ConfigReader b = root.table("buttons", true);
  ButtonsConfig& bc = cfg.buttons;
  std::string backend;
  if (b.string("backend", b.present(), backend, {"gpiod", "hidapi", "stylus", "sim"})) {
    bc.backend = backend == "gpiod"    ? ButtonBackend::gpiod
                 : backend == "hidapi" ? ButtonBackend::hidapi
                 : backend == "sim"    ? ButtonBackend::sim
                                       : ButtonBackend::stylus;
    // The scripted buttons are the simulator scenario's `button` lines.
    if (bc.backend == ButtonBackend::sim && cfg.tracker.backend != TrackerBackend::sim) {
      b.error(b.node("backend"), "backend",
              "\"sim\" plays the simulator scenario's button lines and needs "
              "tracker.backend = \"sim\"");
    }
  }
  read_u(b, "debounce_ms", false, 0, 200, bc.debounce_ms);
  read_gpiod(b, bc, b.present() && backend == "gpiod");
  read_hidapi(b, bc, b.present() && backend == "hidapi");
  b.finish();
}

void read_station(ConfigReader& root, StationFileConfig& cfg) {
  ConfigReader s = root.table("station", true);
  s.string("journal", s.present(), cfg.station.journal);
  s.string("mesh", s.present(), cfg.station.mesh);
  read_u(s, "spare_vertices", false, 0, 4'000'000, cfg.station.spare_vertices);
  read_u(s, "loop_timeout_ms", false, 1, 1000, cfg.station.loop_timeout_ms);
  read_u(s, "checkpoint_interval", false, 0, 1'000'000, cfg.station.checkpoint_interval);
  s.finish();
}

void read_systemd(ConfigReader& root, StationFileConfig& cfg) {
  ConfigReader d = root.table("systemd", false);
  d.boolean("notify", cfg.systemd.notify);
  d.boolean("watchdog", cfg.systemd.watchdog);
  d.finish();
}

}  // namespace

std::string ConfigError::to_string() const {
  std::string s = file + ":" + std::to_string(line) + ": ";
  if (!key.empty()) s += key + ": ";
  return s + message;
}

const char* to_string(TrackerBackend b) {
  switch (b) {
    case TrackerBackend::serial:
      return "serial";
    case TrackerBackend::usb:
      return "usb";
    case TrackerBackend::sim:
      return "sim";
  }
  return "?";
}

const char* to_string(ButtonBackend b) {
  switch (b) {
    case ButtonBackend::gpiod:
      return "gpiod";
    case ButtonBackend::hidapi:
      return "hidapi";
    case ButtonBackend::stylus:
      return "stylus";
    case ButtonBackend::sim:
      return "sim";
  }
  return "?";
}

ConfigParseResult parse_station_config(std::string_view text, std::string_view file_name) {
  ConfigParseResult out;
  // toml++ 3.3.0 (Debian 12) reaches __builtin_unreachable() on some non-ASCII input
  // (marzer/tomlplusplus#190, #295; found again by station_config_fuzz). Station configs
  // are plain ASCII, so non-ASCII bytes are refused before toml++ sees them.
  std::uint32_t line = 1;
  for (const char ch : text) {
    const auto byte = static_cast<unsigned char>(ch);
    if (byte == '\n') ++line;
    if (byte >= 0x80) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "0x%02X", byte);
      out.errors.push_back({std::string(file_name), line, "",
                            std::string("non-ASCII byte ") + hex +
                                "; the config must be plain ASCII (also in comments)"});
      return out;
    }
  }
  toml::parse_result parsed = toml::parse(text, file_name);
  if (!parsed) {
    const toml::parse_error& err = parsed.error();
    out.errors.push_back({std::string(file_name), internal::line_of(err.source()), "",
                          "TOML syntax error: " + std::string(err.description())});
    return out;
  }
  const toml::table& root_table = parsed.table();
  ConfigReader root(&root_table, "", file_name, out.errors);
  read_station(root, out.config);
  read_tracker(root, out.config);
  read_buttons(root, out.config);
  internal::read_sculpt(root, out.config);
  read_systemd(root, out.config);
  internal::read_link(root, out.config);
  internal::read_exhibit(root, out.config);
  internal::read_health(root, out.config);
  root.finish();
  std::stable_sort(out.errors.begin(), out.errors.end(),
                   [](const ConfigError& a, const ConfigError& b) { return a.line < b.line; });
  return out;
}

ConfigParseResult load_station_config(const std::string& path) {
  ConfigParseResult out;
  auto refuse = [&](const std::string& why) {
    out.errors.push_back({path, 0, "", why});
    return out;
  };
  // O_NONBLOCK: a FIFO must not hang the open; only a regular file of bounded size is
  // read (a device such as /dev/zero would never end).
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) return refuse("cannot read the config file (missing or no permission)");
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd);
    return refuse("not a regular file; the config must be a TOML file");
  }
  if (static_cast<std::uint64_t>(st.st_size) > kMaxConfigBytes) {
    ::close(fd);
    return refuse("larger than " + std::to_string(kMaxConfigBytes / 1024) +
                  " KiB; a station config is a few KiB of TOML");
  }
  std::string text(kMaxConfigBytes + 1, '\0');
  std::size_t size = 0;
  for (;;) {  // the file may grow meanwhile: never read past the limit
    const ssize_t n = ::read(fd, text.data() + size, text.size() - size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    size += static_cast<std::size_t>(n);
    if (size == text.size()) break;
  }
  ::close(fd);
  if (size > kMaxConfigBytes) {
    return refuse("larger than " + std::to_string(kMaxConfigBytes / 1024) + " KiB");
  }
  text.resize(size);
  return parse_station_config(text, path);
}

}  // namespace twister::station_app
