// The thumbnail raster: the model upright (+Z) and centred (export_frame), an
// orthographic three-quarter view from the front (-Y), 30 degrees to the right and
// 20 degrees above, framed to the projected vertices with a margin; rendered at up
// to 3x3 samples per pixel (z-buffer, per-sample Phong shading of interpolated
// vertex normals), then averaged and put in sRGB.
#include "twister/meshio/thumbnail.hpp"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

#include "export_file.hpp"
#include "export_frame.hpp"
#include "twister/mesh/vertex_normals.hpp"

namespace twister::meshio {
namespace {

constexpr double kDegree = M_PI / 180.0;
constexpr double kMargin = 0.08;  // of the image on each side

// The camera: right, up, toward-the-viewer axes (orthonormal, world +Z up).
struct View {
  glm::dvec3 right, up, toward;
  double scale = 1.0;      // samples per metre
  glm::dvec2 centre{0.0};  // projected centre of the model
  int samples = 1;         // image size in samples
};

View make_view(double azimuth_deg, double elevation_deg) {
  View v;
  const double a = azimuth_deg * kDegree;
  const double e = elevation_deg * kDegree;
  v.toward = glm::dvec3(std::cos(e) * std::sin(a), -std::cos(e) * std::cos(a), std::sin(e));
  v.right = glm::normalize(glm::cross(-v.toward, glm::dvec3(0, 0, 1)));
  v.up = glm::cross(v.right, -v.toward);
  return v;
}

// Linear light -> 8-bit sRGB.
std::uint8_t to_srgb(double c) {
  c = std::clamp(c, 0.0, 1.0);
  const double s = c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
  return static_cast<std::uint8_t>(std::lround(255.0 * s));
}

double from_srgb(double s) { return s <= 0.04045 ? s / 12.92 : std::pow((s + 0.055) / 1.055, 2.4); }

// The clay under a key light (upper left, in front), a cool fill (right), a rim from
// behind and a sky/ground ambient.
glm::dvec3 shade(glm::dvec3 n, const View& v) {
  if (glm::dot(n, v.toward) < 0.0) n = -n;  // the inside of an open mesh
  const glm::dvec3 clay(from_srgb(0.80), from_srgb(0.56), from_srgb(0.44));
  const glm::dvec3 key = glm::normalize(-0.8 * v.right + 0.7 * v.up + 0.45 * v.toward);
  const glm::dvec3 fill = glm::normalize(0.9 * v.right + 0.1 * v.up + 0.45 * v.toward);
  const glm::dvec3 rim = glm::normalize(-0.8 * v.toward + 0.5 * v.up + 0.4 * v.right);
  // A little wrap on the key keeps the terminator soft.
  const double k = std::max(0.0, (glm::dot(n, key) + 0.15) / 1.15);
  const double f = std::max(0.0, glm::dot(n, fill));
  const double edge = 1.0 - std::max(0.0, glm::dot(n, v.toward));
  const double r = std::max(0.0, glm::dot(n, rim)) * edge * edge;
  const double sky = 0.5 + 0.5 * n.z;
  const glm::dvec3 ambient =
      glm::mix(glm::dvec3(0.03, 0.025, 0.02), glm::dvec3(0.08, 0.085, 0.10), sky);
  const glm::dvec3 half = glm::normalize(key + v.toward);
  const double spec = 0.12 * std::pow(std::max(0.0, glm::dot(n, half)), 32.0);
  const double occlusion = 0.7 + 0.3 * sky;  // darker toward the ground
  return clay * occlusion *
             (ambient + 1.1 * k * glm::dvec3(1.0, 0.95, 0.86) +
              0.10 * f * glm::dvec3(0.75, 0.85, 1.0)) +
         glm::dvec3(0.35 * r + spec);
}

// The background (a quiet vertical gradient) with a soft contact shadow under the
// model: an ellipse (the ground circle under the model, seen from the view's
// elevation) darkening toward its centre.
struct Backdrop {
  glm::dvec3 top{from_srgb(0.94), from_srgb(0.94), from_srgb(0.96)};
  glm::dvec3 bottom{from_srgb(0.80), from_srgb(0.81), from_srgb(0.84)};
  glm::dvec2 shadow{0.0};
  glm::dvec2 radii{1.0};

