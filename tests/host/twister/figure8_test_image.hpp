// Test helpers for the Figure 8 pictures: load a PNG with cairo and count pixels of
// a colour; count the glyphs and read the labels of a cairo SVG.
#pragma once

#include <cairo.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>

namespace twister::cli::test {

struct LoadedPng {
  cairo_status_t status = CAIRO_STATUS_NULL_POINTER;
  int width = 0;
  int height = 0;
  std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)> surface{
      nullptr, &cairo_surface_destroy};

  // 0xRRGGBB of a pixel (alpha ignored: the picture is opaque).
  std::uint32_t pixel(int x, int y) const {
    const unsigned char* row =
        cairo_image_surface_get_data(surface.get()) +
        static_cast<std::ptrdiff_t>(y) * cairo_image_surface_get_stride(surface.get());
    std::uint32_t v;
    std::memcpy(&v, row + 4 * x, sizeof v);
    return v & 0xffffffu;
  }

  // Pixels in [x0, x1) x [y0, y1) within `tol` per channel of `rgb`.
  int count(std::uint32_t rgb, int tol, int x0 = 0, int y0 = 0, int x1 = -1, int y1 = -1) const {
    if (x1 < 0) x1 = width;
    if (y1 < 0) y1 = height;
    int n = 0;
    for (int y = y0; y < y1; ++y) {
      for (int x = x0; x < x1; ++x) {
        const std::uint32_t p = pixel(x, y);
        bool near = true;
        for (int shift : {0, 8, 16}) {
          const int a = static_cast<int>((p >> shift) & 0xffu);
          const int b = static_cast<int>((rgb >> shift) & 0xffu);
          near = near && std::abs(a - b) <= tol;
        }
        n += near ? 1 : 0;
      }
    }
    return n;
  }
};

inline LoadedPng load_png(const std::string& path) {
  LoadedPng png;
  png.surface.reset(cairo_image_surface_create_from_png(path.c_str()));
  png.status = cairo_surface_status(png.surface.get());
  if (png.status == CAIRO_STATUS_SUCCESS) {
    cairo_surface_flush(png.surface.get());
    png.width = cairo_image_surface_get_width(png.surface.get());
    png.height = cairo_image_surface_get_height(png.surface.get());
  }
  return png;
}

inline std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// Text between the first <desc> and </desc> (the labels, one per line).
inline std::string svg_desc(const std::string& svg) {
  const auto a = svg.find("<desc>"), b = svg.find("</desc>");
  if (a == std::string::npos || b == std::string::npos || b < a) return {};
  return svg.substr(a + 6, b - a - 6);
}

// Glyphs cairo placed (one <use> of a glyph symbol each).
inline std::size_t svg_glyph_uses(const std::string& svg) {
  std::size_t n = 0;
  for (auto p = svg.find("xlink:href=\"#glyph"); p != std::string::npos;
       p = svg.find("xlink:href=\"#glyph", p + 1))
    ++n;
  return n;
}

// Code points other than spaces and line breaks (UTF-8 continuation bytes skipped).
inline std::size_t visible_chars(const std::string& s) {
  std::size_t n = 0;
  for (const char ch : s) {
    const auto b = static_cast<unsigned char>(ch);
    if ((b & 0xc0u) != 0x80u && ch != ' ' && ch != '\n') ++n;
  }
  return n;
}

}  // namespace twister::cli::test
