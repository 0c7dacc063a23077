// tracker-dump (also under its old name fastrak-dump). Options are named after the
// protocol's own commands: -O s,items (output list of station s, repeatable, Fastrak item
// codes), -F / -f (ASCII / binary), -U / -u (inches / cm); --binary16 reads the 16-bit
// packed format of the Isotrak II / 3SPACE family; --model liberty|patriot|latus reads
// the Liberty family's binary frames (the lists translated item for item, as the station
// does: to_liberty_config).
// Output: one line per valid record "station ox oy oz ux uy uz vx vy vz wx wy wz"
// (tracker units; receiver axes as unit vectors in tracker coordinates; %.6g) and one
// line starting with "error" per rejected stretch of bytes.
// Note: this tool links twister_hal_termios for DEVICE mode (the one host->hal use).
#include "fastrak_dump_command.hpp"

#include <chrono>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <string>
#include <thread>
#include <vector>

#include "cli_exit_code.hpp"
#include "cli_log.hpp"
#include "twister/hal/expected.hpp"
#include "twister/hal/termios_byte_stream.hpp"
#include "twister/tracker/fastrak_parser.hpp"
#include "twister/tracker/fastrak_session.hpp"
#include "twister/tracker/liberty_parser.hpp"
#include "twister/tracker/pose_conversion.hpp"

