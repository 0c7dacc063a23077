// Strict OBJ reader, its passes and entry points (see obj_reader.hpp).
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <glm/geometric.hpp>

#include "obj_reader.hpp"

namespace twister::meshio {
namespace internal {

bool FileLines::refill() {
  if (begin_ > 0) {  // keep the unfinished line at the front
    std::memmove(buffer_.data(), buffer_.data() + begin_, end_ - begin_);
    end_ -= begin_;
    begin_ = 0;
  }
  const std::size_t n = std::fread(buffer_.data() + end_, 1, buffer_.size() - end_, file_);
  if (n == 0) {
    if (std::ferror(file_) != 0) error_ = std::string("read failed: ") + std::strerror(errno);
    eof_ = true;
  }
  end_ += n;
  return n > 0;
}

bool FileLines::next(std::string_view& line) {
  for (;;) {
    const char* start = buffer_.data() + begin_;
    const void* nl = std::memchr(start, '\n', end_ - begin_);
    if (nl != nullptr) {
      const auto len = static_cast<std::size_t>(static_cast<const char*>(nl) - start);
      line = trim_cr({start, len});
      begin_ += len + 1;
      ++line_number_;
      return true;
    }
    if (eof_ || (begin_ == 0 && end_ == buffer_.size())) break;
    if (!refill() && eof_ && !error_.empty()) return false;
  }
  if (!error_.empty()) return false;
  if (end_ - begin_ == buffer_.size()) {
    error_ = "line " + std::to_string(line_number_ + 1) + ": longer than " +
             std::to_string(kBufferBytes) + " bytes";
    return false;
  }
  if (begin_ == end_) return false;                          // the end
  line = trim_cr({buffer_.data() + begin_, end_ - begin_});  // a last line without '\n'
  begin_ = end_;
  ++line_number_;
  return true;
}

bool FileLines::rewind() {
  begin_ = end_ = 0;
  eof_ = false;
  line_number_ = 0;
  return std::fseek(file_, 0, SEEK_SET) == 0;
}

bool ObjReader::count_line(std::string_view line) {
  Words words(line);
  std::string_view keyword;
  if (!words.next(keyword)) return true;  // blank or comment
  switch (kind_of(keyword)) {
    case Kind::vertex:
      ++defined_.v;
      return check_numbers(words, keyword, nullptr);
    case Kind::texture:
      ++defined_.vt;
      return check_numbers(words, keyword, nullptr);
    case Kind::normal:
      ++defined_.vn;
      return check_numbers(words, keyword, nullptr);
    case Kind::param:
      return check_numbers(words, keyword, nullptr);
    case Kind::face: {
      std::string_view word;
      std::size_t corners = 0;
      std::uint32_t vertex = 0;
      while (words.next(word)) {
        if (!reference(word, vertex)) return false;
        if (++corners > options_.max_polygon) {
          problem_ = "a face of more than " + std::to_string(options_.max_polygon) + " vertices";
          return false;
        }
      }
      if (corners < 3) {
        problem_ = "a face needs at least 3 vertices";
        return false;
      }
      triangles_ += corners - 2;
      if (corners > 3) ++polygons_;
      return true;
    }
    case Kind::ignored:
    case Kind::none:
      return true;
    case Kind::skipped:
      ++skipped_;
      return true;
  }
  return true;
}

bool ObjReader::count_pass() {
  std::string_view line;
  while (lines_.next(line)) {
    if (!count_line(line)) return false;
    if (static_cast<std::size_t>(defined_.v) > options_.max_vertices ||
        triangles_ > options_.max_triangles) {
      problem_ = "more than " + std::to_string(options_.max_vertices) + " vertices or " +
                 std::to_string(options_.max_triangles) + " triangles";
      return false;
    }
  }
  if (!lines_.error().empty()) return false;
  total_ = defined_;
  counted_ = true;
  return true;
}

bool ObjReader::add_polygon(mesh::Mesh& mesh) {
  const std::size_t n = polygon_.size();
  glm::dvec3 normal(0.0);  // Newell's method
  for (std::size_t i = 0; i < n; ++i) {
    const glm::dvec3 a(mesh.position(polygon_[i]));
    const glm::dvec3 b(mesh.position(polygon_[(i + 1) % n]));
    normal +=
        glm::dvec3((a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y));
  }
  const double area = glm::length(normal);
  bool convex = area > 0.0 && std::isfinite(area);
  for (std::size_t i = 0; convex && i < n; ++i) {
    const glm::dvec3 a(mesh.position(polygon_[i]));
    const glm::dvec3 b(mesh.position(polygon_[(i + 1) % n]));
    const glm::dvec3 c(mesh.position(polygon_[(i + 2) % n]));
    // A reflex corner turns against the normal (beyond rounding).
    const glm::dvec3 turn = glm::cross(b - a, c - b);
    if (glm::dot(turn, normal) < -1e-9 * area * (glm::length(b - a) + glm::length(c - b))) {
      convex = false;
    }
  }
  if (!convex) {
    problem_ = "a " + std::to_string(n) +
               "-vertex face is not a convex polygon; triangulate it in the modeller";
    return false;
  }
  for (std::size_t i = 1; i + 1 < n; ++i) {
    (void)mesh.add_triangle(polygon_[0], polygon_[i], polygon_[i + 1]);
  }
  return true;
}

bool ObjReader::add_face(Words& words, mesh::Mesh& mesh) {
  polygon_.clear();
  std::string_view word;
  std::uint32_t vertex = 0;
  while (words.next(word)) {
    if (!reference(word, vertex)) return false;
    polygon_.push_back(vertex);  // capacity reserved: max_polygon
  }
  if (polygon_.size() == 3) {
    (void)mesh.add_triangle(polygon_[0], polygon_[1], polygon_[2]);
    return true;
  }
  return add_polygon(mesh);
}

bool ObjReader::fill_line(std::string_view line, mesh::Mesh& mesh, bool faces) {
  Words words(line);
  std::string_view keyword;
  if (!words.next(keyword)) return true;
  const Kind kind = kind_of(keyword);
  if (kind == Kind::vertex) {
    ++defined_.v;
    if (faces) return true;
    float xyz[3] = {0.0f, 0.0f, 0.0f};
    if (!check_numbers(words, keyword, xyz)) return false;
    (void)mesh.add_vertex({xyz[0], xyz[1], xyz[2]});
    return true;
  }
  if (kind == Kind::texture) ++defined_.vt;
  if (kind == Kind::normal) ++defined_.vn;
  return !faces || kind != Kind::face || add_face(words, mesh);
}

bool ObjReader::fill_pass(mesh::Mesh& mesh, bool faces) {
  if (!lines_.rewind()) {
    problem_ = "cannot read the file again";
    return false;
  }
  defined_ = {};
  std::string_view line;
  while (lines_.next(line)) {
    if (!fill_line(line, mesh, faces)) return false;
  }
  return lines_.error().empty();
}

hal::Expected<ObjMesh> ObjReader::read() {
  if (!count_pass()) return error();
  if (total_.v == 0)
    return hal::make_error(StatusCode::invalid_argument, "the file has no vertices");
  ObjMesh out;
  out.buffer =
      std::make_unique<MeshBuffer>(static_cast<std::size_t>(total_.v) + options_.spare_vertices,
                                   triangles_ + options_.spare_triangles);
  // Faces may name vertices defined after them: positions first, then the faces.
  polygon_.reserve(options_.max_polygon);
  if (!fill_pass(out.buffer->mesh(), false) || !fill_pass(out.buffer->mesh(), true)) {
    return error();
  }
  out.skipped_lines = skipped_;
  out.polygons = polygons_;
  return out;
}

}  // namespace internal

hal::Expected<ObjMesh> parse_obj(std::string_view text, const ObjOptions& options) {
  internal::TextLines lines(text);
  return internal::ObjReader(lines, options).read();
}

hal::Expected<ObjMesh> load_obj(const std::filesystem::path& path, const ObjOptions& options) {
  // O_NONBLOCK: a FIFO must not block the open; only a regular file is read.
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) {
    return hal::make_error(StatusCode::io_error,
                           "cannot open " + path.string() + ": " + std::strerror(errno));
  }
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd);
    return hal::make_error(StatusCode::io_error, path.string() + " is not a regular file");
  }
  std::FILE* file = ::fdopen(fd, "rb");
  if (file == nullptr) {
    ::close(fd);
    return hal::make_error(StatusCode::io_error, "cannot read " + path.string());
  }
  internal::FileLines lines(file);
  auto loaded = internal::ObjReader(lines, options).read();
  std::fclose(file);
  return loaded;
}

}  // namespace twister::meshio
