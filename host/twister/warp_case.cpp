#include "warp_case.hpp"

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <glm/geometric.hpp>
#include <optional>
#include <sstream>

#include "twister/math/warp_plan.hpp"

namespace twister::cli {

namespace {

std::vector<std::string> tokens_of(std::string_view line) {
  if (const auto hash = line.find('#'); hash != std::string_view::npos) {
    line = line.substr(0, hash);
  }
  std::vector<std::string> out;
  std::istringstream in{std::string(line)};
  for (std::string tok; in >> tok;) out.push_back(tok);
  return out;
}

std::optional<double> number(const std::string& tok) {
  errno = 0;
  char* end = nullptr;
  const double v = std::strtod(tok.c_str(), &end);
  // strtod accepts "nan"/"inf": only finite numbers are numbers here.
  if (end == tok.c_str() || *end != '\0' || !std::isfinite(v)) return std::nullopt;
  return v;
}

std::string check_axes(glm::dvec3 u, glm::dvec3 v, const char* which) {
  const double tol = math::kFrameTolerance;
  std::ostringstream msg;
  if (std::fabs(glm::length(u) - 1.0) > tol || std::fabs(glm::length(v) - 1.0) > tol ||
      std::fabs(glm::dot(u, v)) > tol) {
    msg.precision(9);
    msg << which << " frame is not orthonormal within 1e-6 (|U| = " << glm::length(u)
        << ", |V| = " << glm::length(v) << ", U.V = " << glm::dot(u, v) << ")";
  }
  return msg.str();
}

constexpr const char* kSymmetryForms =
    "none | x | y | z | xy | xz | yz | xyz | rotation AXIS N [mirror]";

// The words after `symmetry` (docs/math.md §10): a set of mirror planes, or an n-fold
// rotation about a coordinate axis, optionally with mirrors through the axis.
std::optional<std::string> parse_symmetry(const std::vector<std::string>& tok,
                                          math::SymmetryGroup& group) {
  if (tok.size() == 2 && tok[1] == "none") {
    group.set_none();
    return std::nullopt;
  }
  if (tok.size() == 2 && tok[1] != "rotation") {
    std::uint8_t planes = 0;
    for (const char ch : tok[1]) {
      const std::uint8_t bit = ch == 'x'   ? math::kMirrorX
                               : ch == 'y' ? math::kMirrorY
                               : ch == 'z' ? math::kMirrorZ
                                           : 0;
      if (bit == 0 || (planes & bit) != 0) {
        return "unknown symmetry '" + tok[1] + "' (" + kSymmetryForms + ")";
      }
      planes = static_cast<std::uint8_t>(planes | bit);
    }
    if (!group.set_mirrors(planes).ok()) return std::string("bad mirror planes");
    return std::nullopt;
  }
  if ((tok.size() == 4 || tok.size() == 5) && tok[1] == "rotation") {
    const int axis = tok[2] == "x" ? 0 : tok[2] == "y" ? 1 : tok[2] == "z" ? 2 : -1;
    if (axis < 0) return "rotation axis must be x, y or z, got '" + tok[2] + "'";
    char* end = nullptr;
    const long n = std::strtol(tok[3].c_str(), &end, 10);
    if (end == tok[3].c_str() || *end != '\0' || n < math::kMinRotationOrder ||
        n > math::kMaxRotationOrder) {
      return "rotation order must be an integer from 2 to 12, got '" + tok[3] + "'";
    }
    if (tok.size() == 5 && tok[4] != "mirror") {
      return "after the rotation order only 'mirror' may follow, got '" + tok[4] + "'";
    }
    if (!group.set_rotation(axis, static_cast<int>(n), tok.size() == 5).ok()) {
      return std::string("bad rotation");
    }
    return std::nullopt;
  }
  return std::string("'symmetry' needs ") + kSymmetryForms;
}

}  // namespace

std::variant<WarpCase, WarpCaseError> parse_warp_case(std::string_view text) {
  WarpCase c;
  int radius_line = 0;
  int method_line = 0;
  int symmetry_line = 0;
  int line_no = 0;
  std::size_t pos = 0;
  while (pos <= text.size()) {
    const std::size_t nl = text.find('\n', pos);
    const std::string_view line =
        text.substr(pos, nl == std::string_view::npos ? std::string_view::npos : nl - pos);
    pos = nl == std::string_view::npos ? text.size() + 1 : nl + 1;
    ++line_no;
    const std::vector<std::string> tok = tokens_of(line);
    if (tok.empty()) continue;
    const std::string& key = tok[0];
    const auto fail = [line_no](std::string m) { return WarpCaseError{line_no, std::move(m)}; };
    const auto numbers = [&](std::size_t want,
                             std::vector<double>& out) -> std::optional<WarpCaseError> {
      if (tok.size() - 1 != want) {
        return fail("'" + key + "' needs " + std::to_string(want) + " numbers, got " +
                    std::to_string(tok.size() - 1));
      }
      for (std::size_t i = 1; i < tok.size(); ++i) {
        const auto v = number(tok[i]);
        if (!v) return fail("'" + tok[i] + "' is not a finite number");
        out.push_back(*v);
      }
      return std::nullopt;
    };
    std::vector<double> v;
    if (key == "radius") {
      if (radius_line != 0) return fail("radius given twice");
      if (auto e = numbers(1, v)) return *e;
      if (!(v[0] > 0.0)) return fail("radius must be > 0, got " + tok[1]);
      c.radius = v[0];
      radius_line = line_no;
    } else if (key == "method") {
      if (method_line != 0) return fail("method given twice");
      if (tok.size() != 2) return fail("'method' needs one word: twister | rottran | scodef");
      const auto m = math::parse_warp_method(tok[1]);
      if (!m) return fail("unknown method '" + tok[1] + "' (twister | rottran | scodef)");
      c.method = *m;
      method_line = line_no;
    } else if (key == "symmetry") {
      if (symmetry_line != 0) return fail("symmetry given twice");
      if (auto m = parse_symmetry(tok, c.symmetry)) return fail(*m);
      symmetry_line = line_no;
    } else if (key == "hand") {
      if (c.start.size() == 2) return fail("a third hand (at most two)");
      if (auto e = numbers(18, v)) return *e;
      const glm::dvec3 o(v[0], v[1], v[2]), u(v[3], v[4], v[5]), w(v[6], v[7], v[8]);
      const glm::dvec3 o2(v[9], v[10], v[11]), u2(v[12], v[13], v[14]), w2(v[15], v[16], v[17]);
      if (auto m = check_axes(u, w, "start"); !m.empty()) return fail(m);
      if (auto m = check_axes(u2, w2, "end"); !m.empty()) return fail(m);
      c.start.push_back(math::frame_from_uv(o, u, w));
      c.end.push_back(math::frame_from_uv(o2, u2, w2));
      c.hand_lines.push_back(line_no);
    } else if (key == "point") {
      if (auto e = numbers(3, v)) return *e;
      c.points.emplace_back(v[0], v[1], v[2]);
    } else {
      return fail("unknown keyword '" + key + "' (radius | method | symmetry | hand | point)");
    }
  }
  if (radius_line == 0) return WarpCaseError{line_no, "end of input: no radius given"};
  if (c.start.empty()) return WarpCaseError{line_no, "end of input: no hand given"};
  if (c.start.size() == 2 && glm::length(c.start[1].origin - c.start[0].origin) <=
                                 math::kCoincidentGrabFraction * c.radius) {
    return WarpCaseError{c.hand_lines[1],
                         "both hands grab the same point: the squash is undefined"};
  }
  if (c.start.size() == 2) {
    for (std::size_t g = 1; g < c.symmetry.order(); ++g) {
      if (glm::length(c.start[1].origin - c.symmetry.element(g) * c.start[0].origin) <=
          math::kCoincidentGrabFraction * c.radius) {
        return WarpCaseError{c.hand_lines[1],
                             "the second hand grabs an image of the first hand's grab point "
                             "under the symmetry: the squash is undefined"};
      }
    }
  }
  return c;
}

}  // namespace twister::cli
