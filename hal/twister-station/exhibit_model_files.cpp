// The archive's built-in model writers (ArchiveModelWriter): binary STL, a minimal
// binary glTF (positions, indices, one material) and a 256 x 256 thumbnail PNG (an
// orthographic view from the front-above, Lambert-shaded, z-buffered; stored deflate).
// Vertices are written in the model's (object) frame, metres. Swappable for hal/meshio's
// writers (the export branch) behind ArchiveModelWriter.
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "exhibit_archive.hpp"

namespace twister::station_app {
namespace {

int write_file(const std::string& path, const std::vector<std::uint8_t>& bytes) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) return errno;
  std::size_t done = 0;
  int err = 0;
  while (done < bytes.size()) {
    const ssize_t w = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) {
      err = w < 0 ? errno : ENOSPC;
      break;
    }
    done += static_cast<std::size_t>(w);
  }
  if (::close(fd) != 0 && err == 0) err = errno;
  return err;
}

void put_u32(std::vector<std::uint8_t>& b, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) b.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}
void put_f32(std::vector<std::uint8_t>& b, float f) {
  std::uint32_t v = 0;
  std::memcpy(&v, &f, 4);
  put_u32(b, v);
}
void put_u32_be(std::vector<std::uint8_t>& b, std::uint32_t v) {
  for (int i = 3; i >= 0; --i) b.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}

std::array<float, 3> vertex(const mesh::Mesh& m, std::uint32_t i) {
  return {m.x()[i], m.y()[i], m.z()[i]};
}

std::uint32_t crc32(const std::uint8_t* p, std::size_t n) {
  std::uint32_t c = 0xFFFFFFFFu;
  for (std::size_t i = 0; i < n; ++i) {
    c ^= p[i];
    for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
  }
  return ~c;
}

void png_chunk(std::vector<std::uint8_t>& out, const char* type,
               const std::vector<std::uint8_t>& data) {
  put_u32_be(out, static_cast<std::uint32_t>(data.size()));
  const std::size_t start = out.size();
  out.insert(out.end(), type, type + 4);
  out.insert(out.end(), data.begin(), data.end());
  put_u32_be(out, crc32(out.data() + start, out.size() - start));
}

class BuiltinWriter final : public ArchiveModelWriter {
 public:
  int write_stl(const std::string& path, const mesh::Mesh& m, const Pose& /*pose*/) override {
    std::vector<std::uint8_t> b(80, 0);
    const char* head = "twister-station sculpture (binary STL, metres)";
    std::memcpy(b.data(), head, std::strlen(head));
    put_u32(b, static_cast<std::uint32_t>(m.triangle_count()));
    for (std::size_t t = 0; t < m.triangle_count(); ++t) {
      const auto tri = m.triangle(static_cast<std::uint32_t>(t));
      const auto a = vertex(m, tri[0]), bb = vertex(m, tri[1]), c = vertex(m, tri[2]);
      const std::array<float, 3> u{bb[0] - a[0], bb[1] - a[1], bb[2] - a[2]};
      const std::array<float, 3> v{c[0] - a[0], c[1] - a[1], c[2] - a[2]};
      std::array<float, 3> n{u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                             u[0] * v[1] - u[1] * v[0]};
      const float len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      for (float& x : n) x = len > 0.0F ? x / len : 0.0F;
      for (float x : n) put_f32(b, x);
      for (const auto& p : {a, bb, c}) {
        for (float x : p) put_f32(b, x);
      }
      b.push_back(0);
      b.push_back(0);
    }
    return write_file(path, b);
  }