  glm::dvec3 at(double x, double y, int samples) const {
    const glm::dvec3 c = glm::mix(top, bottom, y / samples);
    const double dx = (x - shadow.x) / radii.x;
    const double dy = (y - shadow.y) / radii.y;
    return c * (1.0 - 0.5 * std::exp(-2.0 * (dx * dx + dy * dy)));
  }
};

// Depth and the interpolated normal of the nearest surface per sample (shaded once
// each, after every triangle is drawn).
struct Raster {
  std::vector<double> depth;
  std::vector<glm::dvec3> normal;
  std::vector<bool> covered;
};

// Screen position (samples, y down) and depth (toward the viewer) of a point.
glm::dvec3 project(const View& v, glm::dvec3 p) {
  const double half = 0.5 * v.samples;
  return {half + v.scale * (glm::dot(p, v.right) - v.centre.x),
          half - v.scale * (glm::dot(p, v.up) - v.centre.y), glm::dot(p, v.toward)};
}

void draw_triangle(Raster& r, const View& v, const glm::dvec3 s[3], const glm::dvec3 n[3]) {
  const double area = (s[1].x - s[0].x) * (s[2].y - s[0].y) - (s[2].x - s[0].x) * (s[1].y - s[0].y);
  if (std::abs(area) < 1e-12) return;
  const int x0 = std::max(0, static_cast<int>(std::floor(std::min({s[0].x, s[1].x, s[2].x}))));
  const int x1 =
      std::min(v.samples - 1, static_cast<int>(std::ceil(std::max({s[0].x, s[1].x, s[2].x}))));
  const int y0 = std::max(0, static_cast<int>(std::floor(std::min({s[0].y, s[1].y, s[2].y}))));
  const int y1 =
      std::min(v.samples - 1, static_cast<int>(std::ceil(std::max({s[0].y, s[1].y, s[2].y}))));
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      const double px = x + 0.5;
      const double py = y + 0.5;
      const double w0 = ((s[1].x - px) * (s[2].y - py) - (s[2].x - px) * (s[1].y - py)) / area;
      const double w1 = ((s[2].x - px) * (s[0].y - py) - (s[0].x - px) * (s[2].y - py)) / area;
      const double w2 = 1.0 - w0 - w1;
      if (w0 < 0.0 || w1 < 0.0 || w2 < 0.0) continue;
      const double z = w0 * s[0].z + w1 * s[1].z + w2 * s[2].z;
      const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(v.samples) +
                            static_cast<std::size_t>(x);
      if (r.covered[i] && z <= r.depth[i]) continue;
      r.depth[i] = z;
      r.covered[i] = true;
      r.normal[i] = w0 * n[0] + w1 * n[1] + w2 * n[2];
    }
  }
}

// Frames the model: the projected vertices' box fills the image less the margins.
void frame_view(View& v, const mesh::Mesh& mesh, const internal::UprightFrame& f) {
  glm::dvec2 lo(1e300), hi(-1e300);
  for (std::uint32_t i = 0; i < mesh.vertex_count(); ++i) {
    const glm::dvec3 p = f.apply(glm::dvec3(mesh.position(i)));
    const glm::dvec2 q(glm::dot(p, v.right), glm::dot(p, v.up));
    lo = glm::min(lo, q);
    hi = glm::max(hi, q);
  }
  const double extent = std::max({hi.x - lo.x, hi.y - lo.y, 1e-9});
  v.scale = (1.0 - 2.0 * kMargin) * v.samples / extent;
  v.centre = 0.5 * (lo + hi);
}

