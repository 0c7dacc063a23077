#include "figure8_plot.hpp"

#include <cairo-svg.h>
#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <memory>
#include <numbers>
#include <string>

#include "twister/hal/posix_file_sink.hpp"

namespace twister::cli {

namespace {

// Layout in pixels. Cells are wider than tall because the bent line is.
constexpr int kMargin = 24;
constexpr int kTitleH = 108;     // title, subtitle, legend
constexpr int kHeadingH = 34;    // panel heading
constexpr int kColHeadH = 24;    // angle above each column
constexpr int kRowLabelW = 110;  // method name left of each row
constexpr int kCellW = 190;
constexpr int kPlotH = 132;          // curve area at the top of a cell
constexpr int kCellH = kPlotH + 22;  // plus one line of numbers
constexpr int kPanelGap = 18;
constexpr double kPlotPad = 8.0;
constexpr const char* kFont = "DejaVu Sans";

struct Rgb {
  double r, g, b;
};
constexpr Rgb kInk{0.13, 0.13, 0.13};
constexpr Rgb kMuted{0.40, 0.40, 0.40};
constexpr Rgb kRest{0.78, 0.78, 0.78};  // the line before the warp
constexpr Rgb kFrame{0.82, 0.82, 0.82};
constexpr Rgb kAlarm{0.70, 0.08, 0.08};  // a non-zero crossing count

Rgb colour(math::WarpMethod m) {
  switch (m) {
    case math::WarpMethod::twister:
      return {0xc0 / 255.0, 0x39 / 255.0, 0x2b / 255.0};
    case math::WarpMethod::rottran:
      return {0x24 / 255.0, 0x71 / 255.0, 0xa3 / 255.0};
    case math::WarpMethod::scodef:
      return {0x1e / 255.0, 0x84 / 255.0, 0x49 / 255.0};
  }
  return kInk;
}

const char* method_note(math::WarpMethod m) {
  switch (m) {
    case math::WarpMethod::twister:
      return "screw motion";
    case math::WarpMethod::rottran:
      return "rotate, translate";
    case math::WarpMethod::scodef:
      return "point constraints";
  }
  return "";
}

std::string degrees(double v, const char* fmt) {
  char buf[32];
  std::snprintf(buf, sizeof buf, fmt, std::abs(v));
  // A typographic minus: the picture is read, not parsed.
  return (v < 0 ? std::string("\u2212") : std::string()) + buf + "\u00b0";
}

enum class Align { left, centre };

// Draws text and records it, so the SVG can carry every label as text as well.
class Painter {
 public:
  Painter(cairo_t* cr, std::vector<std::string>& texts) : cr_(cr), texts_(texts) {}
  cairo_t* cr() const { return cr_; }

  // (x, y) is the baseline start (left) or the baseline centre (centre).
  double text(double x, double y, const std::string& s, double size, bool bold, Rgb c,
              Align align = Align::left) {
    cairo_select_font_face(cr_, kFont, CAIRO_FONT_SLANT_NORMAL,
                           bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr_, size);
    cairo_text_extents_t ext;
    cairo_text_extents(cr_, s.c_str(), &ext);
    cairo_set_source_rgb(cr_, c.r, c.g, c.b);
    cairo_move_to(cr_, align == Align::centre ? x - ext.x_advance / 2.0 : x, y);
    cairo_show_text(cr_, s.c_str());
    texts_.push_back(s);
    return ext.x_advance;
  }

  void line(double x0, double y0, double x1, double y1, Rgb c, double width) {
    cairo_set_source_rgb(cr_, c.r, c.g, c.b);
    cairo_set_line_width(cr_, width);
    cairo_move_to(cr_, x0, y0);
    cairo_line_to(cr_, x1, y1);
    cairo_stroke(cr_);
  }

  // Grab point at rest: a hollow ring; held by the hand: a dark dot.
  void grab(double x, double y, bool held) {
    cairo_new_sub_path(cr_);
    cairo_arc(cr_, x, y, 3.5, 0.0, 2.0 * std::numbers::pi);
    if (held) {
      cairo_set_source_rgb(cr_, kInk.r, kInk.g, kInk.b);
      cairo_fill_preserve(cr_);
      cairo_set_source_rgb(cr_, 1.0, 1.0, 1.0);
      cairo_set_line_width(cr_, 1.0);
    } else {
      cairo_set_source_rgb(cr_, 0.55, 0.55, 0.55);
      cairo_set_line_width(cr_, 1.3);
    }
    cairo_stroke(cr_);
  }