  int write_glb(const std::string& path, const mesh::Mesh& m, const Pose& /*pose*/) override {
    const auto nv = static_cast<std::uint32_t>(m.vertex_count());
    const auto nt = static_cast<std::uint32_t>(m.triangle_count());
    std::array<float, 3> lo{1e30F, 1e30F, 1e30F}, hi{-1e30F, -1e30F, -1e30F};
    std::vector<std::uint8_t> bin;
    for (std::uint32_t i = 0; i < nv; ++i) {
      const auto p = vertex(m, i);
      for (std::size_t k = 0; k < 3; ++k) {
        lo[k] = std::min(lo[k], p[k]);
        hi[k] = std::max(hi[k], p[k]);
        put_f32(bin, p[k]);
      }
    }
    const std::uint32_t index_offset = static_cast<std::uint32_t>(bin.size());
    for (std::uint32_t idx : m.triangle_indices()) put_u32(bin, idx);
    while (bin.size() % 4 != 0) bin.push_back(0);
    std::array<char, 2048> js{};
    std::snprintf(
        js.data(), js.size(),
        "{\"asset\":{\"version\":\"2.0\",\"generator\":\"twister-station\"},\"scene\":0,"
        "\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],"
        "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1,"
        "\"material\":0}]}],\"materials\":[{\"name\":\"clay\",\"pbrMetallicRoughness\":{"
        "\"baseColorFactor\":[0.8,0.62,0.48,1.0],\"metallicFactor\":0.0,\"roughnessFactor\":"
        "0.8}}],\"buffers\":[{\"byteLength\":%zu}],\"bufferViews\":[{\"buffer\":0,"
        "\"byteOffset\":0,\"byteLength\":%u,\"target\":34962},{\"buffer\":0,\"byteOffset\":%u,"
        "\"byteLength\":%u,\"target\":34963}],\"accessors\":[{\"bufferView\":0,"
        "\"componentType\":5126,\"count\":%u,\"type\":\"VEC3\",\"min\":[%.9g,%.9g,%.9g],"
        "\"max\":[%.9g,%.9g,%.9g]},{\"bufferView\":1,\"componentType\":5125,\"count\":%u,"
        "\"type\":\"SCALAR\"}]}",
        bin.size(), index_offset, index_offset, 12 * nt, nv, static_cast<double>(lo[0]),
        static_cast<double>(lo[1]), static_cast<double>(lo[2]), static_cast<double>(hi[0]),
        static_cast<double>(hi[1]), static_cast<double>(hi[2]), 3 * nt);
    std::vector<std::uint8_t> json(js.data(), js.data() + std::strlen(js.data()));
    while (json.size() % 4 != 0) json.push_back(' ');
    std::vector<std::uint8_t> out;
    put_u32(out, 0x46546C67u);  // "glTF"
    put_u32(out, 2);
    put_u32(out, static_cast<std::uint32_t>(12 + 8 + json.size() + 8 + bin.size()));
    put_u32(out, static_cast<std::uint32_t>(json.size()));
    put_u32(out, 0x4E4F534Au);  // JSON
    out.insert(out.end(), json.begin(), json.end());
    put_u32(out, static_cast<std::uint32_t>(bin.size()));
    put_u32(out, 0x004E4942u);  // BIN
    out.insert(out.end(), bin.begin(), bin.end());
    return write_file(path, out);
  }

  int write_thumbnail(const std::string& path, const mesh::Mesh& m, const Pose& pose) override;
};

