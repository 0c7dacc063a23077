// Scenario text parser and trajectory sampling.
#include "twister/sim/scenario.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <iterator>
#include <sstream>

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
  if (!(ls >> sc.duration_s) || !finite(sc.duration_s) || sc.duration_s < 0) {
    return "duration needs seconds >= 0";
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
  if (!finite(k.t_s) || k.t_s < 0) return "time must be >= 0";
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
  if (!(c.period_s > 0)) return "period must be > 0";
  c.enabled = true;
  sc.stations[static_cast<std::size_t>(st - 1)].circle = c;
  return {};
}

std::string read_fault(std::istringstream& ls, Scenario& sc) {
  Fault f;
  std::string kind;
  if (!(ls >> f.t_s >> kind >> f.amount)) return "fault needs: t kind amount";
  if (!finite(f.t_s) || f.t_s < 0 || !finite(f.amount) || f.amount < 0) {
    return "fault time and amount must be >= 0";
  }
  const auto* named = std::find_if(std::begin(kFaultKinds), std::end(kFaultKinds),
                                   [&](FaultKind k) { return kind == fault_kind_name(k); });
  if (named == std::end(kFaultKinds)) return "unknown fault kind '" + kind + "'";
  f.kind = *named;
  sc.faults.push_back(f);
  return {};
}

std::string read_button(std::istringstream& ls, Scenario& sc) {
  ButtonEvent b;
  int level = 0;
  if (!(ls >> b.t_s >> b.line >> level)) return "button needs: t line 0|1";
  if (!finite(b.t_s) || b.t_s < 0) return "button time must be >= 0";
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
  if (!finite(e.t_s) || e.t_s < 0 || !finite(e.duration_s) || e.duration_s < 0) {
    return "status time and seconds must be >= 0";
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

bool parse_scenario(std::string_view text, Scenario& out, std::string& error) {
  Scenario sc;
  std::istringstream in{std::string(text)};
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (const auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
    if (std::string problem = read_line(line, sc); !problem.empty()) {
      error = "line " + std::to_string(line_no) + ": " + problem;
      return false;
    }
  }
  std::stable_sort(sc.faults.begin(), sc.faults.end(),
                   [](const Fault& a, const Fault& b) { return a.t_s < b.t_s; });
  std::stable_sort(sc.buttons.begin(), sc.buttons.end(),
                   [](const ButtonEvent& a, const ButtonEvent& b) { return a.t_s < b.t_s; });
  out = std::move(sc);
  return true;
}

hal::Expected<Scenario> load_scenario_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) return hal::make_error(StatusCode::io_error, "cannot read scenario file " + path);
  std::stringstream text;
  text << in.rdbuf();
  Scenario out;
  if (std::string error; !parse_scenario(text.str(), out, error)) {
    return hal::make_error(StatusCode::invalid_argument, path + ": " + error);
  }
  return out;
}

}  // namespace twister::sim