 private:
  cairo_t* cr_;
  std::vector<std::string>& texts_;
};

std::vector<math::WarpMethod> methods_of(const Figure8Panel& p) {
  std::vector<math::WarpMethod> out;
  for (const auto& c : p.curves)
    if (std::find(out.begin(), out.end(), c.method) == out.end()) out.push_back(c.method);
  return out;
}

std::vector<int> angles_of(const Figure8Panel& p) {
  std::vector<int> out;
  for (const auto& c : p.curves)
    if (std::find(out.begin(), out.end(), c.angle_deg) == out.end()) out.push_back(c.angle_deg);
  return out;
}

// Rows and columns of the picture: the largest counts of any panel.
struct Grid {
  std::size_t rows = 0, cols = 0;
  explicit Grid(const Figure8Picture& pic) {
    for (const auto& panel : pic.panels) {
      rows = std::max(rows, methods_of(panel).size());
      cols = std::max(cols, angles_of(panel).size());
    }
  }
};

// The one scale shared by the cells of a panel. Panels differ in scale because the
// small displacement bends the line further out of its rest place (r = 1).
struct PanelScale {
  glm::dvec2 mid{0.0};
  double scale = 1.0;  // pixels per scene unit

  explicit PanelScale(const Figure8Panel& panel) {
    // The line before the warp is drawn too: x in [-1, 1] at y = 0.
    glm::dvec2 lo(-1.0, 0.0), hi(1.0, 0.0);
    for (const auto& c : panel.curves) {
      for (const auto& p : c.points) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
      }
    }
    mid = 0.5 * (lo + hi);
    const glm::dvec2 span = glm::max(hi - lo, glm::dvec2(1e-9));
    scale = std::min((kCellW - 2 * kPlotPad) / span.x, (kPlotH - 2 * kPlotPad) / span.y);
  }
  // Scene point -> pixel in the cell whose top-left corner is (x0, y0); y up in the scene.
  glm::dvec2 map(glm::dvec2 p, double x0, double y0) const {
    return {x0 + kCellW / 2.0 + (p.x - mid.x) * scale, y0 + kPlotH / 2.0 - (p.y - mid.y) * scale};
  }
};

void draw_legend(Painter& pt, double y) {
  double x = kMargin;
  for (const auto m :
       {math::WarpMethod::twister, math::WarpMethod::rottran, math::WarpMethod::scodef}) {
    pt.line(x, y - 4.5, x + 26, y - 4.5, colour(m), 2.5);
    x += 32 + pt.text(x + 32, y, std::string(math::warp_method_name(m)), 13, true, colour(m));
    x += 22;
  }
  pt.line(x, y - 4.5, x + 26, y - 4.5, kRest, 1.5);
  x += 32 + pt.text(x + 32, y, "line before the warp", 13, false, kInk) + 22;
  pt.grab(x + 5, y - 4.5, false);
  x += 14 + pt.text(x + 14, y, "grab point at rest", 13, false, kInk) + 22;
  pt.grab(x + 5, y - 4.5, true);
  pt.text(x + 14, y, "grab point held by the hand", 13, false, kInk);
}

void draw_cell(Painter& pt, const PanelScale& panel_scale, const Figure8Panel& panel,
               const Figure8Curve& c, double x0, double y0) {
  cairo_t* cr = pt.cr();
  cairo_set_source_rgb(cr, kFrame.r, kFrame.g, kFrame.b);
  cairo_set_line_width(cr, 1.0);
  cairo_rectangle(cr, x0 + 0.5, y0 + 0.5, kCellW, kCellH);
  cairo_stroke(cr);

  const glm::dvec2 a = panel_scale.map({-1.0, 0.0}, x0, y0),
                   b = panel_scale.map({1.0, 0.0}, x0, y0);
  pt.line(a.x, a.y, b.x, b.y, kRest, 1.5);

  const Rgb rgb = colour(c.method);
  cairo_set_source_rgb(cr, rgb.r, rgb.g, rgb.b);
  cairo_set_line_width(cr, 1.8);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  // The 2001 points lie about 0.2 px apart: points closer than kMinStepPx to the last
  // drawn one are skipped (the drawn line stays within that distance of the curve),
  // which keeps the SVG small. The last point is always drawn.
  constexpr double kMinStepPx = 0.4;
  glm::dvec2 last{0.0};
  for (std::size_t i = 0; i < c.points.size(); ++i) {
    const glm::dvec2 q = panel_scale.map(c.points[i], x0, y0);
    if (i == 0) {
      cairo_move_to(cr, q.x, q.y);
    } else if (i + 1 == c.points.size() || glm::distance(q, last) >= kMinStepPx) {
      cairo_line_to(cr, q.x, q.y);
    } else {
      continue;
    }
    last = q;
  }
  cairo_stroke(cr);

  // The grabs sit at x = -0.5 and +0.5; both hands move by (0, lift, 0) (docs/math.md §9).
  for (const double gx : {-0.5, 0.5}) {
    const glm::dvec2 rest = panel_scale.map({gx, 0.0}, x0, y0);
    const glm::dvec2 held = panel_scale.map({gx, panel.setup.lift}, x0, y0);
    pt.grab(rest.x, rest.y, false);
    pt.grab(held.x, held.y, true);
  }

  const double ty = y0 + kCellH - 7;
  char buf[48];
  std::snprintf(buf, sizeof buf, "%zu crossing%s", c.intersections,
                c.intersections == 1 ? "" : "s");
  const bool crossed = c.intersections > 0;
  const double w = pt.text(x0 + 8, ty, buf, 12, crossed, crossed ? kAlarm : kMuted);
  pt.text(x0 + 8 + w, ty, ", turn " + degrees(c.sharpest_turn_deg, "%.1f"), 12, false, kMuted);
}

void draw_panel(Painter& pt, const Figure8Panel& panel, double top) {
  pt.text(kMargin, top + 22, panel.heading, 15, true, kInk);
  const PanelScale panel_scale(panel);
  const auto methods = methods_of(panel);
  const auto angles = angles_of(panel);
  const double grid_x = kMargin + kRowLabelW, grid_y = top + kHeadingH + kColHeadH;
  for (std::size_t j = 0; j < angles.size(); ++j) {
    pt.text(grid_x + static_cast<double>(j) * kCellW + kCellW / 2.0, grid_y - 7,
            degrees(angles[j], "%.0f"), 14, true, kInk, Align::centre);
  }
  for (std::size_t i = 0; i < methods.size(); ++i) {
    const double cy = grid_y + static_cast<double>(i) * kCellH + kPlotH / 2.0;
    pt.text(kMargin, cy, std::string(math::warp_method_name(methods[i])), 16, true,
            colour(methods[i]));
    pt.text(kMargin, cy + 17, method_note(methods[i]), 11, false, kMuted);
  }
  for (const auto& c : panel.curves) {
    const auto i = std::find(methods.begin(), methods.end(), c.method) - methods.begin();
    const auto j = std::find(angles.begin(), angles.end(), c.angle_deg) - angles.begin();
    draw_cell(pt, panel_scale, panel, c, grid_x + static_cast<double>(j) * kCellW,
              grid_y + static_cast<double>(i) * kCellH);
  }
}

// The one drawing routine behind both files.
void draw(cairo_t* cr, const Figure8Picture& pic, std::vector<std::string>& texts) {
  const Grid grid(pic);
  cairo_set_source_rgb(cr, 1.0, 1.0, 1.0);
  cairo_paint(cr);
  cairo_set_antialias(cr, CAIRO_ANTIALIAS_GOOD);
  Painter pt(cr, texts);
  pt.text(kMargin, kMargin + 22, pic.title, 22, true, kInk);
  pt.text(kMargin, kMargin + 48, pic.subtitle, 14, false, kInk);
  draw_legend(pt, kMargin + 78);
  double top = kMargin + kTitleH;
  for (const auto& panel : pic.panels) {
    draw_panel(pt, panel, top);
    top += kHeadingH + kColHeadH + static_cast<double>(grid.rows) * kCellH + kPanelGap;
  }
}

using SurfacePtr = std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)>;
using ContextPtr = std::unique_ptr<cairo_t, decltype(&cairo_destroy)>;

