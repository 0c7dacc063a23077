#include "attract_showcase.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <iterator>
#include <system_error>
#include <utility>

namespace twister::bridge {
namespace {

namespace fs = std::filesystem;
using ports::LogLevel;

// record.json's "strokes" (the station writes it; docs/exhibit.md), or -1.
long record_strokes(const std::string& path) {
  std::ifstream in(path);
  if (!in) return -1;
  std::string text;
  text.resize(4096);
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  text.resize(static_cast<std::size_t>(in.gcount()));
  const std::string key = "\"strokes\":";
  const std::size_t at = text.find(key);
  if (at == std::string::npos) return -1;
  const char* p = text.c_str() + at + key.size();
  char* end = nullptr;
  const long v = std::strtol(p, &end, 10);
  return end == p || v < 0 ? -1 : v;
}

}  // namespace

bool archive_name(const std::string& n) {
  if (n.size() != 31 || n[8] != 'T' || n[15] != 'Z' || n.compare(16, 2, "-v") != 0 ||
      n[22] != '-') {
    return false;
  }
  const auto digits = [&](std::size_t from, std::size_t count) {
    for (std::size_t i = from; i < from + count; ++i)
      if (std::isdigit(static_cast<unsigned char>(n[i])) == 0) return false;
    return true;
  };
  for (std::size_t i = 23; i < 31; ++i)
    if (std::isxdigit(static_cast<unsigned char>(n[i])) == 0) return false;
  return digits(0, 8) && digits(9, 6) && digits(18, 4);
}

std::string showcase_caption(const std::string& name, long strokes) {
  std::string out = "Sculpture " + std::to_string(std::atoi(name.substr(18, 4).c_str()));
  if (strokes >= 0) {
    out += " \u00b7 " + std::to_string(strokes) + (strokes == 1 ? " stroke" : " strokes");
  }
  return out;
}

AttractShowcase::AttractShowcase(ShowcaseOptions options, ports::LogSink& log)
    : options_(std::move(options)), log_(log) {
  options_.models = std::max<std::size_t>(options_.models, 1);
  options_.seconds_each = std::max(options_.seconds_each, 0.5);
}

void AttractShowcase::begin(double now_s) {
  epoch_s_ = now_s;
  if (next_scan_s_ < 0.0 || now_s >= next_scan_s_) rescan(now_s);
}

const ShowcaseModel* AttractShowcase::at(double now_s) {
  if (next_scan_s_ < 0.0 || now_s >= next_scan_s_) rescan(now_s);
  if (models_.empty()) return nullptr;
  const double shown = std::max(0.0, now_s - epoch_s_) / options_.seconds_each;
  const auto k = static_cast<std::size_t>(std::floor(shown)) % models_.size();
  return &models_[k];
}

bool AttractShowcase::load(const std::string& name, ShowcaseModel& out) {
  const std::string dir = options_.dir + "/" + name;
  auto read = meshio::read_glb(dir + "/model.glb", options_.limits);
  if (!read) {
    ++counters_.skipped;
    bad_.insert(name);
    log_.write(LogLevel::warning, "attract", "skipping archive %s: %s",
               {name.c_str(), read.error().message.c_str()});
    return false;
  }
  const mesh::Mesh& m = (*read)->mesh();
  out.name = name;
  out.caption = showcase_caption(name, record_strokes(dir + "/record.json"));
  out.mesh.x.assign(m.x().begin(), m.x().end());
  out.mesh.y.assign(m.y().begin(), m.y().end());
  out.mesh.z.assign(m.z().begin(), m.z().end());
  out.mesh.indices.assign(m.triangle_indices().begin(), m.triangle_indices().end());
  out.serial = ++serials_;
  ++counters_.loaded;
  return true;
}

void AttractShowcase::rescan(double now_s) {
  next_scan_s_ = now_s + options_.rescan_s;
  ++counters_.scans;
  std::vector<std::string> names;
  std::error_code ec;
  std::string why;
  fs::directory_iterator it(options_.dir, ec);
  if (ec) {
    why = "cannot list " + options_.dir + ": " + ec.message();
  } else {
    for (; it != fs::directory_iterator(); it.increment(ec)) {
      if (ec) break;
      const std::string name = it->path().filename().string();
      if (archive_name(name) && bad_.count(name) == 0 && it->is_directory(ec))
        names.push_back(name);
    }
  }
  // The newest first (the names begin with the UTC time); a cheap listing, and only
  // names not held yet are read, until `models` are held.
  std::sort(names.begin(), names.end(), std::greater<>());
  std::vector<ShowcaseModel> next;
  for (const std::string& name : names) {
    if (next.size() == options_.models) break;
    auto held = std::find_if(models_.begin(), models_.end(),
                             [&](const ShowcaseModel& m) { return m.name == name; });
    if (held != models_.end()) {
      next.push_back(std::move(*held));
      continue;
    }
    ShowcaseModel m;
    if (load(name, m)) next.push_back(std::move(m));
  }
  models_ = std::move(next);
  if (models_.empty()) {
    if (!told_empty_) {
      if (why.empty()) why = "no readable sculpture in " + options_.dir;
      log_.write(LogLevel::notice, "attract", "%s; attract mode shows the station's model",
                 {why.c_str()});
      told_empty_ = true;
    }
    return;
  }
  if (told_empty_ || counters_.scans == 1) {
    log_.write(LogLevel::notice, "attract", "showing %zu recent sculptures from %s",
               {models_.size(), options_.dir.c_str()});
  }
  told_empty_ = false;
}

MeshData place_upright(const MeshData& m, glm::vec3 up, glm::vec3 centre, float radius) {
  glm::vec3 lo(1e30F);
  glm::vec3 hi(-1e30F);
  for (std::size_t i = 0; i < m.vertex_count(); ++i) {
    const glm::vec3 p(m.x[i], m.y[i], m.z[i]);
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  const glm::vec3 c = 0.5F * (lo + hi);
  const float own = std::max(0.5F * glm::length(hi - lo), 1e-9F);
  const float scale = radius / own;
  // +Y goes to `up`; a right-handed basis about it (a proper rotation: the winding and
  // so the facing of the triangles is kept).
  const glm::vec3 u = glm::normalize(up);
  const glm::vec3 a = std::abs(u.x) < 0.9F ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
  const glm::vec3 x = glm::normalize(a - glm::dot(a, u) * u);
  const glm::vec3 z = glm::cross(x, u);
  MeshData out;
  out.indices = m.indices;
  out.x.resize(m.vertex_count());
  out.y.resize(m.vertex_count());
  out.z.resize(m.vertex_count());
  for (std::size_t i = 0; i < m.vertex_count(); ++i) {
    const glm::vec3 p = glm::vec3(m.x[i], m.y[i], m.z[i]) - c;
    const glm::vec3 q = centre + scale * (p.x * x + p.y * u + p.z * z);
    out.x[i] = q.x;
    out.y[i] = q.y;
    out.z[i] = q.z;
  }
  return out;
}

}  // namespace twister::bridge