namespace twister::cli {
namespace {

using tracker::FastrakConfig;
using tracker::Format;

volatile std::sig_atomic_t g_stop = 0;
void on_signal(int) { g_stop = 1; }

class SteadyClock final : public ports::Clock {
  ports::TimestampUs do_now_us() override {
    return std::chrono::duration_cast<std::chrono::microseconds>(
               std::chrono::steady_clock::now().time_since_epoch())
        .count();
  }
};

struct DumpOptions {
  std::string device;
  std::string file;
  std::vector<std::string> lists;  // -O s,i1,...,in
  bool ascii = false;              // -F
  bool binary = false;             // -f
  bool binary16 = false;           // --binary16
  bool inches = false;             // -U
  bool cm = false;                 // -u
  int baud = 115200;
  int stylus_width = 1;
  double seconds = 0.0;
  long count = 0;
  bool quick = false;
  std::string model = "fastrak";  // fastrak | liberty | patriot | latus
};

bool liberty_family(const DumpOptions& o) { return o.model != "fastrak"; }

tracker::LibertyModel liberty_model(const DumpOptions& o) {
  return o.model == "patriot" ? tracker::LibertyModel::patriot
         : o.model == "latus" ? tracker::LibertyModel::latus
                              : tracker::LibertyModel::liberty;
}

hal::Error bad_option(std::string message) {
  return hal::make_error(StatusCode::invalid_argument, std::move(message));
}

// Parses "s,i1,...,in" into the config.
hal::Expected<void> parse_list(const std::string& text, FastrakConfig& config) {
  std::vector<int> v;
  std::size_t pos = 0;
  while (pos <= text.size()) {
    const std::size_t comma = std::min(text.find(',', pos), text.size());
    const std::string field = text.substr(pos, comma - pos);
    if (field.empty() || field.find_first_not_of("0123456789") != std::string::npos ||
        field.size() > 3) {
      return bad_option("-O " + text + ": expected station,item,item,... with integers");
    }
    v.push_back(std::stoi(field));
    pos = comma + 1;
  }
  if (v.size() < 2 || v[0] < 1 || v[0] > tracker::kMaxStations) {
    return bad_option("-O " + text + ": station 1..4 and at least one item");
  }
  auto& st = config.stations[static_cast<std::size_t>(v[0] - 1)];
  st.enabled = true;
  st.list = {};
  for (std::size_t i = 1; i < v.size(); ++i) {
    if (v[i] > 255 || !tracker::is_supported_item(static_cast<std::uint8_t>(v[i])) ||
        st.list.count >= tracker::kMaxItems) {
      return bad_option("-O " + text + ": unsupported item " + std::to_string(v[i]));
    }
    st.list.items[st.list.count++] = static_cast<tracker::Item>(v[i]);
  }
  return {};
}

hal::Expected<FastrakConfig> build_config(const DumpOptions& o) {
  if (o.ascii && o.binary) return bad_option("-F and -f exclude each other");
  if (o.binary16 && o.ascii) return bad_option("-F and --binary16 exclude each other");
  if (o.inches && o.cm) return bad_option("-U and -u exclude each other");
  FastrakConfig config;
  config.format = o.binary16 ? Format::binary16 : o.binary ? Format::binary : Format::ascii;
  config.units = o.cm ? tracker::Units::centimetres : tracker::Units::inches;
  config.ascii_stylus_width = static_cast<std::uint8_t>(o.stylus_width);
  if (o.lists.empty()) {
    config.stations[0].enabled = true;  // the unit's default list 2,4,1 on station 1
  }
  for (const auto& l : o.lists) {
    if (auto parsed = parse_list(l, config); !parsed) return parsed.error();
  }
  if (!tracker::validate(config).ok()) {
    return bad_option(o.binary16 ? "output lists: extended items (50+) have no 16-bit form, or a "
                                   "record is longer than 254 bytes"
                                 : "output lists give a record longer than 254 bytes");
  }
  return config;
}

void print_pose(const tracker::FastrakPose& p, Format format) {
  auto r = tracker::tracker_rotation(p, format);
  if (!r.ok()) {
    std::printf("error station %d %s\n", p.station,
                r.status().code() == StatusCode::failed_precondition ? "no_orientation"
                                                                     : "bad_orientation");
    return;
  }
  const glm::dmat3& m = *r;
  std::printf("%d %.6g %.6g %.6g %.6g %.6g %.6g %.6g %.6g %.6g %.6g %.6g %.6g\n", p.station,
              static_cast<double>(p.position[0]), static_cast<double>(p.position[1]),
              static_cast<double>(p.position[2]), m[0].x, m[0].y, m[0].z, m[1].x, m[1].y, m[1].z,
              m[2].x, m[2].y, m[2].z);
}

void print_event(const tracker::FastrakEvent& e, Format format) {
  switch (e.kind) {
    case tracker::EventKind::pose:
      print_pose(e.pose, format);
      break;
    case tracker::EventKind::error:
      std::printf("error station %d %s\n", e.station, tracker::pose_error_name(e.error));
      break;
    case tracker::EventKind::resync:
      std::printf("error resync %u bytes\n", e.dropped);
      break;
    case tracker::EventKind::status:
    case tracker::EventKind::reply:
      break;  // replies are neither records nor errors
  }
}

// The Liberty family's binary frames: the Fastrak lists translated (to_liberty_config).
hal::Expected<tracker::LibertyConfig> liberty_config(const DumpOptions& o,
                                                     const FastrakConfig& config) {
  tracker::LibertyConfig liberty;
  if (!tracker::to_liberty_config(config, liberty_model(o), liberty).ok() ||
      !tracker::validate(liberty).ok()) {
    return bad_option("--model " + o.model +
                      ": an output list has an item without a Liberty-family equivalent "
                      "(position 2, Euler 4, cosines 5-7, quaternion 11, stylus 16, 0, 1)");
  }
  return liberty;
}

template <typename Parser>
int decode_stream(std::istream& in, Parser& parser, Format format) {
  std::vector<char> buf(1 << 16);
  while (in) {
    in.read(buf.data(), static_cast<std::streamsize>(buf.size()));
    const auto n = static_cast<std::size_t>(in.gcount());
    if (n == 0) break;
    parser.feed(std::as_bytes(std::span<const char>(buf.data(), n)),
                [&](const tracker::FastrakEvent& e) { print_event(e, format); });
  }
  for (auto e = parser.finish(); e.ok(); e = parser.finish()) print_event(*e, format);
  const auto& c = parser.counters();
  cli_log().notice("counters", "bytes=%llu poses=%llu errors=%llu resyncs=%llu dropped=%llu",
                   c.bytes, c.poses, c.errors, c.resyncs, c.dropped_bytes);
  return kExitOk;
}

int run_file(const DumpOptions& o, const FastrakConfig& config) {
  std::istream* in = &std::cin;
  std::ifstream file;
  if (o.file != "-") {
    file.open(o.file, std::ios::binary);
    if (!file) {
      cli_log().error("", "cannot read %s", o.file.c_str());
      return kExitFailure;
    }
    in = &file;
  }
  if (liberty_family(o) && config.format == Format::binary) {
    const hal::Expected<tracker::LibertyConfig> liberty = liberty_config(o, config);
    if (!liberty) return fail(kExitBadInput, liberty.error().message);
    tracker::LibertyParser parser(*liberty);
    return decode_stream(*in, parser, config.format);
  }
  // ASCII from a Liberty-family unit: Fastrak records, as twister-sim models them
  // (assumed: the real units' ASCII records are not modelled).
  tracker::FastrakParser parser(config);
  return decode_stream(*in, parser, config.format);
}

int run_device(const DumpOptions& o, const FastrakConfig& config) {
  unsigned speed = 0;
  if (!hal::baud_to_speed(o.baud, speed)) {
    cli_log().error("", "unsupported baud %d", o.baud);
    return kExitBadInput;
  }
  tracker::FastrakSessionConfig sc;
  sc.protocol = config;
  if (liberty_family(o)) {
    if (o.model == "latus" || config.format != Format::binary) {
      return fail(kExitBadInput,
                  "DEVICE mode reads a Liberty or Patriot in binary (-f); a "
                  "Latus only from a --file");
    }
    sc.model =
        o.model == "patriot" ? tracker::TrackerModel::patriot : tracker::TrackerModel::liberty;
  }
  if (o.quick) {  // simulator timings (twister-sim --reset-time 0.5 or less)
    sc.ladder_char_pause_us = 20'000;
    sc.reset_wait_us = 600'000;
    sc.settle_us = 50'000;
    sc.reply_timeout_us = 500'000;
    sc.command_pause_us = 50'000;  // the simulator's default command times (40 ms)
  }
  hal::TermiosByteStream port({o.device, o.baud, hal::FlowControl::none});
  SteadyClock clock;
  tracker::FastrakSession session(port, clock, sc);
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  const auto start = std::chrono::steady_clock::now();
  auto next_report = start + std::chrono::seconds(1);
  long printed = 0;
  auto report = [&] {
    const auto& c = session.counters();
    const auto& p = session.parser_counters();
    cli_log().notice("counters",
                     "state=%s poses=%llu inits=%llu streams=%llu status_timeouts=%llu "
                     "io_errors=%llu silence=%llu garbage=%llu rejected=%llu resyncs=%llu "
                     "dropped_bytes=%llu",
                     tracker::session_state_name(session.state()), c.poses, c.inits,
                     c.streams_started, c.status_timeouts, c.io_errors, c.silence_faults,
                     c.garbage_faults, c.rejected_poses, p.resyncs, p.dropped_bytes);
  };
  while (g_stop == 0) {
    for (auto p = session.poll(); p.ok(); p = session.poll()) {
      print_pose(*p, config.format);
      if (o.count > 0 && ++printed >= o.count) g_stop = 1;
    }
    std::fflush(stdout);
    const auto now = std::chrono::steady_clock::now();
    if (now >= next_report) {
      report();
      next_report += std::chrono::seconds(1);
    }
    if (o.seconds > 0 && now - start >= std::chrono::duration<double>(o.seconds)) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  report();
  return kExitOk;
}

// Either source, the options checked first.
int run_dump(const DumpOptions& o) {
  if (o.device.empty() == o.file.empty()) {
    return fail(kExitBadInput, "give either DEVICE or --file PATH");
  }
  const hal::Expected<FastrakConfig> config = build_config(o);
  if (!config) return fail(kExitBadInput, config.error().message);
  if (liberty_family(o) && config->format == Format::binary16) {
    return fail(kExitBadInput, "--binary16 is a Fastrak-family format, not --model " + o.model);
  }
  const int rc = o.file.empty() ? run_device(o, *config) : run_file(o, *config);
  std::fflush(stdout);
  return rc;
}

// One subcommand; `name` is tracker-dump or its old name fastrak-dump (same options).
void add_dump_command(CLI::App& app, const std::string& name, const std::string& help,
                      int& exit_code) {
  auto opts = std::make_shared<DumpOptions>();
  CLI::App* cmd = app.add_subcommand(name, help);
  cmd->add_option("DEVICE", opts->device, "serial device or twister-sim link to configure");
  cmd->add_option("--file", opts->file, "decode a recorded stream from PATH ('-' = stdin)");
  cmd->add_option("-O", opts->lists,
                  "output list of a station as the O command: s,i1,...,in (repeatable; "
                  "default 1,2,4,1)");
  cmd->add_flag("-F", opts->ascii, "ASCII format (default)");
  cmd->add_flag("-f", opts->binary, "binary (IEEE float) format");
  cmd->add_flag("--binary16", opts->binary16,
                "16-bit packed binary (Isotrak II / 3SPACE; DEVICE mode sends f)");
  cmd->add_flag("-U", opts->inches, "inches (default)");
  cmd->add_flag("-u", opts->cm, "centimetres");
  cmd->add_option("--baud", opts->baud, "DEVICE mode line rate")->capture_default_str();
  cmd->add_option("--stylus-width", opts->stylus_width, "ASCII width of item 16 (1 or 2)")
      ->check(CLI::IsMember({1, 2}));
  cmd->add_option("--seconds", opts->seconds, "DEVICE mode: stop after this many seconds")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--count", opts->count, "DEVICE mode: stop after this many records")
      ->check(CLI::NonNegativeNumber);
  cmd->add_flag("--quick", opts->quick, "short reset waits, for twister-sim");
  cmd->add_option("--model", opts->model,
                  "the unit: fastrak (default), liberty, patriot or latus (binary frames; "
                  "-O in Fastrak item codes, translated; latus: --file only)")
      ->check(CLI::IsMember({"fastrak", "liberty", "patriot", "latus"}));
  cmd->callback([opts, name, &exit_code] {
    start_command_log(name.c_str());
    exit_code = run_dump(*opts);
  });
}

}  // namespace

void add_fastrak_dump_command(CLI::App& app, int& exit_code) {
  add_dump_command(app, "tracker-dump",
                   "Configure a tracker (Fastrak, Liberty, Patriot) and print decoded records, "
                   "or decode a recording of any frame format",
                   exit_code);
  add_dump_command(app, "fastrak-dump", "The old name of tracker-dump (the same options)",
                   exit_code);
}

}  // namespace twister::cli