hal::Error cairo_error(cairo_status_t st) {
  return hal::make_error(StatusCode::failed_precondition,
                         std::string("cairo: ") + cairo_status_to_string(st));
}

// Draws onto `surface`; an Error when cairo reports one.
hal::Expected<void> render(cairo_surface_t* surface, const Figure8Picture& pic,
                           std::vector<std::string>& texts) {
  const ContextPtr cr(cairo_create(surface), &cairo_destroy);
  draw(cr.get(), pic, texts);
  cairo_status_t st = cairo_status(cr.get());
  cairo_surface_flush(surface);
  if (st == CAIRO_STATUS_SUCCESS) st = cairo_surface_status(surface);
  if (st != CAIRO_STATUS_SUCCESS) return cairo_error(st);
  return {};
}

std::string xml_escape(const std::string& s) {
  std::string out;
  for (const char ch : s) {
    if (ch == '&')
      out += "&amp;";
    else if (ch == '<')
      out += "&lt;";
    else if (ch == '>')
      out += "&gt;";
    else
      out += ch;
  }
  return out;
}

cairo_status_t append_to_string(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

Figure8Size size_of(const Figure8Picture& pic) {
  const Grid grid(pic);
  return figure8_picture_size(pic.panels.size(), grid.rows, grid.cols);
}

}  // namespace

