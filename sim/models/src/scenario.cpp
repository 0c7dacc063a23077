// Scenario text parser and trajectory sampling.
#include "twister/sim/scenario.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iterator>
#include <sstream>

#include "twister/hal/output_file.hpp"

namespace twister::sim {
namespace {
constexpr FaultKind kFaultKinds[] = {FaultKind::noise,  FaultKind::drop,   FaultKind::truncate,
                                     FaultKind::stall,  FaultKind::hangup, FaultKind::wrong_baud,
                                     FaultKind::corrupt};
static_assert(std::size(kFaultKinds) == kFaultKindCount);
}  // namespace

const char* fault_kind_name(FaultKind k) {
  switch (k) {
    case FaultKind::noise:
      return "noise";
    case FaultKind::drop:
      return "drop";
    case FaultKind::truncate:
      return "truncate";
    case FaultKind::stall:
      return "stall";
    case FaultKind::hangup:
      return "hangup";
    case FaultKind::wrong_baud:
      return "wrongbaud";
    case FaultKind::corrupt:
      return "corrupt";
  }
  return "unknown";
}

HandSample sample(const Scenario& scenario, int station, double t_s) {
  HandSample s;
  if (station < 1 || station > 4) return s;
  const StationTrack& tr = scenario.stations[static_cast<std::size_t>(station - 1)];
  if (tr.circle.enabled) {
    constexpr double kTwoPi = 6.283185307179586;
    const double a = kTwoPi * t_s / tr.circle.period_s;
    s.position_in = {tr.circle.center_in[0] + tr.circle.radius_in * std::cos(a),
                     tr.circle.center_in[1] + tr.circle.radius_in * std::sin(a),
                     tr.circle.center_in[2]};
    double az = std::remainder(a * 180.0 / 3.141592653589793 + 90.0, 360.0);
    s.euler_deg = {az, 0.0, 0.0};
  } else if (tr.keys.empty()) {
    // A resting hand in front of the transmitter (+X hemisphere).
    s.position_in = {10.0, station == 1 ? -4.0 : 4.0, 2.0};
  } else if (t_s <= tr.keys.front().t_s) {
    s.position_in = tr.keys.front().position_in;
    s.euler_deg = tr.keys.front().euler_deg;
    s.button = tr.keys.front().button;
  } else if (t_s >= tr.keys.back().t_s) {
    s.position_in = tr.keys.back().position_in;
    s.euler_deg = tr.keys.back().euler_deg;
    s.button = tr.keys.back().button;
  } else {
    auto it = std::upper_bound(tr.keys.begin(), tr.keys.end(), t_s,
                               [](double t, const KeyFrame& k) { return t < k.t_s; });
    const KeyFrame& b = *it;
    const KeyFrame& a = *(it - 1);
    const double u = (t_s - a.t_s) / (b.t_s - a.t_s);
    for (std::size_t i = 0; i < 3; ++i) {
      s.position_in[i] = a.position_in[i] + u * (b.position_in[i] - a.position_in[i]);
      s.euler_deg[i] = a.euler_deg[i] + u * (b.euler_deg[i] - a.euler_deg[i]);
    }
    s.button = a.button;
  }
  return s;
}

namespace {

bool finite(double v) { return std::isfinite(v); }

std::string format_limit(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.0f", v);
  return text;
}

bool within(const std::array<double, 3>& v, double limit) {
  return std::all_of(v.begin(), v.end(),
                     [limit](double x) { return finite(x) && std::fabs(x) <= limit; });
}

// Each keyword's reader: the rest of the line in `ls`; returns "" or the problem.
std::string read_seed(std::istringstream& ls, Scenario& sc) {
  long long v = 0;
  if (!(ls >> v) || v < 0) return "seed needs a non-negative integer";
  sc.seed = static_cast<std::uint32_t>(v);
  return {};
}

std::string read_receivers(std::istringstream& ls, Scenario& sc) {
  if (!(ls >> sc.receivers) || sc.receivers < 1 || sc.receivers > 4) {
    return "receivers must be 1..4";
  }
  return {};
}

std::string read_duration(std::istringstream& ls, Scenario& sc) {
  if (!(ls >> sc.duration_s) || !finite(sc.duration_s) || sc.duration_s < 0 ||
      sc.duration_s > kMaxScenarioSeconds) {
    return "duration needs seconds 0.." + format_limit(kMaxScenarioSeconds);
  }
  return {};
}

std::string read_key(std::istringstream& ls, Scenario& sc) {
  KeyFrame k;
  int st = 0;
  if (!(ls >> k.t_s >> st >> k.position_in[0] >> k.position_in[1] >> k.position_in[2] >>
        k.euler_deg[0] >> k.euler_deg[1] >> k.euler_deg[2])) {
    return "key needs: t station x y z az el roll [button]";
  }
  int button = 0;
  if (ls >> button) k.button = button != 0;
  if (st < 1 || st > 4) return "station must be 1..4";
  if (!finite(k.t_s) || k.t_s < 0 || k.t_s > kMaxScenarioSeconds) {
    return "time must be 0.." + format_limit(kMaxScenarioSeconds) + " s";
  }
  if (!within(k.position_in, kMaxPositionIn) || !within(k.euler_deg, kMaxAngleDeg)) {
    return "positions must be finite and within " + format_limit(kMaxPositionIn) +
           " in, angles within " + format_limit(kMaxAngleDeg) + " degrees";
  }
  auto& keys = sc.stations[static_cast<std::size_t>(st - 1)].keys;
  if (!keys.empty() && k.t_s <= keys.back().t_s) return "key times must increase";
  keys.push_back(k);
  return {};
}

std::string read_circle(std::istringstream& ls, Scenario& sc) {
  Circle c;
  int st = 0;
  if (!(ls >> st >> c.center_in[0] >> c.center_in[1] >> c.center_in[2] >> c.radius_in >>
        c.period_s)) {
    return "circle needs: station cx cy cz radius period";
  }
  if (st < 1 || st > 4) return "station must be 1..4";
  if (!(c.period_s > 0) || c.period_s > kMaxScenarioSeconds) {
    return "period must be > 0 and at most " + format_limit(kMaxScenarioSeconds) + " s";
  }
  if (!within(c.center_in, kMaxPositionIn) || !finite(c.radius_in) ||
      std::fabs(c.radius_in) > kMaxPositionIn) {
    return "centre and radius must be finite and within " + format_limit(kMaxPositionIn) + " in";
  }
  c.enabled = true;
  sc.stations[static_cast<std::size_t>(st - 1)].circle = c;
  return {};
}

// The largest amount of each fault kind, and whether it counts whole things (bytes,
// records) or seconds. Beyond these a fault is no test of anything, only a way to
// spin the model (noise 1e12 once made 4e9 passes of its noise loop).
struct FaultLimit {
  double max;
  bool whole;
  const char* unit;
};

FaultLimit fault_limit(FaultKind kind) {
  switch (kind) {
    case FaultKind::noise:
      return {kMaxNoiseBytes, true, "bytes"};
    case FaultKind::drop:
      return {kMaxDropBytes, true, "bytes"};
    case FaultKind::truncate:
    case FaultKind::corrupt:
      return {kMaxFaultRecords, true, "records"};
    case FaultKind::stall:
    case FaultKind::hangup:
    case FaultKind::wrong_baud:
      return {kMaxFaultSeconds, false, "seconds"};
  }
  return {0.0, true, ""};
}

std::string read_fault(std::istringstream& ls, Scenario& sc) {
  Fault f;
  std::string kind;
  if (!(ls >> f.t_s >> kind >> f.amount)) return "fault needs: t kind amount";
  if (!finite(f.t_s) || f.t_s < 0 || f.t_s > kMaxScenarioSeconds) {
    return "fault time must be 0.." + format_limit(kMaxScenarioSeconds) + " s";
  }
  const auto* named = std::find_if(std::begin(kFaultKinds), std::end(kFaultKinds),
                                   [&](FaultKind k) { return kind == fault_kind_name(k); });
  if (named == std::end(kFaultKinds)) return "unknown fault kind '" + kind + "'";
  f.kind = *named;
  const FaultLimit limit = fault_limit(f.kind);
  if (!finite(f.amount) || f.amount < 0 || f.amount > limit.max ||
      (limit.whole && f.amount != std::floor(f.amount))) {
    return "fault " + kind + " amount must be " + (limit.whole ? "a whole number " : "") + "0.." +
           format_limit(limit.max) + " " + limit.unit;
  }
  sc.faults.push_back(f);
  return {};
}

std::string read_button(std::istringstream& ls, Scenario& sc) {
  ButtonEvent b;
  int level = 0;
  if (!(ls >> b.t_s >> b.line >> level)) return "button needs: t line 0|1";
  if (!finite(b.t_s) || b.t_s < 0 || b.t_s > kMaxScenarioSeconds) {
    return "button time must be 0.." + format_limit(kMaxScenarioSeconds) + " s";
  }
  if (b.line < 0 || b.line >= kMaxScenarioButtonLines) {
    return "button line must be 0.." + std::to_string(kMaxScenarioButtonLines - 1);
  }
  if (level != 0 && level != 1) return "button level must be 0 or 1";
  b.pressed = level == 1;
  sc.buttons.push_back(b);
  return {};
}

std::string read_status(std::istringstream& ls, Scenario& sc) {
  StatusEvent e;
  std::string code;
  if (!(ls >> e.t_s >> e.station >> code >> e.duration_s)) {
    return "status needs: t station letter seconds";
  }
  if (e.station < 1 || e.station > 4) return "station must be 1..4";
  if (code.size() != 1 || !std::isalpha(static_cast<unsigned char>(code[0]))) {
    return "status code must be one letter";
  }
  if (!finite(e.t_s) || e.t_s < 0 || !finite(e.duration_s) || e.duration_s < 0 ||
      e.t_s > kMaxScenarioSeconds || e.duration_s > kMaxScenarioSeconds) {
    return "status time and seconds must be 0.." + format_limit(kMaxScenarioSeconds);
  }
  e.code = code[0];
  sc.status.push_back(e);
  return {};
}

struct Keyword {
  const char* word;
  std::string (*read)(std::istringstream&, Scenario&);
};
constexpr Keyword kKeywords[] = {{"seed", read_seed},         {"receivers", read_receivers},
                                 {"duration", read_duration}, {"key", read_key},
                                 {"circle", read_circle},     {"fault", read_fault},
                                 {"button", read_button},     {"status", read_status}};

// One line (comments already cut); "" or the problem.
std::string read_line(const std::string& line, Scenario& sc) {
  std::istringstream ls(line);
  std::string word;
  if (!(ls >> word)) return {};
  const auto* keyword = std::find_if(std::begin(kKeywords), std::end(kKeywords),
                                     [&](const Keyword& k) { return word == k.word; });
  if (keyword == std::end(kKeywords)) return "unknown keyword '" + word + "'";
  if (std::string problem = keyword->read(ls, sc); !problem.empty()) return problem;
  std::string extra;
  if (ls >> extra) return "unexpected '" + extra + "'";
  return {};
}

}  // namespace

namespace {

// Every line through read_line(); the result sorted as the players need it.
class LineReader {
 public:
  bool line(std::string text, std::string& error) {
    ++line_no_;
    if (const auto hash = text.find('#'); hash != std::string::npos) text.erase(hash);
    if (std::string problem = read_line(text, sc_); !problem.empty()) {
      error = "line " + std::to_string(line_no_) + ": " + problem;
      return false;
    }
    return true;
  }
  int line_no() const { return line_no_; }
  Scenario finish() {
    std::stable_sort(sc_.faults.begin(), sc_.faults.end(),
                     [](const Fault& a, const Fault& b) { return a.t_s < b.t_s; });
    std::stable_sort(sc_.buttons.begin(), sc_.buttons.end(),
                     [](const ButtonEvent& a, const ButtonEvent& b) { return a.t_s < b.t_s; });
    return std::move(sc_);
  }

