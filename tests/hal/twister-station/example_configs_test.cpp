// The shipped example configs are wired as their comments say (issue "a session"):
// every "line N = HAND ACTION" and "hold line A, press line B = HAND ACTION" comment of
// deploy/station.toml, sim.toml and usb_hid.toml is exactly the [sculpt.buttons] map,
// and pressing each configured line through the simulator (the real backend factory:
// simulated Fastrak, scripted buttons or the simulated stylus, virtual time) into a
// core Station does the documented action. Also: undo and redo from buttons through
// the station, and the counters count a two-handed stroke once. Label interaction.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "backend_factory.hpp"
#include "config/station_config.hpp"
#include "fakes/fake_storage.hpp"
#include "station_setup.hpp"
#include "twister/station/station.hpp"

namespace twister::station_app {
namespace {

using session::SessionEvent;
using session::SessionEventKind;

// A documented or configured binding: lines (held..., trigger), hand, action key.
using Binding = std::tuple<std::vector<std::uint8_t>, std::uint8_t, std::string>;

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string action_key(std::string words) {
  std::replace(words.begin(), words.end(), '-', '_');  // "move-object" -> "move_object"
  return words;
}

// The bindings the file's comments describe.
std::set<Binding> documented(const std::string& text) {
  const std::regex chord(
      R"(hold line (\d+)(?:, line (\d+))?, press line (\d+) = (left|right) ([a-z-]+))");
  const std::regex single(R"(line (\d+) = (left|right) ([a-z-]+))");
  std::set<Binding> out;
  std::istringstream lines(text);
  for (std::string l; std::getline(lines, l);) {
    if (l.rfind('#', 0) != 0) continue;
    std::smatch m;
    std::string rest = l;
    while (std::regex_search(rest, m, chord)) {
      std::vector<std::uint8_t> ls{static_cast<std::uint8_t>(std::stoi(m[1]))};
      if (m[2].matched) ls.push_back(static_cast<std::uint8_t>(std::stoi(m[2])));
      ls.push_back(static_cast<std::uint8_t>(std::stoi(m[3])));
      out.insert({ls, m[4] == "left" ? 0 : 1, action_key(m[5])});
      rest = m.prefix().str() + m.suffix().str();
    }
    for (auto it = std::sregex_iterator(rest.begin(), rest.end(), single);
         it != std::sregex_iterator(); ++it) {
      out.insert({{static_cast<std::uint8_t>(std::stoi((*it)[1]))},
                  (*it)[2] == "left" ? std::uint8_t{0} : std::uint8_t{1},
                  action_key((*it)[3])});
    }
  }
  return out;
}

std::set<Binding> configured(const StationFileConfig& c) {
  std::set<Binding> out;
  for (const ButtonBindingConfig& b : c.sculpt.buttons) {
    out.insert({b.lines, b.hand, to_string(b.action)});
  }
  return out;
}

std::string describe(const Binding& b) {
  std::ostringstream s;
  s << (std::get<1>(b) == 0 ? "left " : "right ") << std::get<2>(b) << " on";
  for (const std::uint8_t l : std::get<0>(b)) s << ' ' << int{l};
  return s.str();
}

// 21 x 21 vertices around the simulator's resting hands (station frame, metres).
constexpr std::size_t kGridN = 21;
using TestMesh = mesh::MeshWithStorage<kGridN * kGridN, 2 * kGridN * kGridN>;
using TestWork = session::SculptStorageArrays<kGridN * kGridN, kGridN * kGridN, 8192, 16>;

void make_grid(mesh::Mesh& m) {
  for (std::size_t j = 0; j < kGridN; ++j) {
    for (std::size_t i = 0; i < kGridN; ++i) {
      const float x = 0.2f + 0.3f * static_cast<float>(i) / (kGridN - 1);
      const float y = -0.3f + 0.6f * static_cast<float>(j) / (kGridN - 1);
      ASSERT_TRUE(m.add_vertex({x, y, 0.127f}).ok());
    }
  }
}

// One scripted press of a binding: its lines go down in order and up in reverse.
struct Press {
  double at_s;
  std::vector<std::uint8_t> lines;
  double hold_s = 0.4;
};

// A station on the simulator: `config`'s map, a scenario with both hands resting and
// the given presses (as `button` lines, or as the stylus of receiver 1 when the
// config's buttons are the stylus), run in virtual time to the scenario's end.
class SimStation {
 public:
  // `keys`: more key frames (scenario text), e.g. a hand turning.
  SimStation(StationFileConfig config, const std::vector<Press>& presses, double duration_s,
             const std::string& keys = "") {
    const bool stylus = config.buttons.backend == ButtonBackend::stylus;
    std::string scn = "receivers 2\nduration " + std::to_string(duration_s) + "\n";
    scn += "key 0 1 14 -4 5 0 0 0\nkey 0 2 14 4 5 0 0 0\n" + keys;
    if (!stylus) {
      for (const Press& p : presses) {
        for (std::size_t k = 0; k < p.lines.size(); ++k) {
          const double down = p.at_s + 0.1 * static_cast<double>(k);
          const double up = p.at_s + p.hold_s + 0.1 * static_cast<double>(p.lines.size() - 1 - k);
          scn += "button " + std::to_string(down) + " " + std::to_string(p.lines[k]) + " 1\n";
          scn += "button " + std::to_string(up) + " " + std::to_string(p.lines[k]) + " 0\n";
        }
      }
    } else {
      for (const Press& p : presses) {  // the stylus column of receiver 1's key frames
        scn += "key " + std::to_string(p.at_s) + " 1 14 -4 5 0 0 0 1\n";
        scn += "key " + std::to_string(p.at_s + p.hold_s) + " 1 14 -4 5 0 0 0 0\n";
      }
    }
    scenario_path_ = testing::TempDir() + "/example_" + std::to_string(++serial_) + ".scn";
    std::ofstream(scenario_path_) << scn;
    config.tracker.backend = TrackerBackend::sim;
    config.tracker.sim.scenario_file = scenario_path_;
    config.tracker.sim.time = SimTime::virtual_time;
    if (!stylus) config.buttons.backend = ButtonBackend::sim;
    auto backends = make_backends(config);
    EXPECT_TRUE(backends) << backends.error().message;
    if (backends) backends_ = std::move(*backends);
    const auto setup = make_station_setup(config);
    EXPECT_TRUE(setup) << setup.error().message;
    if (setup) setup_ = *setup;
    make_grid(*mesh_);
    station_ =
        std::make_unique<station::Station>(*backends_.tracker, *backends_.buttons, *backends_.clock,
                                           storage_, *mesh_, work_->spans(), setup_);
    EXPECT_TRUE(station_->start().ok());
  }
  ~SimStation() { std::remove(scenario_path_.c_str()); }

