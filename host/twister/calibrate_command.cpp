// calibrate. The pose file holds `twister fastrak-dump` lines "station ox oy oz ux uy uz
// vx vy vz wx wy wz" (tracker units; "error ..." lines and "#" comments are skipped).
// The stylus's lines (--station) are grouped into rests: runs of consecutive poses
// within --rest-mm of the run's first pose; runs shorter than --rest-poses are the
// stylus moving and are dropped. Exactly three rests must remain: their mean tip points
// (position + R * --tip-offset, metres) are the origin, the +X point and the +Y point.
// The model's +Z (up) is X x Y: touch them counter-clockwise seen from above.
#include "calibrate_command.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "cli_exit_code.hpp"
#include "cli_log.hpp"

namespace twister::cli {
namespace {

struct Vec {
  double x = 0, y = 0, z = 0;
};
Vec operator+(Vec a, Vec b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
Vec operator-(Vec a, Vec b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Vec operator*(double s, Vec a) { return {s * a.x, s * a.y, s * a.z}; }
double dot(Vec a, Vec b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
double length(Vec a) { return std::sqrt(dot(a, a)); }
Vec cross(Vec a, Vec b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

// The points' least distances: the +X point this far from the origin, the +Y point this
// far from the X axis (a stylus rests within a millimetre or two).
constexpr double kMinSpanM = 0.05;

struct CalibrateOptions {
  std::string file;
  std::vector<std::string> points;  // --point X,Y,Z (metres)
  int station = 1;
  std::string units = "in";
  std::string tip_offset = "0,0,0";  // metres, receiver axes
  int rest_poses = 1;
  double rest_mm = 2.0;
};

bool parse_vec(const std::string& text, Vec& out) {
  double v[3];
  char tail = 0;
  if (std::sscanf(text.c_str(), "%lf,%lf,%lf%c", &v[0], &v[1], &v[2], &tail) != 3) return false;
  for (const double x : v) {
    if (!std::isfinite(x)) return false;
  }
  out = {v[0], v[1], v[2]};
  return true;
}

struct Rest {
  Vec first;
  Vec sum;
  int count = 0;
};

// The tip points of the file's rests; "" or the problem.
std::string read_rests(const CalibrateOptions& o, std::vector<Vec>& points) {
  std::ifstream file_stream;
  std::istream* in = &std::cin;
  if (o.file != "-") {
    file_stream.open(o.file);
    if (!file_stream) return o.file + ": cannot read the pose file";
    in = &file_stream;
  }
  Vec tip;
  if (!parse_vec(o.tip_offset, tip)) return "--tip-offset: expected X,Y,Z in metres";
  const double scale = o.units == "cm" ? 0.01 : 0.0254;
  std::vector<Rest> runs;
  std::string line;
  int line_no = 0;
  while (std::getline(*in, line)) {
    ++line_no;
    if (line.empty() || line[0] == '#' || line.rfind("error", 0) == 0) continue;
    std::istringstream fields(line);
    int station = 0;
    double v[12];
    fields >> station;
    for (double& x : v) fields >> x;
    if (!fields) {
      return o.file + ":" + std::to_string(line_no) +
             ": expected a fastrak-dump pose line \"station ox oy oz ux uy uz vx vy vz wx wy "
             "wz\"";
    }
    if (station != o.station) continue;
    // The tip: the receiver's position + its axes (U, V, W) weighted by the offset.
    const Vec p = scale * Vec{v[0], v[1], v[2]};
    const Vec t = p + tip.x * Vec{v[3], v[4], v[5]} + tip.y * Vec{v[6], v[7], v[8]} +
                  tip.z * Vec{v[9], v[10], v[11]};
    if (runs.empty() || length(t - runs.back().first) > o.rest_mm * 1e-3) {
      runs.push_back({t, {}, 0});
    }
    runs.back().sum = runs.back().sum + t;
    ++runs.back().count;
  }
  for (const Rest& r : runs) {
    if (r.count >= o.rest_poses) points.push_back((1.0 / r.count) * r.sum);
  }
  if (points.size() != 3) {
    return o.file + ": expected the stylus (station " + std::to_string(o.station) +
           ") resting at exactly 3 points (runs of at least " + std::to_string(o.rest_poses) +
           " poses within " + std::to_string(o.rest_mm).substr(0, 4) + " mm), found " +
           std::to_string(points.size());
  }
  return {};
}

int run_calibrate(const CalibrateOptions& o) {
  std::vector<Vec> p;
  if (!o.file.empty() && !o.points.empty()) {
    cli_log().error("", "give --file or three --point, not both");
    return kExitBadInput;
  }
  if (!o.file.empty()) {
    if (const std::string problem = read_rests(o, p); !problem.empty()) {
      cli_log().error("", "%s", problem.c_str());
      return kExitBadInput;
    }
  } else {
    for (const std::string& text : o.points) {
      Vec v;
      if (!parse_vec(text, v)) {
        cli_log().error("", "--point %s: expected X,Y,Z in metres", text.c_str());
        return kExitBadInput;
      }
      p.push_back(v);
    }
    if (p.size() != 3) {
      cli_log().error("", "expected three --point (origin, +X, +Y) or --file, got %d",
                      static_cast<int>(p.size()));
      return kExitBadInput;
    }
  }
  const Vec origin = p[0];
  const Vec ax = p[1] - origin;
  const double x_len = length(ax);
  if (x_len < kMinSpanM) {
    cli_log().error("", "the +X point is %.1f mm from the origin; touch it at least %.0f mm away",
                    x_len * 1e3, kMinSpanM * 1e3);
    return kExitBadInput;
  }
  const Vec x = (1.0 / x_len) * ax;
  const Vec ay = (p[2] - origin) - dot(p[2] - origin, x) * x;  // perpendicular part
  const double y_len = length(ay);
  if (y_len < kMinSpanM) {
    cli_log().error("",
                    "the +Y point is %.1f mm from the X axis; touch it at least %.0f mm off "
                    "the line through the origin and the +X point",
                    y_len * 1e3, kMinSpanM * 1e3);
    return kExitBadInput;
  }
  const Vec y = (1.0 / y_len) * ay;
  const Vec z = cross(x, y);
  std::printf(
      "# twister calibrate: the work frame from three touches (transmitter frame, metres):\n"
      "# origin (%.4f, %.4f, %.4f), +X point %.1f mm away, +Y point %.1f mm off the X axis;\n"
      "# the model's up (+Z) is (%.4f, %.4f, %.4f) in the transmitter frame.\n"
      "[tracker.calibration.work_frame]\n"
      "origin = [%.6f, %.6f, %.6f]\n"
      "x_axis = [%.6f, %.6f, %.6f]\n"
      "y_axis = [%.6f, %.6f, %.6f]\n",
      origin.x, origin.y, origin.z, x_len * 1e3, y_len * 1e3, z.x, z.y, z.z, origin.x, origin.y,
      origin.z, x.x, x.y, x.z, y.x, y.y, y.z);
  return kExitOk;
}

}  // namespace

void add_calibrate_command(CLI::App& app, int& exit_code) {
  auto opts = std::make_shared<CalibrateOptions>();
  CLI::App* cmd = app.add_subcommand(
      "calibrate",
      "The work frame from three stylus touches (origin, +X, +Y): prints the station "
      "config's [tracker.calibration.work_frame]");
  cmd->add_option("--file", opts->file,
                  "`twister fastrak-dump` output with the stylus resting at the three points "
                  "in turn ('-' = stdin)");
  cmd->add_option("--point", opts->points,
                  "X,Y,Z in metres, transmitter frame; three times: origin, +X, +Y");
  cmd->add_option("--station", opts->station, "the stylus's receiver")
      ->check(CLI::Range(1, 4))
      ->capture_default_str();
  cmd->add_option("--units", opts->units, "the file's units: in | cm")
      ->check(CLI::IsMember({"in", "cm"}))
      ->capture_default_str();
  cmd->add_option("--tip-offset", opts->tip_offset,
                  "X,Y,Z metres in the stylus's axes (as tracker.calibration.tip_offset)")
      ->capture_default_str();
  cmd->add_option("--rest-poses", opts->rest_poses,
                  "poses a rest needs (60 Hz per receiver: 30 = half a second)")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  cmd->add_option("--rest-mm", opts->rest_mm, "how still a rest is, mm")
      ->check(CLI::Range(0.01, 100.0))
      ->capture_default_str();
  cmd->callback([opts, &exit_code] {
    start_command_log("calibrate");
    exit_code = run_calibrate(*opts);
  });
}

}  // namespace twister::cli