// Looks at the model from the front (-y), 30 degrees above, z up; fits it in the frame.
int BuiltinWriter::write_thumbnail(const std::string& path, const mesh::Mesh& m,
                                   const Pose& /*pose*/) {
  constexpr int kN = 256;
  const double el = 30.0 * 3.14159265358979 / 180.0;
  const auto view = [&](std::array<float, 3> p) {
    // camera axes: right = x, up = z cos + y sin, depth toward the viewer
    const double sx = p[0];
    const double sy = p[2] * std::cos(el) + p[1] * std::sin(el);
    const double sz = -p[1] * std::cos(el) + p[2] * std::sin(el);
    return std::array<double, 3>{sx, sy, sz};
  };
  double lo[2] = {1e30, 1e30}, hi[2] = {-1e30, -1e30};
  for (std::uint32_t i = 0; i < m.vertex_count(); ++i) {
    const auto v = view(vertex(m, i));
    for (std::size_t k = 0; k < 2; ++k) {
      lo[k] = std::min(lo[k], v[k]);
      hi[k] = std::max(hi[k], v[k]);
    }
  }
  const double span = std::max({hi[0] - lo[0], hi[1] - lo[1], 1e-9});
  const double scale = 0.85 * kN / span;
  const double cx = 0.5 * (lo[0] + hi[0]), cy = 0.5 * (lo[1] + hi[1]);
  std::vector<double> depth(std::size_t{kN} * kN, -1e30);
  std::vector<std::uint8_t> rgb(std::size_t{kN} * kN * 3);
  for (std::size_t i = 0; i < std::size_t{kN} * kN; ++i) {  // a soft vertical gradient
    const auto g = static_cast<std::uint8_t>(236 - 40 * (i / kN) / kN);
    rgb[3 * i] = g;
    rgb[3 * i + 1] = g;
    rgb[3 * i + 2] = static_cast<std::uint8_t>(g + 8 > 255 ? 255 : g + 8);
  }
  for (std::size_t t = 0; t < m.triangle_count(); ++t) {
    const auto tri = m.triangle(static_cast<std::uint32_t>(t));
    std::array<std::array<double, 3>, 3> p{};
    for (std::size_t k = 0; k < 3; ++k) {
      const auto v = view(vertex(m, tri[k]));
      p[k] = {kN / 2.0 + (v[0] - cx) * scale, kN / 2.0 - (v[1] - cy) * scale, v[2]};
    }
    const double ux = p[1][0] - p[0][0], uy = p[1][1] - p[0][1];
    const double vx = p[2][0] - p[0][0], vy = p[2][1] - p[0][1];
    const double area = ux * vy - uy * vx;
    if (std::abs(area) < 1e-12) continue;
    // Lambert shade from the view-space normal, both sides lit.
    const auto a = view(vertex(m, tri[0])), b = view(vertex(m, tri[1])), c = view(vertex(m, tri[2]));
    const std::array<double, 3> e1{b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const std::array<double, 3> e2{c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    std::array<double, 3> n{e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                            e1[0] * e2[1] - e1[1] * e2[0]};
    const double nl = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (nl <= 0.0) continue;
    const double light = std::abs((0.35 * n[0] + 0.5 * n[1] + 0.79 * n[2]) / nl);
    const double shade = 0.25 + 0.75 * light;
    const int x0 = std::max(0, static_cast<int>(std::floor(std::min({p[0][0], p[1][0], p[2][0]}))));
    const int x1 = std::min(kN - 1, static_cast<int>(std::ceil(std::max({p[0][0], p[1][0], p[2][0]}))));
    const int y0 = std::max(0, static_cast<int>(std::floor(std::min({p[0][1], p[1][1], p[2][1]}))));
    const int y1 = std::min(kN - 1, static_cast<int>(std::ceil(std::max({p[0][1], p[1][1], p[2][1]}))));
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) {
        const double px = x + 0.5 - p[0][0], py = y + 0.5 - p[0][1];
        const double s = (px * vy - py * vx) / area, r = (ux * py - uy * px) / area;
        if (s < 0 || r < 0 || s + r > 1) continue;
        const double z = p[0][2] + s * (p[1][2] - p[0][2]) + r * (p[2][2] - p[0][2]);
        const std::size_t i = static_cast<std::size_t>(y) * kN + static_cast<std::size_t>(x);
        if (z <= depth[i]) continue;
        depth[i] = z;
        rgb[3 * i] = static_cast<std::uint8_t>(std::min(255.0, 205.0 * shade + 20));
        rgb[3 * i + 1] = static_cast<std::uint8_t>(std::min(255.0, 158.0 * shade + 15));
        rgb[3 * i + 2] = static_cast<std::uint8_t>(std::min(255.0, 122.0 * shade + 10));
      }
    }
  }
  // PNG: 8-bit RGB, filter 0 rows, zlib of stored deflate blocks.
  std::vector<std::uint8_t> raw;
  for (std::ptrdiff_t y = 0; y < kN; ++y) {
    raw.push_back(0);
    raw.insert(raw.end(), rgb.begin() + y * kN * 3, rgb.begin() + (y + 1) * kN * 3);
  }
  std::vector<std::uint8_t> z{0x78, 0x01};
  for (std::size_t at = 0; at < raw.size();) {
    const std::size_t n = std::min<std::size_t>(65535, raw.size() - at);
    z.push_back(at + n == raw.size() ? 1 : 0);
    z.push_back(static_cast<std::uint8_t>(n));
    z.push_back(static_cast<std::uint8_t>(n >> 8));
    z.push_back(static_cast<std::uint8_t>(~n));
    z.push_back(static_cast<std::uint8_t>(~n >> 8));
    z.insert(z.end(), raw.begin() + static_cast<std::ptrdiff_t>(at),
             raw.begin() + static_cast<std::ptrdiff_t>(at + n));
    at += n;
  }
  std::uint32_t s1 = 1, s2 = 0;
  for (std::uint8_t c : raw) {
    s1 = (s1 + c) % 65521;
    s2 = (s2 + s1) % 65521;
  }
  put_u32_be(z, (s2 << 16) | s1);
  std::vector<std::uint8_t> out{0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
  std::vector<std::uint8_t> ihdr;
  put_u32_be(ihdr, kN);
  put_u32_be(ihdr, kN);
  ihdr.insert(ihdr.end(), {8, 2, 0, 0, 0});
  png_chunk(out, "IHDR", ihdr);
  png_chunk(out, "IDAT", z);
  png_chunk(out, "IEND", {});
  return write_file(path, out);
}

}  // namespace

ArchiveModelWriter& builtin_model_writer() {
  static BuiltinWriter writer;
  return writer;
}

}  // namespace twister::station_app
