#include "warp_case.hpp"

#include <cerrno>
#include <cmath>
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

}  // namespace

std::variant<WarpCase, WarpCaseError> parse_warp_case(std::string_view text) {
  WarpCase c;
  int radius_line = 0;
  int method_line = 0;
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
      return fail("unknown keyword '" + key + "' (radius | method | hand | point)");
    }
  }
  if (radius_line == 0) return WarpCaseError{line_no, "end of input: no radius given"};
  if (c.start.empty()) return WarpCaseError{line_no, "end of input: no hand given"};
  if (c.start.size() == 2 && glm::length(c.start[1].origin - c.start[0].origin) <=
                                 math::kCoincidentGrabFraction * c.radius) {
    return WarpCaseError{c.hand_lines[1],
                         "both hands grab the same point: the squash is undefined"};
  }
  return c;
}

}  // namespace twister::cli