Figure8Size figure8_picture_size(std::size_t panels, std::size_t rows, std::size_t cols) {
  const int p = static_cast<int>(panels), r = static_cast<int>(rows), c = static_cast<int>(cols);
  const int panel_h = kHeadingH + kColHeadH + r * kCellH;
  return {2 * kMargin + kRowLabelW + c * kCellW,
          2 * kMargin + kTitleH + p * panel_h + std::max(0, p - 1) * kPanelGap};
}

hal::Expected<void> write_figure8_svg(const std::string& path, const Figure8Picture& picture,
                                      bool force) {
  const Figure8Size size = size_of(picture);
  std::string svg;
  std::vector<std::string> texts;
  {
    const SurfacePtr surface(
        cairo_svg_surface_create_for_stream(&append_to_string, &svg, size.width, size.height),
        &cairo_surface_destroy);
    cairo_svg_surface_set_document_unit(surface.get(), CAIRO_SVG_UNIT_PX);
    if (auto drawn = render(surface.get(), picture, texts); !drawn) return drawn;
    cairo_surface_finish(surface.get());
    if (const cairo_status_t st = cairo_surface_status(surface.get()); st != CAIRO_STATUS_SUCCESS) {
      return cairo_error(st);
    }
  }
  // cairo draws text as glyph outlines; the labels go in as text too (search, screen readers).
  const std::size_t open = svg.find("<svg");
  const std::size_t end = open == std::string::npos ? open : svg.find('>', open);
  if (end == std::string::npos) {
    return hal::make_error(StatusCode::failed_precondition, "cairo wrote no <svg> element");
  }
  std::string meta = "\n<title>" + xml_escape(picture.title) + "</title>\n<desc>";
  for (const auto& t : texts) meta += xml_escape(t) + "\n";
  meta += "</desc>";
  svg.insert(end + 1, meta);
  return hal::write_output_file(path, svg, {hal::OutputKind::svg, force});
}

hal::Expected<void> write_figure8_png(const std::string& path, const Figure8Picture& picture,
                                      bool force) {
  const Figure8Size size = size_of(picture);
  const SurfacePtr surface(cairo_image_surface_create(CAIRO_FORMAT_RGB24, size.width, size.height),
                           &cairo_surface_destroy);
  std::vector<std::string> texts;
  if (auto drawn = render(surface.get(), picture, texts); !drawn) return drawn;
  std::string bytes;
  const auto append = [](void* closure, const unsigned char* data, unsigned int length) {
    static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
    return CAIRO_STATUS_SUCCESS;
  };
  if (const cairo_status_t st = cairo_surface_write_to_png_stream(surface.get(), append, &bytes);
      st != CAIRO_STATUS_SUCCESS) {
    return hal::make_error(StatusCode::io_error,
                           "cannot write '" + path + "': " + cairo_status_to_string(st));
  }
  return hal::write_output_file(path, bytes, {hal::OutputKind::png, force});
}

}  // namespace twister::cli