  // Runs to `until_s` (scenario time), 1 ms per poll; `sample` sees each poll.
  template <typename Sample>
  void run(double until_s, Sample sample) {
    const auto end_us = static_cast<ports::TimestampUs>(until_s * 1e6) + 1'000'000;
    while (backends_.clock->now_us() < end_us) {
      backends_.virtual_clock->advance_us(1000);
      ASSERT_TRUE(station_->poll().ok());
      for (auto e = station_->next_event(); e.ok(); e = station_->next_event()) {
        events.push_back(*e);
      }
      sample(seconds(), station_->sculpt().state());
    }
  }
  void run(double until_s) {
    run(until_s, [](double, const session::SessionState&) {});
  }
  double seconds() const { return static_cast<double>(backends_.clock->now_us()) / 1e6 - 1.0; }
  // Events of `kind` (of `hand`) between `from_s` and `to_s` scenario time.
  std::size_t count(SessionEventKind kind, int hand, double from_s, double to_s) const {
    std::size_t n = 0;
    for (const SessionEvent& e : events) {
      const double t = static_cast<double>(e.time_us) / 1e6 - 1.0;
      n += e.kind == kind && (hand < 0 || e.hand == hand) && t >= from_s && t < to_s ? 1 : 0;
    }
    return n;
  }
  const station::Station& station() const { return *station_; }

  std::vector<SessionEvent> events;

