// [sculpt] of station.toml: see sculpt_config.hpp. Each key is type and range
// checked; the button map is then checked as a whole (lines the backend has, one own
// action per line, distinct chords, the stylus's single button).
#include "sculpt_config.hpp"

#include <algorithm>
#include <array>
#include <cstdio>
#include <string>

namespace twister::station_app {

const char* to_string(SculptAction a) {
  switch (a) {
    case SculptAction::grab:
      return "grab";
    case SculptAction::radius:
      return "radius";
    case SculptAction::freeze:
      return "freeze";
    case SculptAction::move_object:
      return "move_object";
    case SculptAction::undo:
      return "undo";
    case SculptAction::redo:
      return "redo";
    case SculptAction::method_cycle:
      return "method_cycle";
    case SculptAction::symmetry_cycle:
      return "symmetry_cycle";
  }
  return "?";
}

std::size_t button_line_count(const StationFileConfig& config) {
  switch (config.buttons.backend) {
    case ButtonBackend::gpiod:
      return config.buttons.gpiod.lines.size();
    case ButtonBackend::hidapi:
      return config.buttons.hidapi.buttons.size();
    case ButtonBackend::sim:
      return kMaxSculptButtonLines;
    case ButtonBackend::stylus:
      return 1;
  }
  return 0;
}

namespace internal {
namespace {

constexpr std::array<SculptAction, kSculptActionCount> kActions{
    SculptAction::grab,         SculptAction::radius,        SculptAction::freeze,
    SculptAction::move_object,  SculptAction::undo,          SculptAction::redo,
    SculptAction::method_cycle, SculptAction::symmetry_cycle};
constexpr std::array<const char*, 2> kHandNames{"left", "right"};

std::string binding_key(const ButtonBindingConfig& b) {
  return std::string("sculpt.buttons.") + kHandNames[b.hand] + "." + to_string(b.action);
}

constexpr const char kBindingForm[] =
    "expected a button line from 0 to 15, or a chord [HELD, TRIGGER] / [HELD, HELD, "
    "TRIGGER] of distinct lines (hold the first ones, press the last)";

// A line or a chord; false (and an error) when malformed.
bool read_binding(ConfigReader& h, const toml::node& node, ButtonBindingConfig& out) {
  const std::string key = to_string(out.action);
  out.file_line = line_of(node.source());
  if (const auto* i = node.as_integer()) {
    if (i->get() < 0 || i->get() >= kMaxSculptButtonLines) {
      h.error(&node, key, std::string(kBindingForm) + ", got " + describe(node));
      return false;
    }
    out.lines = {static_cast<std::uint8_t>(i->get())};
    return true;
  }
  const auto* a = node.as_array();
  if (a == nullptr || a->size() < 2 || a->size() > kMaxSculptChordLines) {
    h.error(&node, key, std::string(kBindingForm) + ", got " + describe(node));
    return false;
  }
  for (std::size_t k = 0; k < a->size(); ++k) {
    const auto* i = a->get(k)->as_integer();
    if (i == nullptr || i->get() < 0 || i->get() >= kMaxSculptButtonLines ||
        std::find(out.lines.begin(), out.lines.end(), i->get()) != out.lines.end()) {
      h.error(
          &node, key,
          std::string(kBindingForm) + ", got " + describe(*a->get(k)) + " at " + std::to_string(k));
      return false;
    }
    out.lines.push_back(static_cast<std::uint8_t>(i->get()));
  }
  return true;
}

std::string lines_text(const std::vector<std::uint8_t>& lines) {
  std::string s;
  for (const std::uint8_t l : lines) s += (s.empty() ? "" : ", ") + std::to_string(l);
  return lines.size() == 1 ? s : "[" + s + "]";
}

// The lines the backend has; with the stylus only its hand's grab exists.
void check_lines_exist(ConfigReader& s, const StationFileConfig& cfg,
                       const ButtonBindingConfig& b) {
  const std::size_t count = button_line_count(cfg);
  if (cfg.buttons.backend == ButtonBackend::stylus) {
    const std::uint8_t stylus_hand = cfg.tracker.left_station == 1 ? 0 : 1;
    if (b.action != SculptAction::grab || b.hand != stylus_hand || b.lines.size() != 1) {
      s.error_at(b.file_line, binding_key(b),
                 std::string("buttons.backend = \"stylus\" has one button, the stylus of "
                             "receiver 1: only sculpt.buttons.") +
                     kHandNames[stylus_hand] + ".grab (a single line) can be set");
    }
    return;
  }
  const std::string n = std::to_string(count);
  const std::string what = cfg.buttons.backend == ButtonBackend::gpiod
                               ? "buttons.gpiod.lines lists " + n + " lines"
                           : cfg.buttons.backend == ButtonBackend::hidapi
                               ? "buttons.hidapi.buttons lists " + n + " buttons"
                               : "the simulator has " + n + " lines";
  for (const std::uint8_t line : b.lines) {
    if (line < count) continue;
    s.error_at(b.file_line, binding_key(b),
               "line " + std::to_string(line) + " does not exist: " + what +
                   (count > 0 ? " (button lines 0 to " + std::to_string(count - 1) + ")" : ""));
    return;
  }
}

// One own action per line; chords distinct and at most kMaxSculptChords.
void check_map(ConfigReader& s, const StationFileConfig& cfg) {
  const std::vector<ButtonBindingConfig>& all = cfg.sculpt.buttons;
  std::size_t chords = 0;
  for (std::size_t i = 0; i < all.size(); ++i) {
    const ButtonBindingConfig& b = all[i];
    check_lines_exist(s, cfg, b);
    if (b.lines.size() > 1 && ++chords > kMaxSculptChords) {
      s.error_at(b.file_line, binding_key(b),
                 "expected at most " + std::to_string(kMaxSculptChords) + " chords");
    }
    for (std::size_t j = 0; j < i; ++j) {
      if (all[j].lines != b.lines) continue;
      s.error_at(b.file_line, binding_key(b),
                 (b.lines.size() == 1 ? "line " : "chord ") + lines_text(b.lines) + " is already " +
                     binding_key(all[j]) + " (one action per line or chord)");
      break;
    }
  }
}

void read_buttons_of(ConfigReader& buttons, std::uint8_t hand, StationFileConfig& cfg) {
  ConfigReader h = buttons.table(kHandNames[hand], false);
  for (const SculptAction action : kActions) {
    const toml::node* node = h.value(to_string(action));
    if (node == nullptr) continue;
    ButtonBindingConfig b;
    b.action = action;
    b.hand = hand;
    if (read_binding(h, *node, b)) cfg.sculpt.buttons.push_back(b);
  }
  h.finish();
}

void read_radius(ConfigReader& s, SculptConfig& sc) {
  s.boolean("radius_gesture", sc.radius_gesture);
  s.real("radius_min_m", false, 0.001, 10.0, sc.radius_min_m);
  s.real("radius_max_m", false, 0.001, 10.0, sc.radius_max_m);
  const bool have_start = s.real("radius_m", false, 0.001, 10.0, sc.radius_m);
  char text[160];
  if (!(sc.radius_min_m < sc.radius_max_m)) {
    std::snprintf(text, sizeof text, "expected more than sculpt.radius_min_m (%g), got %g",
                  sc.radius_min_m, sc.radius_max_m);
    s.error(s.node("radius_max_m"), "radius_max_m", text);
    return;
  }
  if (sc.radius_m < sc.radius_min_m || sc.radius_m > sc.radius_max_m) {
    std::snprintf(text, sizeof text,
                  "expected a radius within sculpt.radius_min_m .. radius_max_m (%g to %g), got %g",
                  sc.radius_min_m, sc.radius_max_m, sc.radius_m);
    s.error(s.node(have_start ? "radius_m" : "radius_min_m"),
            have_start ? "radius_m" : "radius_min_m", text);
  }
}

// A group's name in [sculpt] ("none", "x".."xyz", "rot") into `sym` (mode, mirrors);
// false: not a name.
bool symmetry_mode_of(const std::string& text, SymmetryConfig& sym) {
  if (text == "none") {
    sym.mode = SymmetryMode::none;
  } else if (text == "rot") {
    sym.mode = SymmetryMode::rotation;
  } else {
    for (const char* name : {"x", "y", "z", "xy", "xz", "yz", "xyz"}) {
      if (text != name) continue;
      sym.mode = SymmetryMode::mirrors;
      sym.mirrors = 0;
      for (const char c : text)
        sym.mirrors = static_cast<std::uint8_t>(sym.mirrors | 1u << (c - 'x'));
      return true;
    }
    return false;
  }
  return true;
}

// symmetry_cycle: the groups the symmetry_cycle chord and a display's key step through,
// by the names of `symmetry` ("rot" with symmetry_axis/order/mirror).
void read_symmetry_cycle(ConfigReader& s, SculptConfig& sc) {
  const toml::array* list = s.array("symmetry_cycle", false);
  if (list == nullptr) return;
  if (list->size() < 1 || list->size() > kMaxSymmetryCycle) {
    s.error(s.node("symmetry_cycle"), "symmetry_cycle",
            "expected 1 to " + std::to_string(kMaxSymmetryCycle) + " groups");
    return;
  }
  sc.symmetry_cycle.clear();
  for (const toml::node& item : *list) {
    const std::optional<std::string> text = item.value<std::string>();
    SymmetryConfig group = sc.symmetry;
    if (!text || !symmetry_mode_of(*text, group)) {
      s.error(&item, "symmetry_cycle",
              "expected \"none\", \"x\", \"y\", \"z\", \"xy\", \"xz\", \"yz\", \"xyz\" or "
              "\"rot\"");
      return;
    }
    sc.symmetry_cycle.push_back(group);
  }
}

// symmetry, symmetry_axis, symmetry_order, symmetry_mirror (docs/math.md §11).
void read_symmetry(ConfigReader& s, SculptConfig& sc) {
  SymmetryConfig& sym = sc.symmetry;
  std::string text;
  if (s.string("symmetry", false, text, {"none", "x", "y", "z", "xy", "xz", "yz", "xyz", "rot"})) {
    symmetry_mode_of(text, sym);
  }
  if (s.string("symmetry_axis", false, text, {"x", "y", "z"})) {
    sym.axis = static_cast<std::uint8_t>(text[0] - 'x');
  }
  std::int64_t order = 0;
  if (s.integer("symmetry_order", false, 2, 12, order))
    sym.order = static_cast<std::uint8_t>(order);
  s.boolean("symmetry_mirror", sym.mirror);
  read_symmetry_cycle(s, sc);
  bool rotation = sym.mode == SymmetryMode::rotation;
  for (const SymmetryConfig& g : sc.symmetry_cycle)
    rotation = rotation || g.mode == SymmetryMode::rotation;
  for (const char* key : {"symmetry_axis", "symmetry_order", "symmetry_mirror"}) {
    if (s.has(key) && !rotation) {
      s.error(s.node(key), key,
              "only with sculpt.symmetry = \"rot\" (an n-fold rotation) or \"rot\" in "
              "symmetry_cycle");
    }
  }
}

}  // namespace

void read_sculpt(ConfigReader& root, StationFileConfig& cfg) {
  ConfigReader s = root.table("sculpt", false);
  SculptConfig& sc = cfg.sculpt;
  std::string text;
  if (s.string("method", false, text, {"twister", "rottran", "scodef"})) {
    sc.method = text == "twister"   ? SculptMethod::twister
                : text == "rottran" ? SculptMethod::rottran
                                    : SculptMethod::scodef;
  }
  read_radius(s, sc);
  if (s.string("turn_tracking", false, text, {"unwrapped", "minimal"})) {
    sc.turn_tracking =
        text == "unwrapped" ? TurnTrackingMode::unwrapped : TurnTrackingMode::minimal;
  }
  s.real("turn_limit_deg", false, 180.0, 350.0, sc.turn_limit_deg);
  std::int64_t timeout = 0;
  if (s.integer("lost_timeout_ms", false, 50, 10000, timeout)) {
    sc.lost_timeout_ms = static_cast<std::uint32_t>(timeout);
  }
  s.boolean("refine", sc.refine);
  s.real("refine_threshold_m", false, 1e-5, 0.1, sc.refine_threshold_m);
  read_symmetry(s, sc);
  ConfigReader buttons = s.table("buttons", false);
  sc.buttons_configured = buttons.present();
  for (std::uint8_t hand = 0; hand < 2; ++hand) read_buttons_of(buttons, hand, cfg);
  buttons.finish();
  s.finish();
  if (sc.buttons_configured) check_map(s, cfg);
}

}  // namespace internal
}  // namespace twister::station_app
