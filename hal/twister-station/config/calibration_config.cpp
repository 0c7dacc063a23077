#include "calibration_config.hpp"

#include <array>
#include <cmath>
#include <cstdio>

namespace twister::station_app::internal {
namespace {

std::string fmt(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

// An array of exactly three numbers, each in [min, max]; false (reported) otherwise.
bool read_vec3(ConfigReader& r, std::string_view key, double min, double max,
               std::array<double, 3>& out) {
  const toml::array* a = r.array(key, false);
  if (a == nullptr) return false;
  const std::string expected = "an array of three numbers from " + fmt(min) + " to " + fmt(max);
  if (a->size() != 3) {
    r.error(a, key, "expected " + expected + ", got " + std::to_string(a->size()) + " elements");
    return false;
  }
  std::array<double, 3> v{};
  for (std::size_t i = 0; i < 3; ++i) {
    const toml::node& n = *a->get(i);
    if (const auto* x = n.as_integer()) {
      v[i] = static_cast<double>(x->get());
    } else if (const auto* f = n.as_floating_point()) {
      v[i] = f->get();
    } else {
      r.error(&n, key, "expected " + expected + ", got " + describe(n));
      return false;
    }
    if (!(v[i] >= min && v[i] <= max)) {
      r.error(&n, key, "expected " + expected + ", got " + describe(n));
      return false;
    }
  }
  out = v;
  return true;
}

double norm(const std::array<double, 3>& v) {
  return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

// "unit" (leave the unit's EEPROM setting), "off", "medium" (the manual's 0.2, 0.2,
// 0.8, 0.95) or an inline table { f, flow, fhigh, factor }.
void read_filter(ConfigReader& c, std::string_view key, FilterConfig& out) {
  const toml::node* n = c.value(key);
  if (n == nullptr) return;
  if (n->is_string()) {
    std::string mode;
    if (!c.string(key, false, mode, {"unit", "off", "medium"})) return;
    out = FilterConfig{};
    out.mode = mode == "unit"  ? FilterConfig::Mode::unit
               : mode == "off" ? FilterConfig::Mode::off
                               : FilterConfig::Mode::set;
    return;
  }
  const toml::table* t = n->as_table();
  if (t == nullptr) {
    c.error(n, key,
            "expected \"unit\", \"off\", \"medium\" or { f = F, flow = L, fhigh = H, factor = "
            "A }, got " +
                describe(*n));
    return;
  }
  ConfigReader e = c.element(t, key);
  FilterConfig f;
  f.mode = FilterConfig::Mode::set;
  // Every key is read (each bad one reported), then the verdict.
  const std::array<bool, 4> read = {
      e.real("f", true, 0.001, 0.999, f.f), e.real("flow", true, 0.001, 0.999, f.flow),
      e.real("fhigh", true, 0.001, 0.999, f.fhigh), e.real("factor", true, 0.001, 0.999, f.factor)};
  const bool ok = read[0] && read[1] && read[2] && read[3];
  e.finish();
  if (!ok) return;
  if (!(f.flow < f.fhigh)) {
    c.error(n, key,
            "expected flow < fhigh (the unit refuses it), got flow " + fmt(f.flow) + ", fhigh " +
                fmt(f.fhigh));
    return;
  }
  out = f;
}

void read_work_frame(ConfigReader& c, CalibrationConfig& cal) {
  ConfigReader w = c.table("work_frame", false);
  if (!w.present()) {
    w.finish();
    return;
  }
  WorkFrameConfig wf;
  bool ok = true;
  for (const auto& [key, out] : {std::pair{"origin", &wf.origin}, std::pair{"x_axis", &wf.x_axis},
                                 std::pair{"y_axis", &wf.y_axis}}) {
    if (!w.has(key)) {
      w.error_at(line_of(c.node("work_frame")->source()), w.name(key),
                 "missing; the work frame needs origin, x_axis and y_axis (transmitter frame, "
                 "metres)");
      ok = false;
      continue;
    }
    ok = read_vec3(w, key, -10.0, 10.0, *out) && ok;
  }
  if (ok) {
    const double nx = norm(wf.x_axis), ny = norm(wf.y_axis);
    if (nx < 1e-6) {
      w.error(w.node("x_axis"), "x_axis", "expected a non-zero direction, got [0, 0, 0]");
      ok = false;
    }
    if (ny < 1e-6) {
      w.error(w.node("y_axis"), "y_axis", "expected a non-zero direction, got [0, 0, 0]");
      ok = false;
    }
    if (ok) {
      const double cosine = (wf.x_axis[0] * wf.y_axis[0] + wf.x_axis[1] * wf.y_axis[1] +
                             wf.x_axis[2] * wf.y_axis[2]) /
                            (nx * ny);
      const double angle =
          std::acos(std::fmax(-1.0, std::fmin(1.0, cosine))) * 180.0 / 3.14159265358979323846;
      if (std::fabs(angle - 90.0) > kMaxWorkFrameSkewDeg) {
        w.error(w.node("y_axis"), "y_axis",
                "expected a direction perpendicular to x_axis (within " +
                    fmt(kMaxWorkFrameSkewDeg) + " degrees), got " + fmt(angle) +
                    " degrees between them");
        ok = false;
      }
    }
  }
  w.finish();
  if (ok) {
    cal.work_frame = wf;
    cal.has_work_frame = true;
  }
}

void read_work_volume(ConfigReader& c, CalibrationConfig& cal) {
  ConfigReader w = c.table("work_volume", false);
  if (!w.present()) {
    w.finish();
    return;
  }
  WorkVolumeConfig v;
  bool ok = true;
  for (const auto& [key, out] : {std::pair{"min", &v.min}, std::pair{"max", &v.max}}) {
    if (!w.has(key)) {
      w.error_at(line_of(c.node("work_volume")->source()), w.name(key),
                 "missing; the work volume needs min and max (the model's frame, metres)");
      ok = false;
      continue;
    }
    ok = read_vec3(w, key, -10.0, 10.0, *out) && ok;
  }
  for (std::size_t i = 0; ok && i < 3; ++i) {
    if (v.max[i] - v.min[i] < 0.01) {
      w.error(w.node("max"), "max",
              "expected each coordinate at least 0.01 above min's, got " + fmt(v.max[i]) +
                  " against " + fmt(v.min[i]));
      ok = false;
    }
  }
  w.finish();
  if (ok) {
    cal.work_volume = v;
    cal.has_work_volume = true;
  }
}

}  // namespace

void read_calibration(ConfigReader& tracker, TrackerConfig& tc) {
  ConfigReader c = tracker.table("calibration", false);
  CalibrationConfig& cal = tc.calibration;
  std::array<double, 3> h{};
  if (read_vec3(c, "hemisphere", -1.0, 1.0, h)) {
    bool whole = true;
    for (const double x : h) whole = whole && x == std::floor(x);
    if (!whole || norm(h) == 0.0) {
      c.error(c.node("hemisphere"), "hemisphere",
              "expected a direction of -1, 0 or 1 per axis, not all 0 (e.g. [1, 0, 0] forward, "
              "[0, 0, 1] down)");
    } else {
      for (std::size_t i = 0; i < 3; ++i) cal.hemisphere[i] = static_cast<int>(h[i]);
    }
  }
  if (read_vec3(c, "boresight", -180.0, 180.0, cal.boresight_deg)) cal.boresight = true;
  if (read_vec3(c, "boresight_reference", -180.0, 180.0, cal.boresight_reference_deg) &&
      !c.has("boresight")) {
    c.error(c.node("boresight_reference"), "boresight_reference",
            "needs tracker.calibration.boresight (the orientation that reads as these angles)");
  }
  for (const auto& [key, angles] :
       {std::pair{"boresight", &cal.boresight_deg},
        std::pair{"boresight_reference", &cal.boresight_reference_deg}}) {
    if (std::fabs((*angles)[1]) > 90.0) {
      c.error(c.node(key), key,
              "expected an elevation (the second angle) from -90 to 90, got " + fmt((*angles)[1]));
    }
  }
  read_vec3(c, "tip_offset", -0.5, 0.5, cal.tip_offset_m);
  read_filter(c, "position_filter", cal.position_filter);
  read_filter(c, "attitude_filter", cal.attitude_filter);
  read_work_frame(c, cal);
  read_work_volume(c, cal);
  c.finish();
}

}  // namespace twister::station_app::internal