// Shades each covered sample, averages ss x ss samples per pixel, sRGB.
ThumbnailImage resolve(const Raster& r, const View& v, const Backdrop& backdrop, int size, int ss) {
  const auto n = static_cast<std::size_t>(size);
  ThumbnailImage image{size, size, std::vector<std::uint8_t>(4 * n * n), 0};
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      glm::dvec3 sum(0.0);
      int hits = 0;
      for (int sy = 0; sy < ss; ++sy) {
        for (int sx = 0; sx < ss; ++sx) {
          const int px = x * ss + sx;
          const int py = y * ss + sy;
          const std::size_t i = static_cast<std::size_t>(py) * static_cast<std::size_t>(v.samples) +
                                static_cast<std::size_t>(px);
          if (r.covered[i]) {
            ++hits;
            const double len = glm::length(r.normal[i]);
            sum += shade(len > 1e-12 ? r.normal[i] / len : v.toward, v);
          } else {
            sum += backdrop.at(px + 0.5, py + 0.5, v.samples);
          }
        }
      }
      sum /= static_cast<double>(ss * ss);
      if (2 * hits >= ss * ss) ++image.covered_pixels;
      const std::size_t o = 4 * (static_cast<std::size_t>(y) * n + static_cast<std::size_t>(x));
      image.rgba[o] = to_srgb(sum.x);
      image.rgba[o + 1] = to_srgb(sum.y);
      image.rgba[o + 2] = to_srgb(sum.z);
      image.rgba[o + 3] = 255;
    }
  }
  return image;
}

}  // namespace

hal::Expected<ThumbnailImage> render_thumbnail(const mesh::Mesh& mesh, glm::vec3 up, int size) {
  if (size < 16 || size > 4096) {
    return hal::make_error(StatusCode::invalid_argument,
                           "thumbnail size must be 16..4096 pixels, got " + std::to_string(size));
  }
  if (mesh.triangle_count() == 0) {
    return hal::make_error(StatusCode::invalid_argument, "the mesh has no triangles");
  }
  auto frame = internal::upright_frame(mesh, up, glm::dvec3(0, 0, 1));
  if (!frame) return frame.error();
  const int ss = std::clamp(2048 / size, 1, 3);
  View v = make_view(30.0, 20.0);
  v.samples = size * ss;
  frame_view(v, mesh, *frame);
  std::vector<float> nx(mesh.vertex_count()), ny(mesh.vertex_count()), nz(mesh.vertex_count());
  (void)mesh::compute_vertex_normals(mesh, {nx, ny, nz});
  const auto n_samples = static_cast<std::size_t>(v.samples) * static_cast<std::size_t>(v.samples);
  Raster r{std::vector<double>(n_samples, 0.0), std::vector<glm::dvec3>(n_samples),
           std::vector<bool>(n_samples, false)};
  for (std::uint32_t t = 0; t < mesh.triangle_count(); ++t) {
    const auto tri = mesh.triangle(t);
    glm::dvec3 s[3], n[3];
    for (std::size_t k = 0; k < 3; ++k) {
      s[k] = project(v, frame->apply(glm::dvec3(mesh.position(tri[k]))));
      n[k] = frame->rotation * glm::dvec3(nx[tri[k]], ny[tri[k]], nz[tri[k]]);
    }
    draw_triangle(r, v, s, n);
  }
  // The contact shadow: the ground circle under the model, projected.
  Backdrop backdrop;
  backdrop.shadow = glm::dvec2(project(v, glm::dvec3(0.0, 0.0, frame->lo.z)));
  const double radius =
      0.75 * std::max(frame->hi.x - frame->lo.x, frame->hi.y - frame->lo.y) * v.scale;
  backdrop.radii =
      glm::dvec2(std::max(radius, 1.0), std::max(radius * std::sin(20.0 * kDegree), 1.0));
  return resolve(r, v, backdrop, size, ss);
}

hal::Expected<void> render_thumbnail_png(const mesh::Mesh& mesh, glm::vec3 up, int size,
                                         const std::string& path, bool force) {
  auto image = render_thumbnail(mesh, up, size);
  if (!image) return hal::Error{image.error().status, path + ": " + image.error().message};
  std::string bytes;
  if (!encode_png(bytes, image->width, image->height, image->rgba)) {
    return hal::make_error(StatusCode::io_error, "cannot encode " + path + " (libpng)");
  }
  return internal::write_export_file(path, bytes, hal::OutputKind::png, force);
}

}  // namespace twister::meshio
