// [exhibit]: enabled, archive_dir, idle_seconds, grace_seconds, new_sculpture_chord,
// chord_hold_seconds, motion_threshold_m, keep_archives, keep_archive_mb, retry_seconds.
#include "exhibit_config.hpp"

#include <algorithm>
#include <array>

namespace twister::station_app::internal {
namespace {

// What each line does: the configured map, or the paper's default (no [sculpt.buttons]).
struct LineUse {
  bool grab_or_move = false;
};

std::array<LineUse, 16> line_uses(const StationFileConfig& cfg,
                                  std::vector<std::vector<std::uint8_t>>& chords) {
  std::array<LineUse, 16> use{};
  if (cfg.sculpt.buttons.empty()) {
    for (int line : {0, 2, 3}) use[static_cast<std::size_t>(line)].grab_or_move = true;
    return use;
  }
  for (const ButtonBindingConfig& b : cfg.sculpt.buttons) {
    if (b.lines.size() > 1) {
      std::vector<std::uint8_t> sorted = b.lines;
      std::sort(sorted.begin(), sorted.end());
      chords.push_back(sorted);
      continue;
    }
    if ((b.action == SculptAction::grab || b.action == SculptAction::move_object) &&
        !b.lines.empty() && b.lines[0] < use.size()) {
      use[b.lines[0]].grab_or_move = true;
    }
  }
  return use;
}

}  // namespace

void read_exhibit(ConfigReader& root, StationFileConfig& cfg) {
  ConfigReader e = root.table("exhibit", false);
  ExhibitSection& x = cfg.exhibit;
  e.boolean("enabled", x.enabled);
  const bool has_dir = e.string("archive_dir", x.enabled, x.archive_dir);
  if (has_dir && x.archive_dir.empty()) {
    e.error(e.node("archive_dir"), "archive_dir", "expected a directory path, got \"\"");
  }
  e.real("idle_seconds", false, 5.0, 86400.0, x.idle_seconds);
  e.real("grace_seconds", false, 0.0, 600.0, x.grace_seconds);
  e.real("chord_hold_seconds", false, 0.2, 30.0, x.chord_hold_seconds);
  e.real("motion_threshold_m", false, 0.001, 1.0, x.motion_threshold_m);
  e.real("retry_seconds", false, 1.0, 3600.0, x.retry_seconds);
  std::int64_t keep = 0;
  if (e.integer("keep_archives", false, 1, 1'000'000, keep)) {
    x.keep_archives = static_cast<std::uint32_t>(keep);
  }
  if (e.integer("keep_archive_mb", false, 1, 100'000'000, keep)) {
    x.keep_archive_mb = static_cast<std::uint64_t>(keep);
  }
  const toml::array* chord = e.array("new_sculpture_chord", false);
  if (chord != nullptr) {
    const std::size_t count = button_line_count(cfg);
    std::vector<std::vector<std::uint8_t>> chords;
    const std::array<LineUse, 16> use = line_uses(cfg, chords);
    const char* form =
        "expected [] (no chord) or 2 to 3 distinct button lines held together, none of them "
        "a grab or move_object line and not an existing chord (e.g. [1, 5]: left radius + right "
        "freeze with the paper's buttons)";
    std::vector<std::uint8_t> lines;
    bool bad = chord->size() == 1 || chord->size() > 3;
    for (std::size_t k = 0; k < chord->size() && !bad; ++k) {
      const auto* i = chord->get(k)->as_integer();
      bad = i == nullptr || i->get() < 0 || i->get() >= 16 ||
            std::find(lines.begin(), lines.end(), i->get()) != lines.end();
      if (!bad) lines.push_back(static_cast<std::uint8_t>(i->get()));
    }
    if (bad) {
      e.error(e.node("new_sculpture_chord"), "new_sculpture_chord", form);
    } else {
      std::string why;
      for (const std::uint8_t l : lines) {
        if (l >= count) {
          why = "line " + std::to_string(l) + " does not exist (button lines 0 to " +
                std::to_string(count == 0 ? 0 : count - 1) + ")";
        } else if (use[l].grab_or_move) {
          why = "line " + std::to_string(l) +
                " grabs or moves the object: holding it would sculpt (choose lines whose own "
                "action does nothing alone, e.g. radius or freeze)";
        }
        if (!why.empty()) break;
      }
      std::vector<std::uint8_t> sorted = lines;
      std::sort(sorted.begin(), sorted.end());
      if (why.empty() && std::find(chords.begin(), chords.end(), sorted) != chords.end()) {
        why = "these lines are already a [sculpt.buttons] chord";
      }
      if (!why.empty()) {
        e.error(e.node("new_sculpture_chord"), "new_sculpture_chord", why);
      } else {
        x.new_sculpture_chord = lines;
      }
    }
  }
  e.finish();
}

}  // namespace twister::station_app::internal
