// OBJ writer: "v" lines (%.9g: every float survives the round trip), then 1-based
// "f" lines, formatted through a fixed buffer into a hal::PosixFileSink.
#include <cstdio>
#include <string>

#include "twister/hal/posix_file_sink.hpp"
#include "twister/meshio/obj_file.hpp"

namespace twister::meshio {
namespace {

// Formats the mesh's lines in order, calling flush(text) whenever the buffer fills.
template <typename Flush>
bool write_lines(const mesh::Mesh& mesh, Flush&& flush) {
  std::string buffer;
  buffer.reserve(1 << 16);
  char line[128];
  auto put = [&](int n) {
    buffer.append(line, static_cast<std::size_t>(n));
    if (buffer.size() + sizeof line < buffer.capacity()) return true;
    const bool ok = flush(buffer);
    buffer.clear();
    return ok;
  };
  for (std::uint32_t i = 0; i < mesh.vertex_count(); ++i) {
    const glm::vec3 p = mesh.position(i);
    if (!put(std::snprintf(line, sizeof line, "v %.9g %.9g %.9g\n", double(p.x), double(p.y),
                           double(p.z)))) {
      return false;
    }
  }
  const auto idx = mesh.triangle_indices();
  for (std::size_t t = 0; t + 2 < idx.size(); t += 3) {
    if (!put(std::snprintf(line, sizeof line, "f %u %u %u\n", idx[t] + 1, idx[t + 1] + 1,
                           idx[t + 2] + 1))) {
      return false;
    }
  }
  return buffer.empty() || flush(buffer);
}

}  // namespace

std::string obj_text(const mesh::Mesh& mesh) {
  std::string out;
  out.reserve(40 * mesh.vertex_count() + 30 * mesh.triangle_count());
  write_lines(mesh, [&out](const std::string& text) {
    out += text;
    return true;
  });
  return out;
}

hal::Expected<void> save_obj(const std::filesystem::path& path, const mesh::Mesh& mesh,
                             bool force) {
  hal::PosixFileSinkConfig config;
  config.path = path.string();
  config.replace = hal::PosixFileSinkConfig::Replace::output;
  config.output = {hal::OutputKind::obj, force};
  hal::PosixFileSink sink(config);
  Status s = sink.begin();
  if (s.ok()) {
    const bool written = write_lines(mesh, [&sink](const std::string& text) {
      return sink.write(std::as_bytes(std::span(text.data(), text.size()))).ok();
    });
    s = written ? sink.commit() : Status(StatusCode::io_error);
  }
  if (s.ok()) return {};
  sink.abort();
  return hal::Error{s, "cannot write " + path.string() + ": " + sink.last_error()};
}

}  // namespace twister::meshio