 private:
  static inline int serial_ = 0;
  std::string scenario_path_;
  Backends backends_;
  station::StationConfig setup_;
  test::FakeStorageWithStorage<1 << 20> storage_;
  std::unique_ptr<TestMesh> mesh_ = std::make_unique<TestMesh>();
  std::unique_ptr<TestWork> work_ = std::make_unique<TestWork>();
  std::unique_ptr<station::Station> station_;
};

constexpr double kSlot = 2.0;   // seconds per tested binding
constexpr double kFirst = 3.0;  // the simulated tracker streams from about 2 s

// The line a hand's grab is on (single-line grab), or none.
std::vector<std::uint8_t> grab_of(const std::set<Binding>& map, std::uint8_t hand) {
  for (const Binding& b : map) {
    if (std::get<1>(b) == hand && std::get<2>(b) == "grab") return std::get<0>(b);
  }
  return {};
}
const Binding* find(const std::set<Binding>& map, const std::string& action) {
  for (const Binding& b : map) {
    if (std::get<2>(b) == action) return &b;
  }
  return nullptr;
}

// The presses that show a binding's action in its slot starting at `t`.
std::vector<Press> presses_for(const Binding& b, const std::set<Binding>& map, double t) {
  const std::string& action = std::get<2>(b);
  const std::vector<std::uint8_t>& lines = std::get<0>(b);
  const std::vector<std::uint8_t> grab = grab_of(map, std::get<1>(b));
  if (action == "freeze") return {{t + 0.1, grab, 1.2}, {t + 0.4, lines, 0.4}};
  if (action == "undo" || action == "redo") {
    std::vector<Press> p{{t + 0.1, grab_of(map, 0), 0.2}};  // something to undo
    if (action == "redo") p.push_back({t + 0.5, std::get<0>(*find(map, "undo")), 0.2});
    p.push_back({t + 1.0, lines, 0.3});
    return p;
  }
  return {{t + 0.3, lines, 0.6}};
}

void check_example(const std::string& name) {
  SCOPED_TRACE(name);
  const std::string path = std::string(TWISTER_DEPLOY_DIR) + "/" + name;
  const ConfigParseResult parsed = load_station_config(path);
  ASSERT_TRUE(parsed.ok()) << (parsed.errors.empty() ? "" : parsed.errors[0].to_string());
  const std::set<Binding> map = configured(parsed.config);
  ASSERT_TRUE(parsed.config.sculpt.buttons_configured) << "the example wires [sculpt.buttons]";
  ASSERT_EQ(documented(read_file(path)), map) << "comments and [sculpt.buttons] differ";

  std::vector<Press> presses;
  std::vector<std::pair<Binding, double>> slots;
  double t = kFirst;
  for (const Binding& b : map) {
    for (const Press& p : presses_for(b, map, t)) presses.push_back(p);
    slots.emplace_back(b, t);
    t += kSlot;
  }
  SimStation s(parsed.config, presses, t);
  std::map<std::pair<std::size_t, std::string>, bool> seen;  // slot, state flag
  s.run(t, [&](double now, const session::SessionState& st) {
    for (std::size_t i = 0; i < slots.size(); ++i) {
      const double at = slots[i].second;
      if (now < at + 0.5 || now > at + 0.8) continue;
      const std::uint8_t h = std::get<1>(slots[i].first);
      if (st.hands[h].buttons.radius) seen[{i, "radius"}] = true;
      if (st.moving_object) seen[{i, "move_object"}] = true;
      if (st.hands[h].buttons.grab && st.hands[h].in_stroke) seen[{i, "grab"}] = true;
    }
  });
  for (std::size_t i = 0; i < slots.size(); ++i) {
    const auto& [b, at] = slots[i];
    SCOPED_TRACE(describe(b));
    const std::uint8_t h = std::get<1>(b);
    const std::string& action = std::get<2>(b);
    const double end = at + kSlot;
    if (action == "grab") {
      EXPECT_EQ(s.count(SessionEventKind::grab_begin, h, at, end), 1u);
      EXPECT_EQ(s.count(SessionEventKind::committed, h, at, end), 1u);
      EXPECT_TRUE((seen[{i, "grab"}]));
    } else if (action == "radius" || action == "move_object") {
      EXPECT_TRUE((seen[{i, action}]));
    } else if (action == "freeze") {
      EXPECT_EQ(s.count(SessionEventKind::disengaged, h, at, end), 1u);
      EXPECT_EQ(s.count(SessionEventKind::engaged, h, at, end), 1u);
    } else if (action == "undo") {
      EXPECT_EQ(s.count(SessionEventKind::undone, -1, at, end), 1u);
      EXPECT_EQ(s.count(SessionEventKind::grab_begin, h, at + 0.9, end), 0u);  // consumed
    } else if (action == "redo") {
      EXPECT_EQ(s.count(SessionEventKind::redone, -1, at, end), 1u);
    } else if (action == "method_cycle") {
      EXPECT_EQ(s.count(SessionEventKind::method_changed, h, at, end), 1u);
    } else {
      ADD_FAILURE() << "no check for " << action;
    }
  }
  EXPECT_EQ(s.count(SessionEventKind::refused, -1, 0, t + 1), 0u);
  EXPECT_EQ(s.count(SessionEventKind::command_refused, -1, 0, t + 1), 0u);
}

TEST(ExampleConfigs, StationTomlIsWiredAsItsCommentsSay) { check_example("station.toml"); }
TEST(ExampleConfigs, SimTomlIsWiredAsItsCommentsSay) { check_example("sim.toml"); }
TEST(ExampleConfigs, UsbHidTomlIsWiredAsItsCommentsSay) { check_example("usb_hid.toml"); }

// The fuzz corpus carries the same examples (so the fuzzer starts from real configs).
TEST(ExampleConfigs, FuzzCorpusHoldsTheExamples) {
  for (const char* name : {"station.toml", "sim.toml", "usb_hid.toml"}) {
    EXPECT_EQ(read_file(std::string(TWISTER_DEPLOY_DIR) + "/" + name),
              read_file(std::string(TWISTER_CORPUS_DIR) + "/" + name))
        << name;
  }
}

// Undo and redo from buttons through the station on the simulator (usb_hid.toml's
// chords), and the counters: a two-handed stroke released together is one stroke.
TEST(ExampleConfigs, UndoRedoFromButtonsAndStrokesCountedOnce) {
  const ConfigParseResult parsed =
      load_station_config(std::string(TWISTER_DEPLOY_DIR) + "/usb_hid.toml");
  ASSERT_TRUE(parsed.ok());
  // Both grabs (lines 0 and 3) together, then undo (hold 5, press 3), then redo.
  SimStation s(parsed.config,
               {{3.0, {0}, 0.6}, {3.0, {3}, 0.6}, {4.0, {5, 3}, 0.3}, {5.0, {5, 4}, 0.3}}, 6.0);
  s.run(6.0);
  EXPECT_EQ(s.count(SessionEventKind::committed, -1, 3, 4), 2u);   // one per hand
  EXPECT_EQ(s.station().counters().events.strokes_committed, 1u);  // one stroke
  EXPECT_EQ(s.count(SessionEventKind::undone, 1, 4, 5), 1u);
  EXPECT_EQ(s.count(SessionEventKind::redone, 1, 5, 6), 1u);
  EXPECT_EQ(s.station().counters().events.undos, 1u);
  EXPECT_EQ(s.station().counters().events.redos, 1u);
  EXPECT_EQ(s.station().journal_records(), 3u);  // stroke, undo, redo
}

// One stroke turning on past the limit: the station holds and says so (a notice in the
// log, station_log_test), and commits the turn at the limit, the long way round.
TEST(ExampleConfigs, TheStationHoldsAtTheTurnLimitAndSaysSo) {
  const ConfigParseResult parsed =
      load_station_config(std::string(TWISTER_DEPLOY_DIR) + "/usb_hid.toml");
  ASSERT_TRUE(parsed.ok());
  // The right hand (receiver 2, line 3 = its grab) turns 350 degrees in azimuth.
  SimStation s(parsed.config, {{3.0, {3}, 3.0}}, 7.0,
               "key 3.3 2 14 4 5 0 0 0\nkey 5.5 2 14 4 5 350 0 0\n");
  double most = 0.0;
  s.run(7.0, [&](double, const session::SessionState& st) {
    if (st.hands[1].in_stroke) most = std::max(most, st.hands[1].turn_rad);
  });
  ASSERT_EQ(s.count(SessionEventKind::turn_limit_reached, 1, 3, 7), 1u);
  for (const SessionEvent& e : s.events) {
    if (e.kind == SessionEventKind::turn_limit_reached) {
      EXPECT_NEAR(e.turn_limit().limit_rad * 180 / 3.14159265358979, 330.0, 1e-9);
    }
  }
  EXPECT_EQ(s.count(SessionEventKind::turn_limit_left, 1, 3, 7), 0u);
  EXPECT_EQ(s.count(SessionEventKind::committed, 1, 6, 7), 1u);
  EXPECT_NEAR(most * 180 / 3.14159265358979, 350.0, 0.5);  // the hand's turn, unwrapped
}

}  // namespace
}  // namespace twister::station_app
