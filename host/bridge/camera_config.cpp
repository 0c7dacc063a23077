#include "camera_config.hpp"

#define TOML_EXCEPTIONS 0
#include <toml++/toml.h>

#include <cmath>
#include <fstream>
#include <sstream>

namespace twister::bridge {
namespace {

constexpr const char* kCameraKeys[] = {"azimuth_deg", "elevation_deg", "zoom", "fov_deg",
                                       "up",          "target",        "fixed"};

hal::Error bad(const std::string& file, const std::string& key, const std::string& what) {
  return hal::make_error(StatusCode::invalid_argument, file + ": camera." + key + ": " + what);
}

// A number in [lo, hi] into `out`; absent keys keep the default.
hal::Expected<void> read_number(const toml::table& t, const std::string& file, const char* key,
                                double lo, double hi, float& out) {
  const toml::node* n = t.get(key);
  if (n == nullptr) return {};
  const std::optional<double> v = n->value<double>();
  if (!v || !std::isfinite(*v) || *v < lo || *v > hi) {
    std::ostringstream range;
    range << "expected a number from " << lo << " to " << hi;
    return bad(file, key, range.str());
  }
  out = static_cast<float>(*v);
  return {};
}

hal::Expected<void> read_vec3(const toml::table& t, const std::string& file, const char* key,
                              float (&out)[3], bool& present) {
  const toml::node* n = t.get(key);
  if (n == nullptr) return {};
  const toml::array* a = n->as_array();
  if (a == nullptr || a->size() != 3) return bad(file, key, "expected [x, y, z] in metres");
  for (std::size_t i = 0; i < 3; ++i) {
    const std::optional<double> v = (*a)[i].value<double>();
    if (!v || !std::isfinite(*v)) return bad(file, key, "expected [x, y, z] in metres");
    out[i] = static_cast<float>(*v);
  }
  present = true;
  return {};
}

hal::Expected<void> read_camera(const toml::table& t, const std::string& file, CameraConfig& c) {
  for (const auto& [key, node] : t) {
    bool known = false;
    for (const char* k : kCameraKeys) known = known || key.str() == k;
    if (!known) return bad(file, std::string(key.str()), "unknown key");
  }
  hal::Expected<void> ok = read_number(t, file, "azimuth_deg", -360.0, 360.0, c.view.azimuth_deg);
  if (ok) ok = read_number(t, file, "elevation_deg", -89.0, 89.0, c.view.elevation_deg);
  if (ok) ok = read_number(t, file, "zoom", 0.05, 50.0, c.view.zoom);
  if (ok) ok = read_number(t, file, "fov_deg", 5.0, 120.0, c.view.fov_deg);
  bool up_given = false;
  if (ok) ok = read_vec3(t, file, "up", c.view.up, up_given);
  if (ok && up_given && std::hypot(c.view.up[0], c.view.up[1], c.view.up[2]) < 1e-6F) {
    ok = bad(file, "up", "expected a non-zero direction");
  }
  if (ok) ok = read_vec3(t, file, "target", c.view.target, c.view.has_target);
  if (ok && t.get("fixed") != nullptr) {
    const toml::value<bool>* fixed = t.get("fixed")->as_boolean();
    if (fixed == nullptr) return bad(file, "fixed", "expected true or false");
    c.fixed = fixed->get();
  }
  return ok;
}

hal::Expected<void> read_attract(const toml::table& t, const std::string& file, AttractConfig& a) {
  const auto wrong = [&](const std::string& key, const std::string& what) {
    return hal::make_error(StatusCode::invalid_argument, file + ": attract." + key + ": " + what);
  };
  for (const auto& [key, node] : t) {
    const std::string k(key.str());
    if (k != "archive" && k != "models" && k != "seconds") return wrong(k, "unknown key");
  }
  if (const toml::node* n = t.get("archive")) {
    const std::optional<std::string> v = n->value<std::string>();
    if (!v || v->empty()) return wrong("archive", "expected the archive directory's path");
    a.archive = *v;
  }
  if (const toml::node* n = t.get("models")) {
    const std::optional<std::int64_t> v = n->value<std::int64_t>();
    if (!v || *v < 1 || *v > 32 || !n->is_integer())
      return wrong("models", "expected a whole number from 1 to 32");
    a.models = static_cast<int>(*v);
  }
  if (const toml::node* n = t.get("seconds")) {
    const std::optional<double> v = n->value<double>();
    if (!v || !std::isfinite(*v) || *v < 1.0 || *v > 600.0)
      return wrong("seconds", "expected a number from 1 to 600");
    a.seconds = *v;
  }
  return {};
}

}  // namespace

hal::Expected<CameraConfig> parse_camera_config(const std::string& text,
                                                const std::string& file_name) {
  toml::parse_result parsed = toml::parse(text, file_name);
  if (!parsed) {
    std::ostringstream where;
    where << file_name << ":" << parsed.error().source().begin.line
          << ": TOML syntax error: " << parsed.error().description();
    return hal::make_error(StatusCode::invalid_argument, where.str());
  }
  const toml::table& root = parsed.table();
  CameraConfig config;
  for (const auto& [key, node] : root) {
    if ((key.str() != "camera" && key.str() != "attract") || !node.is_table()) {
      return hal::make_error(StatusCode::invalid_argument,
                             file_name + ": " + std::string(key.str()) +
                                 ": unknown (the file holds a [camera] and an [attract] table)");
    }
  }
  if (const toml::table* attract = root["attract"].as_table()) {
    if (hal::Expected<void> ok = read_attract(*attract, file_name, config.attract); !ok)
      return ok.error();
  }
  if (const toml::table* camera = root["camera"].as_table()) {
    if (hal::Expected<void> ok = read_camera(*camera, file_name, config); !ok) return ok.error();
  }
  return config;
}

hal::Expected<CameraConfig> load_camera_config(const std::string& path) {
  std::ifstream in(path);
  if (!in) return hal::make_error(StatusCode::io_error, "cannot read the camera file " + path);
  std::ostringstream text;
  text << in.rdbuf();
  return parse_camera_config(text.str(), path);
}

}  // namespace twister::bridge