 private:
  Scenario sc_;
  int line_no_ = 0;
};

// Reads the open file line by line through a fixed buffer into `reader`.
hal::Expected<void> read_lines(int fd, const std::string& path, LineReader& reader) {
  std::array<char, 1 << 16> buffer{};
  std::string line;
  std::string error;
  for (;;) {
    const ssize_t n = ::read(fd, buffer.data(), buffer.size());
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      return hal::make_error(StatusCode::io_error,
                             "cannot read scenario file " + path + ": " + std::strerror(errno));
    }
    if (n == 0) break;
    for (std::size_t i = 0; i < static_cast<std::size_t>(n); ++i) {
      if (buffer[i] != '\n') {
        if (line.size() >= kMaxScenarioLineBytes) {
          return hal::make_error(StatusCode::invalid_argument,
                                 path + ": line " + std::to_string(reader.line_no() + 1) +
                                     ": longer than " + std::to_string(kMaxScenarioLineBytes) +
                                     " bytes");
        }
        line.push_back(buffer[i]);
        continue;
      }
      if (!reader.line(std::move(line), error)) {
        return hal::make_error(StatusCode::invalid_argument, path + ": " + error);
      }
      line.clear();
    }
  }
  if (!line.empty() && !reader.line(std::move(line), error)) {
    return hal::make_error(StatusCode::invalid_argument, path + ": " + error);
  }
  return {};
}

}  // namespace

