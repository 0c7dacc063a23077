#include "figure8_plot.hpp"

#include <png.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <limits>

namespace twister::cli {

namespace {

constexpr int kCell = 200;  // pixels per cell
constexpr int kLabel = 40;  // room for row/column labels
constexpr double kPad = 0.06;

struct Grid {
  std::vector<math::WarpMethod> rows;
  std::vector<int> cols;
  glm::dvec2 lo{std::numeric_limits<double>::max()}, hi{-std::numeric_limits<double>::max()};

  explicit Grid(const std::vector<Figure8Curve>& curves) {
    for (const auto& c : curves) {
      if (std::find(rows.begin(), rows.end(), c.method) == rows.end()) rows.push_back(c.method);
      if (std::find(cols.begin(), cols.end(), c.angle_deg) == cols.end())
        cols.push_back(c.angle_deg);
      for (const auto& p : c.points) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
      }
    }
  }
  int row(math::WarpMethod m) const {
    return static_cast<int>(std::find(rows.begin(), rows.end(), m) - rows.begin());
  }
  int col(int a) const {
    return static_cast<int>(std::find(cols.begin(), cols.end(), a) - cols.begin());
  }
  // Cell-local pixel position, y up in the curve, down in the image.
  glm::dvec2 map(glm::dvec2 p, int r, int c) const {
    const double span = std::max(hi.x - lo.x, hi.y - lo.y) * (1.0 + 2.0 * kPad);
    const glm::dvec2 mid = 0.5 * (lo + hi);
    const double s = kCell / span;
    return {kLabel + c * kCell + kCell / 2.0 + (p.x - mid.x) * s,
            kLabel + r * kCell + kCell / 2.0 - (p.y - mid.y) * s};
  }
  int width() const { return kLabel + static_cast<int>(cols.size()) * kCell; }
  int height() const { return kLabel + static_cast<int>(rows.size()) * kCell; }
};

const char* colour(math::WarpMethod m) {
  switch (m) {
    case math::WarpMethod::twister:
      return "#c0392b";
    case math::WarpMethod::rottran:
      return "#2471a3";
    case math::WarpMethod::scodef:
      return "#1e8449";
  }
  return "#000000";
}

std::array<std::uint8_t, 3> rgb(math::WarpMethod m) {
  unsigned v = 0;
  std::sscanf(colour(m) + 1, "%x", &v);
  return {static_cast<std::uint8_t>(v >> 16), static_cast<std::uint8_t>(v >> 8),
          static_cast<std::uint8_t>(v)};
}

}  // namespace

bool write_figure8_svg(const std::string& path, const std::vector<Figure8Curve>& curves,
                       const std::string& title, std::string& error) {
  const Grid g(curves);
  std::ofstream out(path);
  if (!out) {
    error = "cannot write '" + path + "'";
    return false;
  }
  out << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << g.width() << "\" height=\""
      << g.height() + 20 << "\" font-family=\"sans-serif\" font-size=\"13\">\n"
      << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
      << "<text x=\"4\" y=\"" << g.height() + 15 << "\">" << title << "</text>\n";
  for (std::size_t c = 0; c < g.cols.size(); ++c) {
    out << "<text x=\"" << kLabel + static_cast<int>(c) * kCell + kCell / 2 - 14 << "\" y=\"25\">"
        << g.cols[c] << "&#176;</text>\n";
  }
  for (std::size_t r = 0; r < g.rows.size(); ++r) {
    const int y = kLabel + static_cast<int>(r) * kCell + kCell / 2;
    out << "<text x=\"4\" y=\"" << y << "\" transform=\"rotate(-90 14 " << y << ")\">"
        << math::warp_method_name(g.rows[r]) << "</text>\n";
  }
  for (const auto& cur : curves) {
    const int r = g.row(cur.method), c = g.col(cur.angle_deg);
    out << "<rect x=\"" << kLabel + c * kCell << "\" y=\"" << kLabel + r * kCell << "\" width=\""
        << kCell << "\" height=\"" << kCell << "\" fill=\"none\" stroke=\"#cccccc\"/>\n";
    out << "<polyline fill=\"none\" stroke=\"" << colour(cur.method)
        << "\" stroke-width=\"1.5\" points=\"";
    char buf[64];
    for (const auto& p : cur.points) {
      const glm::dvec2 q = g.map(p, r, c);
      std::snprintf(buf, sizeof buf, "%.1f,%.1f ", q.x, q.y);
      out << buf;
    }
    out << "\"/>\n<text x=\"" << kLabel + c * kCell + 4 << "\" y=\"" << kLabel + (r + 1) * kCell - 6
        << "\" font-size=\"11\">" << cur.intersections << " x, "
        << static_cast<int>(std::lround(cur.sharpest_turn_deg)) << "&#176;</text>\n";
  }
  out << "</svg>\n";
  out.close();
  if (!out) {
    error = "write to '" + path + "' failed";
    return false;
  }
  return true;
}

bool write_figure8_png(const std::string& path, const std::vector<Figure8Curve>& curves,
                       std::string& error) {
  const Grid g(curves);
  const int w = g.width(), h = g.height();
  std::vector<std::uint8_t> img(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 3, 255);
  const auto plot = [&](int x, int y, std::array<std::uint8_t, 3> c) {
    if (x < 0 || y < 0 || x >= w || y >= h) return;
    std::uint8_t* px = &img[(static_cast<std::size_t>(y) * static_cast<std::size_t>(w) +
                             static_cast<std::size_t>(x)) *
                            3];
    px[0] = c[0];
    px[1] = c[1];
    px[2] = c[2];
  };
  for (int x = kLabel; x < w; x += kCell) {
    for (int y = kLabel; y < h; ++y) plot(x, y, {200, 200, 200});
  }
  for (int y = kLabel; y < h; y += kCell) {
    for (int x = kLabel; x < w; ++x) plot(x, y, {200, 200, 200});
  }
  for (const auto& cur : curves) {
    const int r = g.row(cur.method), c = g.col(cur.angle_deg);
    const auto col = rgb(cur.method);
    for (std::size_t i = 0; i + 1 < cur.points.size(); ++i) {
      const glm::dvec2 a = g.map(cur.points[i], r, c), b = g.map(cur.points[i + 1], r, c);
      const int steps = std::max(1, static_cast<int>(std::ceil(glm::length(b - a) * 2.0)));
      for (int s = 0; s <= steps; ++s) {
        const glm::dvec2 p = a + (b - a) * (static_cast<double>(s) / steps);
        const int px = static_cast<int>(std::lround(p.x)), py = static_cast<int>(std::lround(p.y));
        plot(px, py, col);
        plot(px + 1, py, col);
        plot(px, py + 1, col);
      }
    }
  }
  FILE* f = std::fopen(path.c_str(), "wb");
  if (f == nullptr) {
    error = "cannot write '" + path + "'";
    return false;
  }
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png != nullptr ? png_create_info_struct(png) : nullptr;
  if (png == nullptr || info == nullptr || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    std::fclose(f);
    error = "libpng failed writing '" + path + "'";
    return false;
  }
  png_init_io(png, f);
  png_set_IHDR(png, info, static_cast<png_uint_32>(w), static_cast<png_uint_32>(h), 8,
               PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  for (int y = 0; y < h; ++y) {
    png_write_row(png, &img[static_cast<std::size_t>(y) * static_cast<std::size_t>(w) * 3]);
  }
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return std::fclose(f) == 0;
}

}  // namespace twister::cli
