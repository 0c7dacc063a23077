#include "config_reader.hpp"

#include <algorithm>
#include <cstdio>

namespace twister::station_app::internal {

std::string type_name(const toml::node& node) {
  switch (node.type()) {
    case toml::node_type::table:
      return "a table";
    case toml::node_type::array:
      return "an array";
    case toml::node_type::string:
      return "a string";
    case toml::node_type::integer:
      return "an integer";
    case toml::node_type::floating_point:
      return "a float";
    case toml::node_type::boolean:
      return "a boolean";
    case toml::node_type::date:
      return "a date";
    case toml::node_type::time:
      return "a time";
    case toml::node_type::date_time:
      return "a date-time";
    default:
      return "nothing";
  }
}

// Short rendering of the offending value for "got ..." (strings quoted, long ones cut).
std::string describe(const toml::node& node) {
  if (const auto* s = node.as_string()) {
    std::string v = s->get();
    if (v.size() > 40) v = v.substr(0, 40) + "...";
    return "\"" + v + "\"";
  }
  if (const auto* i = node.as_integer()) return std::to_string(i->get());
  if (const auto* f = node.as_floating_point()) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", f->get());
    return text;
  }
  if (const auto* b = node.as_boolean()) return b->get() ? "true" : "false";
  return type_name(node);
}

std::string ConfigReader::name(std::string_view key) const {
  return prefix_.empty() ? std::string(key) : prefix_ + "." + std::string(key);
}

void ConfigReader::error(const toml::node* at, std::string_view key, std::string message) {
  if (at == nullptr) at = table_;
  const std::uint32_t line = at != nullptr ? line_of(at->source()) : 1;
  errors_.push_back({std::string(file_), line, name(key), std::move(message)});
}

const toml::node* ConfigReader::lookup(std::string_view key, bool required,
                                       std::string_view expected) {
  known_.emplace_back(key);
  const toml::node* node = this->node(key);
  if (node == nullptr && required) {
    error(nullptr, key, "missing required key; expected " + std::string(expected));
  }
  return node;
}

ConfigReader ConfigReader::table(std::string_view key, bool required) {
  const toml::node* node = lookup(key, required, "a table [" + name(key) + "]");
  const toml::table* t = nullptr;
  if (node != nullptr) {
    t = node->as_table();
    if (t == nullptr)
      error(node, key, "expected a table [" + name(key) + "], got " + type_name(*node));
  }
  return ConfigReader(t, name(key), file_, errors_);
}

bool ConfigReader::string(std::string_view key, bool required, std::string& out,
                          std::initializer_list<std::string_view> allowed) {
  std::string expected = "a string";
  if (allowed.size() != 0) {
    expected = "one of";
    for (auto a : allowed) expected += " \"" + std::string(a) + "\"";
  }
  const toml::node* node = lookup(key, required, expected);
  if (node == nullptr) return false;
  const auto* s = node->as_string();
  if (s == nullptr) {
    error(node, key, "expected " + expected + ", got " + type_name(*node));
    return false;
  }
  const std::string& v = s->get();
  if (allowed.size() != 0 &&
      std::find(allowed.begin(), allowed.end(), std::string_view(v)) == allowed.end()) {
    error(node, key, "expected " + expected + ", got " + describe(*node));
    return false;
  }
  if (allowed.size() == 0 && v.empty()) {
    error(node, key, "expected a non-empty string, got \"\"");
    return false;
  }
  // A NUL would cut a path short where the system reads it (station.journal = "a\u0000b"
  // opens "a"): no key takes one.
  if (v.find('\0') != std::string::npos) {
    error(node, key, "expected a string without NUL characters (\\u0000), got one");
    return false;
  }
  out = v;
  return true;
}

bool ConfigReader::integer(std::string_view key, bool required, std::int64_t min, std::int64_t max,
                           std::int64_t& out) {
  const std::string expected =
      "an integer from " + std::to_string(min) + " to " + std::to_string(max);
  const toml::node* node = lookup(key, required, expected);
  if (node == nullptr) return false;
  const auto* i = node->as_integer();
  if (i == nullptr || i->get() < min || i->get() > max) {
    error(node, key, "expected " + expected + ", got " + describe(*node));
    return false;
  }
  out = i->get();
  return true;
}

bool ConfigReader::real(std::string_view key, bool required, double min, double max, double& out) {
  char range[96];
  std::snprintf(range, sizeof range, "a number from %g to %g", min, max);
  const std::string expected = range;
  const toml::node* node = lookup(key, required, expected);
  if (node == nullptr) return false;
  double v = 0.0;
  if (const auto* i = node->as_integer()) {
    v = static_cast<double>(i->get());
  } else if (const auto* f = node->as_floating_point()) {
    v = f->get();
  } else {
    error(node, key, "expected " + expected + ", got " + describe(*node));
    return false;
  }
  if (!(v >= min && v <= max)) {  // also NaN
    error(node, key, "expected " + expected + ", got " + describe(*node));
    return false;
  }
  out = v;
  return true;
}

bool ConfigReader::boolean(std::string_view key, bool& out) {
  const toml::node* node = lookup(key, false, "true or false");
  if (node == nullptr) return false;
  const auto* b = node->as_boolean();
  if (b == nullptr) {
    error(node, key, "expected true or false, got " + describe(*node));
    return false;
  }
  out = b->get();
  return true;
}

const toml::array* ConfigReader::array(std::string_view key, bool required) {
  const toml::node* node = lookup(key, required, "an array");
  if (node == nullptr) return nullptr;
  const auto* a = node->as_array();
  if (a == nullptr) error(node, key, "expected an array, got " + type_name(*node));
  return a;
}

void ConfigReader::finish() {
  if (table_ == nullptr) return;
  for (auto&& [k, v] : *table_) {
    if (std::find(known_.begin(), known_.end(), k.str()) != known_.end()) continue;
    std::string allowed;
    for (const auto& kn : known_) allowed += (allowed.empty() ? "" : ", ") + kn;
    errors_.push_back({std::string(file_), line_of(k.source()), name(k.str()),
                       "unknown key (allowed here: " + allowed + ")"});
  }
}

}  // namespace twister::station_app::internal
