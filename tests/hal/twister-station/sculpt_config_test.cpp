// The [sculpt] section (issue "a session"): every key with a good and a bad value,
// messages as FILE:LINE: KEY: expected form, the button map checked against the
// backend's lines, and the translation into the core's SculptSessionConfig.
// Label interaction.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "config/station_config.hpp"
#include "config_test_support.hpp"
#include "station_setup.hpp"

namespace twister::station_app {
namespace {

using test::messages;

using ::testing::HasSubstr;

// Six GPIO lines (lines 0-5); the [sculpt] text under test is appended.
constexpr const char* kBase = test::kSixButtonStation;
constexpr std::uint32_t kBaseLines = 11;  // the [sculpt] text starts on line 12

ConfigParseResult parse(const std::string& sculpt, const std::string& base = kBase) {
  return parse_station_config(base + sculpt, "t.toml");
}

// The one error of `sculpt`, as "t.toml:LINE: KEY: MESSAGE".
std::string one_error(const std::string& sculpt, const std::string& base = kBase) {
  const auto r = parse(sculpt, base);
  EXPECT_EQ(r.errors.size(), 1u) << messages(r);
  return r.errors.empty() ? "" : r.errors[0].to_string();
}

std::string at(std::uint32_t sculpt_line) {
  return "t.toml:" + std::to_string(kBaseLines + sculpt_line) + ": ";
}

TEST(SculptConfig, DefaultsWithoutTheSection) {
  const auto r = parse("");
  ASSERT_TRUE(r.ok()) << messages(r);
  const SculptConfig& s = r.config.sculpt;
  EXPECT_EQ(s.method, SculptMethod::twister);
  EXPECT_EQ(s.radius_m, 0.25);
  EXPECT_EQ(s.radius_min_m, 0.02);
  EXPECT_EQ(s.radius_max_m, 2.0);
  EXPECT_TRUE(s.radius_gesture);
  EXPECT_EQ(s.turn_tracking, TurnTrackingMode::unwrapped);
  EXPECT_EQ(s.turn_limit_deg, 330.0);
  EXPECT_EQ(s.lost_timeout_ms, 500u);
  EXPECT_FALSE(s.buttons_configured);
  const auto setup = make_station_setup(r.config);
  ASSERT_TRUE(setup) << setup.error().message;
  EXPECT_EQ(setup->sculpt.buttons.binding(5).role, input::ButtonRole::freeze);  // paper's
}

TEST(SculptConfig, Method) {
  EXPECT_EQ(parse("[sculpt]\nmethod = \"rottran\"\n").config.sculpt.method, SculptMethod::rottran);
  EXPECT_EQ(parse("[sculpt]\nmethod = \"scodef\"\n").config.sculpt.method, SculptMethod::scodef);
  EXPECT_EQ(one_error("[sculpt]\nmethod = \"twirl\"\n"),
            at(2) +
                "sculpt.method: expected one of \"twister\" \"rottran\" \"scodef\", got "
                "\"twirl\"");
}

TEST(SculptConfig, RadiusM) {
  EXPECT_EQ(parse("[sculpt]\nradius_m = 0.5\n").config.sculpt.radius_m, 0.5);
  EXPECT_EQ(parse("[sculpt]\nradius_m = 1\n").config.sculpt.radius_m, 1.0);  // integer is fine
  EXPECT_EQ(one_error("[sculpt]\nradius_m = \"big\"\n"),
            at(2) + "sculpt.radius_m: expected a number from 0.001 to 10, got \"big\"");
  EXPECT_EQ(one_error("[sculpt]\nradius_m = 2.5\n"),
            at(2) +
                "sculpt.radius_m: expected a radius within sculpt.radius_min_m .. "
                "radius_max_m (0.02 to 2), got 2.5");
}

TEST(SculptConfig, RadiusMinM) {
  EXPECT_EQ(parse("[sculpt]\nradius_min_m = 0.05\n").config.sculpt.radius_min_m, 0.05);
  EXPECT_EQ(one_error("[sculpt]\nradius_min_m = 0\n"),
            at(2) + "sculpt.radius_min_m: expected a number from 0.001 to 10, got 0");
  EXPECT_EQ(one_error("[sculpt]\nradius_min_m = 0.3\n"),  // above the start radius
            at(2) +
                "sculpt.radius_min_m: expected a radius within sculpt.radius_min_m .. "
                "radius_max_m (0.3 to 2), got 0.25");
}

TEST(SculptConfig, RadiusMaxM) {
  EXPECT_EQ(parse("[sculpt]\nradius_max_m = 1.5\n").config.sculpt.radius_max_m, 1.5);
  EXPECT_EQ(one_error("[sculpt]\nradius_max_m = 0.01\n"),
            at(2) +
                "sculpt.radius_max_m: expected more than sculpt.radius_min_m (0.02), got "
                "0.01");
  EXPECT_EQ(one_error("[sculpt]\nradius_max_m = 11\n"),
            at(2) + "sculpt.radius_max_m: expected a number from 0.001 to 10, got 11");
}

TEST(SculptConfig, RadiusGesture) {
  EXPECT_FALSE(parse("[sculpt]\nradius_gesture = false\n").config.sculpt.radius_gesture);
  EXPECT_EQ(one_error("[sculpt]\nradius_gesture = \"no\"\n"),
            at(2) + "sculpt.radius_gesture: expected true or false, got \"no\"");
}

TEST(SculptConfig, TurnTracking) {
  EXPECT_EQ(parse("[sculpt]\nturn_tracking = \"minimal\"\n").config.sculpt.turn_tracking,
            TurnTrackingMode::minimal);
  EXPECT_EQ(one_error("[sculpt]\nturn_tracking = \"wrapped\"\n"),
            at(2) +
                "sculpt.turn_tracking: expected one of \"unwrapped\" \"minimal\", got "
                "\"wrapped\"");
}

TEST(SculptConfig, TurnLimitDeg) {
  EXPECT_EQ(parse("[sculpt]\nturn_limit_deg = 270\n").config.sculpt.turn_limit_deg, 270.0);
  EXPECT_EQ(parse("[sculpt]\nturn_limit_deg = 300.5\n").config.sculpt.turn_limit_deg, 300.5);
  EXPECT_EQ(one_error("[sculpt]\nturn_limit_deg = 360\n"),
            at(2) + "sculpt.turn_limit_deg: expected a number from 180 to 350, got 360");
  EXPECT_EQ(one_error("[sculpt]\nturn_limit_deg = 90\n"),
            at(2) + "sculpt.turn_limit_deg: expected a number from 180 to 350, got 90");
}

TEST(SculptConfig, LostTimeoutMs) {
  EXPECT_EQ(parse("[sculpt]\nlost_timeout_ms = 1000\n").config.sculpt.lost_timeout_ms, 1000u);
  EXPECT_EQ(one_error("[sculpt]\nlost_timeout_ms = 20\n"),
            at(2) + "sculpt.lost_timeout_ms: expected an integer from 50 to 10000, got 20");
  EXPECT_EQ(one_error("[sculpt]\nlost_timeout_ms = 1.5\n"),
            at(2) + "sculpt.lost_timeout_ms: expected an integer from 50 to 10000, got 1.5");
}

TEST(SculptConfig, UnknownKeysAreErrors) {
  EXPECT_THAT(one_error("[sculpt]\nradius = 0.3\n"),
              HasSubstr(at(2) + "sculpt.radius: unknown key (allowed here: method, "
                                "radius_gesture, radius_min_m, radius_max_m, radius_m, "
                                "turn_tracking, turn_limit_deg, lost_timeout_ms, refine, "
                                "refine_threshold_m, symmetry, symmetry_axis, symmetry_order, "
                                "symmetry_mirror, symmetry_cycle, buttons)"));
  EXPECT_THAT(one_error("[sculpt.buttons.middle]\ngrab = 0\n"),
              HasSubstr("sculpt.buttons.middle: unknown key (allowed here: left, right)"));
  EXPECT_THAT(
      one_error("[sculpt.buttons.left]\ngrip = 0\n"),
      HasSubstr(at(2) + "sculpt.buttons.left.grip: unknown key (allowed here: grab, "
                        "radius, freeze, move_object, undo, redo, method_cycle, symmetry_cycle)"));
}

// Every action of both hands takes a line and a chord, and refuses a bad value.
TEST(SculptConfig, EveryButtonActionTakesALineOrAChord) {
  for (const char* hand : {"left", "right"}) {
    for (const char* action : {"grab", "radius", "freeze", "move_object", "undo", "redo",
                               "method_cycle", "symmetry_cycle"}) {
      const std::string table = std::string("[sculpt.buttons.") + hand + "]\n";
      const std::string key = std::string("sculpt.buttons.") + hand + "." + action;
      const auto line = parse(table + action + " = 4\n");
      ASSERT_TRUE(line.ok()) << key << "\n" << messages(line);
      ASSERT_EQ(line.config.sculpt.buttons.size(), 1u);
      EXPECT_EQ(line.config.sculpt.buttons[0].lines, std::vector<std::uint8_t>{4});
      EXPECT_EQ(line.config.sculpt.buttons[0].hand, std::string(hand) == "left" ? 0 : 1);
      EXPECT_STREQ(to_string(line.config.sculpt.buttons[0].action), action);
      const auto chord = parse(table + action + " = [5, 2]\n");
      ASSERT_TRUE(chord.ok()) << key << "\n" << messages(chord);
      EXPECT_EQ(chord.config.sculpt.buttons[0].lines, (std::vector<std::uint8_t>{5, 2}));
      EXPECT_EQ(one_error(table + action + " = 16\n"),
                at(2) + key +
                    ": expected a button line from 0 to 15, or a chord [HELD, TRIGGER] / "
                    "[HELD, HELD, TRIGGER] of distinct lines (hold the first ones, press the "
                    "last), got 16");
    }
  }
}

TEST(SculptConfig, MalformedChords) {
  const std::string t = "[sculpt.buttons.right]\n";
  EXPECT_THAT(one_error(t + "undo = [3]\n"), HasSubstr("got an array"));
  EXPECT_THAT(one_error(t + "undo = [1, 2, 3, 4]\n"), HasSubstr("got an array"));
  EXPECT_THAT(one_error(t + "undo = [3, 3]\n"), HasSubstr("got 3 at 1"));
  EXPECT_THAT(one_error(t + "undo = [3, \"x\"]\n"), HasSubstr("got \"x\" at 1"));
  EXPECT_THAT(one_error(t + "undo = \"5+3\"\n"), HasSubstr("got \"5+3\""));
}

TEST(SculptConfig, LinesMustExistOnTheBackend) {
  EXPECT_EQ(one_error("[sculpt.buttons.right]\nundo = [5, 6]\n"),
            at(2) +
                "sculpt.buttons.right.undo: line 6 does not exist: buttons.gpiod.lines "
                "lists 6 lines (button lines 0 to 5)");
  std::string hid = kBase;
  hid.replace(hid.find("backend = \"gpiod\""), 17, "backend = \"hidapi\"");
  hid += "[buttons.hidapi]\npath = \"/dev/hidraw0\"\nbuttons = [{byte = 1, mask = 1}]\n";
  EXPECT_THAT(one_error("[sculpt.buttons.left]\nradius = 1\n", hid),
              HasSubstr("sculpt.buttons.left.radius: line 1 does not exist: "
                        "buttons.hidapi.buttons lists 1 buttons (button lines 0 to 0)"));
}

TEST(SculptConfig, OneActionPerLineAndDistinctChords) {
  EXPECT_EQ(one_error("[sculpt.buttons.left]\ngrab = 0\n[sculpt.buttons.right]\nfreeze = 0\n"),
            at(4) +
                "sculpt.buttons.right.freeze: line 0 is already sculpt.buttons.left.grab "
                "(one action per line or chord)");
  EXPECT_EQ(one_error("[sculpt.buttons.right]\nundo = [5, 3]\nredo = [5, 3]\n"),
            at(3) +
                "sculpt.buttons.right.redo: chord [5, 3] is already "
                "sculpt.buttons.right.undo (one action per line or chord)");
  // The same lines in another order are another chord (hold 3, press 5).
  EXPECT_TRUE(parse("[sculpt.buttons.right]\nundo = [5, 3]\nredo = [3, 5]\n").ok());
}

TEST(SculptConfig, TheStylusIsTheOnlyButton) {
  std::string stylus = kBase;
  stylus.replace(stylus.find("backend = \"gpiod\""), 17, "backend = \"stylus\"");
  stylus.erase(stylus.find("[buttons.gpiod]"));
  EXPECT_TRUE(parse("[sculpt.buttons.left]\ngrab = 2\n", stylus).ok());
  EXPECT_THAT(one_error("[sculpt.buttons.left]\nfreeze = 1\n", stylus),
              HasSubstr("sculpt.buttons.left.freeze: buttons.backend = \"stylus\" has one "
                        "button, the stylus of receiver 1: only sculpt.buttons.left.grab (a "
                        "single line) can be set"));
  // Configured without the stylus hand's grab: the setup says what is missing.
  const auto r = parse("[sculpt.buttons]\n", stylus);
  ASSERT_TRUE(r.ok()) << messages(r);
  EXPECT_THAT(make_station_setup(r.config).error().message,
              HasSubstr("drives the grab of the hand holding receiver 1: set "
                        "sculpt.buttons.left.grab"));
  // The stylus then drives that line.
  const auto s = make_station_setup(parse("[sculpt.buttons.left]\ngrab = 2\n", stylus).config);
  ASSERT_TRUE(s) << s.error().message;
  EXPECT_EQ(s->stylus_line[0], 2);
  EXPECT_EQ(s->sculpt.buttons.binding(2).role, input::ButtonRole::grab);
}

// The translation into the core's session config.
TEST(SculptConfig, SetupGivesTheCoreItsSession) {
  const auto r = parse(R"([sculpt]
method = "rottran"
radius_m = 0.4
radius_min_m = 0.1
radius_max_m = 0.9
radius_gesture = false
turn_tracking = "minimal"
turn_limit_deg = 270
lost_timeout_ms = 800
[sculpt.buttons.left]
grab = 0
method_cycle = 1
[sculpt.buttons.right]
grab = 3
freeze = 5
undo = [5, 3]
redo = [4, 5, 3]
)");
  ASSERT_TRUE(r.ok()) << messages(r);
  const auto setup = make_station_setup(r.config);
  ASSERT_TRUE(setup) << setup.error().message;
  const session::SculptSessionConfig& c = setup->sculpt;
  EXPECT_EQ(c.method, math::WarpMethod::rottran);
  EXPECT_FLOAT_EQ(c.interaction.initial_radius_m, 0.4f);
  EXPECT_FLOAT_EQ(c.interaction.radius_min_m, 0.1f);
  EXPECT_FLOAT_EQ(c.interaction.radius_max_m, 0.9f);
  EXPECT_FALSE(c.interaction.radius_gesture);
  EXPECT_EQ(c.interaction.lost_timeout_us, 800'000);
  EXPECT_EQ(c.turns.tracking, session::TurnTracking::minimal);
  EXPECT_NEAR(c.turns.limit_rad, 270.0 * std::acos(-1.0) / 180.0, 1e-12);
  EXPECT_EQ(c.buttons.binding(0).role, input::ButtonRole::grab);
  EXPECT_EQ(c.buttons.binding(1).role, input::ButtonRole::method_cycle);
  EXPECT_EQ(c.buttons.binding(2).role, input::ButtonRole::none);  // not the paper's map
  EXPECT_EQ(c.buttons.binding(3).hand, 1);
  EXPECT_EQ(c.buttons.resolve(3, 1u << 5).role, input::ButtonRole::undo);
  EXPECT_EQ(c.buttons.resolve(3, (1u << 5) | (1u << 4)).role, input::ButtonRole::redo);
  EXPECT_EQ(c.debounce.line_count, 6);
}

}  // namespace
}  // namespace twister::station_app

namespace twister::station_app {
namespace {

// Issue 26: [sculpt] symmetry, symmetry_axis, symmetry_order, symmetry_mirror.
math::SymmetrySpec symmetry_of(const std::string& sculpt) {
  const auto r = parse(sculpt);
  EXPECT_TRUE(r.ok()) << messages(r);
  const auto setup = make_station_setup(r.config);
  EXPECT_TRUE(setup) << setup.error().message;
  return setup ? setup->sculpt.symmetry : math::SymmetrySpec{};
}

TEST(SculptConfig, SymmetryMirrorsAndRotations) {
  using K = math::SymmetryKind;
  EXPECT_EQ(symmetry_of(""), math::SymmetrySpec{});
  EXPECT_EQ(symmetry_of("[sculpt]\nsymmetry = \"none\"\n"), math::SymmetrySpec{});
  EXPECT_EQ(symmetry_of("[sculpt]\nsymmetry = \"x\"\n"), (math::SymmetrySpec{K::mirrors, 1, 0, 0}));
  EXPECT_EQ(symmetry_of("[sculpt]\nsymmetry = \"yz\"\n"),
            (math::SymmetrySpec{K::mirrors, 6, 0, 0}));
  EXPECT_EQ(symmetry_of("[sculpt]\nsymmetry = \"xyz\"\n"),
            (math::SymmetrySpec{K::mirrors, 7, 0, 0}));
  EXPECT_EQ(symmetry_of("[sculpt]\nsymmetry = \"rot\"\n"),
            (math::SymmetrySpec{K::rotation, 0, 2, 6}));  // about z, 6-fold by default
  EXPECT_EQ(symmetry_of("[sculpt]\nsymmetry = \"rot\"\nsymmetry_axis = \"y\"\n"
                        "symmetry_order = 12\nsymmetry_mirror = true\n"),
            (math::SymmetrySpec{K::rotation_mirror, 0, 1, 12}));
  // Every group the configuration names is one the core accepts.
  math::SymmetryGroup g;
  EXPECT_TRUE(g.set(symmetry_of("[sculpt]\nsymmetry = \"rot\"\nsymmetry_order = 2\n")).ok());
}

TEST(SculptConfig, SymmetryErrors) {
  EXPECT_EQ(one_error("[sculpt]\nsymmetry = \"w\"\n"),
            at(2) +
                "sculpt.symmetry: expected one of \"none\" \"x\" \"y\" \"z\" \"xy\" \"xz\" \"yz\" "
                "\"xyz\" \"rot\", got \"w\"");
  EXPECT_EQ(one_error("[sculpt]\nsymmetry = \"rot\"\nsymmetry_order = 13\n"),
            at(3) + "sculpt.symmetry_order: expected an integer from 2 to 12, got 13");
  EXPECT_EQ(one_error("[sculpt]\nsymmetry = \"rot\"\nsymmetry_order = 1\n"),
            at(3) + "sculpt.symmetry_order: expected an integer from 2 to 12, got 1");
  EXPECT_EQ(one_error("[sculpt]\nsymmetry = \"rot\"\nsymmetry_axis = \"w\"\n"),
            at(3) + "sculpt.symmetry_axis: expected one of \"x\" \"y\" \"z\", got \"w\"");
  EXPECT_EQ(
      one_error("[sculpt]\nsymmetry = \"x\"\nsymmetry_order = 4\n"),
      at(3) +
          "sculpt.symmetry_order: only with sculpt.symmetry = \"rot\" (an n-fold rotation) or "
          "\"rot\" in symmetry_cycle");
  EXPECT_EQ(
      one_error("[sculpt]\nsymmetry_mirror = true\n"),
      at(2) +
          "sculpt.symmetry_mirror: only with sculpt.symmetry = \"rot\" (an n-fold rotation) or "
          "\"rot\" in symmetry_cycle");
}

session::SymmetryCycle cycle_of(const std::string& sculpt) {
  const auto r = parse(sculpt);
  EXPECT_TRUE(r.ok()) << messages(r);
  const auto setup = make_station_setup(r.config);
  EXPECT_TRUE(setup) << setup.error().message;
  return setup ? setup->sculpt.symmetry_cycle : session::SymmetryCycle{};
}

TEST(SculptConfig, SymmetryCycleListsGroupsByTheirNames) {
  using K = math::SymmetryKind;
  EXPECT_EQ(cycle_of("").count, 0u);  // the session's default: none and `symmetry`
  const session::SymmetryCycle c = cycle_of(
      "[sculpt]\nsymmetry_cycle = [\"none\", \"x\", \"rot\"]\nsymmetry_order = 5\n"
      "symmetry_axis = \"y\"\n");
  ASSERT_EQ(c.count, 3u);
  EXPECT_EQ(c.groups[0], math::SymmetrySpec{});
  EXPECT_EQ(c.groups[1], (math::SymmetrySpec{K::mirrors, 1, 0, 0}));
  EXPECT_EQ(c.groups[2], (math::SymmetrySpec{K::rotation, 0, 1, 5}));
}

TEST(SculptConfig, SymmetryCycleErrors) {
  EXPECT_EQ(one_error("[sculpt]\nsymmetry_cycle = [\"none\", \"w\"]\n"),
            at(2) +
                "sculpt.symmetry_cycle: expected \"none\", \"x\", \"y\", \"z\", \"xy\", \"xz\", "
                "\"yz\", \"xyz\" or \"rot\"");
  EXPECT_EQ(one_error("[sculpt]\nsymmetry_cycle = []\n"),
            at(2) + "sculpt.symmetry_cycle: expected 1 to 8 groups");
}

// scodef is symmetrised too (docs/math.md §11.8): no longer refused with a group.
TEST(SculptConfig, ScodefTakesASymmetry) {
  const auto r = parse("[sculpt]\nmethod = \"scodef\"\nsymmetry = \"xy\"\n");
  ASSERT_TRUE(r.ok()) << messages(r);
  EXPECT_EQ(r.config.sculpt.method, SculptMethod::scodef);
  EXPECT_EQ(r.config.sculpt.symmetry.mode, SymmetryMode::mirrors);
  EXPECT_EQ(r.config.sculpt.symmetry.mirrors, 3u);
  EXPECT_EQ(cycle_of("[sculpt]\nmethod = \"scodef\"\nsymmetry_cycle = [\"none\", \"x\"]\n").count,
            2u);
}

}  // namespace
}  // namespace twister::station_app
