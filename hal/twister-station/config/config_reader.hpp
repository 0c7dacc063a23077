// ConfigReader: a strict view of one TOML table. Each accessor records the key as
// known, checks its type and range, and on a problem appends a ConfigError with the
// file, the line of the offending node (or of the table for a missing key), the
// dotted key name and the expected form. finish() reports every key never asked for,
// so typos are errors instead of silently ignored settings.
#pragma once

#include <cstdint>
#include <initializer_list>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#define TOML_EXCEPTIONS 0
#define TOML_HEADER_ONLY 1
#include <toml++/toml.h>

#include "config/station_config.hpp"

namespace twister::station_app::internal {

class ConfigReader {
 public:
  ConfigReader(const toml::table* table, std::string prefix, std::string_view file,
               std::vector<ConfigError>& errors)
      : table_(table), prefix_(std::move(prefix)), file_(file), errors_(errors) {}

  bool present() const { return table_ != nullptr; }
  bool has(std::string_view key) const { return node(key) != nullptr; }
  // The node under key (nullptr when missing), to point an error at its line.
  const toml::node* node(std::string_view key) const {
    return table_ != nullptr ? table_->get(key) : nullptr;
  }

  // Sub-table; a missing table gives a reader with present() == false (every key
  // then takes its default, or is reported missing when required).
  ConfigReader table(std::string_view key, bool required);
  // Reader over an inline table that is an array element (key like "buttons[2]").
  ConfigReader element(const toml::table* t, std::string_view key) const {
    return ConfigReader(t, name(key), file_, errors_);
  }

  // A string; with `allowed` non-empty the value must be one of them.
  bool string(std::string_view key, bool required, std::string& out,
              std::initializer_list<std::string_view> allowed = {});
  // An integer in [min, max].
  bool integer(std::string_view key, bool required, std::int64_t min, std::int64_t max,
               std::int64_t& out);
  // A number (integer or float) in [min, max].
  bool real(std::string_view key, bool required, double min, double max, double& out);
  bool boolean(std::string_view key, bool& out);
  // Any value (nullptr when missing); the caller checks its form.
  const toml::node* value(std::string_view key) { return lookup(key, false, ""); }
  // An array (possibly missing); returns nullptr and reports when not an array.
  const toml::array* array(std::string_view key, bool required);

  // Reports every key of this table that no accessor asked for.
  void finish();

  void error(const toml::node* at, std::string_view key, std::string message);
  // An error at `line` for the full dotted key `full_key` (cross-key checks).
  void error_at(std::uint32_t line, std::string full_key, std::string message) {
    errors_.push_back({std::string(file_), line, std::move(full_key), std::move(message)});
  }
  std::string name(std::string_view key) const;

 private:
  const toml::node* lookup(std::string_view key, bool required, std::string_view expected);

  const toml::table* table_;
  std::string prefix_;
  std::string_view file_;
  std::vector<ConfigError>& errors_;
  std::vector<std::string> known_;
};

std::string type_name(const toml::node& node);
std::string describe(const toml::node& node);
// The 1-based line a source region starts on (toml++ reports 0 when unknown: line 1).
inline std::uint32_t line_of(const toml::source_region& region) {
  return region.begin.line == 0 ? 1u : region.begin.line;
}

}  // namespace twister::station_app::internal