bool parse_scenario(std::string_view text, Scenario& out, std::string& error) {
  LineReader reader;
  while (!text.empty()) {
    const auto end = text.find('\n');
    const std::string_view line = text.substr(0, end);
    if (!reader.line(std::string(line), error)) return false;
    if (end == std::string_view::npos) break;
    text.remove_prefix(end + 1);
  }
  out = reader.finish();
  return true;
}

hal::Expected<Scenario> load_scenario_file(const std::string& path) {
  // O_NONBLOCK: a FIFO never blocks the open; then only a regular file of a sane size.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    return hal::make_error(StatusCode::io_error,
                           "cannot read scenario file " + path + ": " + std::strerror(errno));
  }
  struct stat st {};
  if (::fstat(fd, &st) != 0) {
    ::close(fd);
    return hal::make_error(StatusCode::io_error, "cannot read scenario file " + path);
  }
  if (!S_ISREG(st.st_mode)) {
    ::close(fd);
    return hal::make_error(StatusCode::io_error, "scenario file " + path + " is " +
                                                     hal::file_type_name(st.st_mode) +
                                                     ", not a regular file");
  }
  if (static_cast<std::uint64_t>(st.st_size) > kMaxScenarioBytes) {
    ::close(fd);
    return hal::make_error(StatusCode::invalid_argument,
                           "scenario file " + path + " is " + std::to_string(st.st_size) +
                               " bytes; scenarios are limited to " +
                               std::to_string(kMaxScenarioBytes) + " bytes");
  }
  ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);
  LineReader reader;
  const hal::Expected<void> read = read_lines(fd, path, reader);
  ::close(fd);
  if (!read) return read.error();
  return reader.finish();
}

}  // namespace twister::sim
