#include "twister/mesh/mesh.hpp"

#include <algorithm>
#include <bit>

#include "twister/base/assert.hpp"

namespace twister::mesh {
namespace {

constexpr std::uint64_t kFnvOffset = 0xcbf29ce484222325ull;
constexpr std::uint64_t kFnvPrime = 0x100000001b3ull;

std::uint64_t fnv_u32(std::uint64_t h, std::uint32_t v) {
  // Byte by byte in little-endian order so the checksum is the same on every host.
  for (int i = 0; i < 4; ++i) {
    h ^= (v >> (8 * i)) & 0xffu;
    h *= kFnvPrime;
  }
  return h;
}

}  // namespace

Mesh::Mesh(std::span<float> x, std::span<float> y, std::span<float> z,
           std::span<std::uint32_t> triangle_indices)
    : x_(x), y_(y), z_(z), indices_(triangle_indices) {
  TWISTER_ASSERT(x.size() == y.size() && y.size() == z.size());
}

Result<std::uint32_t> Mesh::add_vertex(glm::vec3 position_m) {
  if (vertex_count_ >= x_.size()) return StatusCode::resource_exhausted;
  const auto i = static_cast<std::uint32_t>(vertex_count_++);
  set_position(i, position_m);
  return i;
}

Result<std::uint32_t> Mesh::add_triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  if (a >= vertex_count_ || b >= vertex_count_ || c >= vertex_count_) {
    return StatusCode::invalid_argument;
  }
  if (triangle_count_ >= triangle_capacity()) return StatusCode::resource_exhausted;
  const std::size_t base = 3 * triangle_count_;
  indices_[base] = a;
  indices_[base + 1] = b;
  indices_[base + 2] = c;
  ++topology_version_;
  return static_cast<std::uint32_t>(triangle_count_++);
}

void Mesh::clear() {
  vertex_count_ = 0;
  triangle_count_ = 0;
  ++topology_version_;
}

glm::vec3 Mesh::position(std::uint32_t i) const {
  TWISTER_ASSERT(i < vertex_count_);
  return {x_[i], y_[i], z_[i]};
}

void Mesh::set_position(std::uint32_t i, glm::vec3 position_m) {
  TWISTER_ASSERT(i < vertex_count_);
  x_[i] = position_m.x;
  y_[i] = position_m.y;
  z_[i] = position_m.z;
}

std::array<std::uint32_t, 3> Mesh::triangle(std::uint32_t t) const {
  TWISTER_ASSERT(t < triangle_count_);
  const std::size_t base = 3 * std::size_t{t};
  return {indices_[base], indices_[base + 1], indices_[base + 2]};
}

void Mesh::set_triangle(std::uint32_t t, const std::array<std::uint32_t, 3>& v) {
  TWISTER_ASSERT(t < triangle_count_);
  TWISTER_ASSERT(v[0] < vertex_count_ && v[1] < vertex_count_ && v[2] < vertex_count_);
  const std::size_t base = 3 * std::size_t{t};
  indices_[base] = v[0];
  indices_[base + 1] = v[1];
  indices_[base + 2] = v[2];
  ++topology_version_;
}

Status Mesh::resize(std::size_t vertices, std::size_t triangles) {
  if (vertices > vertex_capacity() || triangles > triangle_capacity()) {
    return StatusCode::resource_exhausted;
  }
  if (vertices == vertex_count_ && triangles == triangle_count_) return ok_status();
  vertex_count_ = vertices;
  triangle_count_ = triangles;
  ++topology_version_;
  return ok_status();
}

Status Mesh::copy_from(const Mesh& other) {
  if (other.vertex_count_ > vertex_capacity() || other.triangle_count_ > triangle_capacity()) {
    return StatusCode::resource_exhausted;
  }
  std::copy_n(other.x_.begin(), other.vertex_count_, x_.begin());
  std::copy_n(other.y_.begin(), other.vertex_count_, y_.begin());
  std::copy_n(other.z_.begin(), other.vertex_count_, z_.begin());
  std::copy_n(other.indices_.begin(), 3 * other.triangle_count_, indices_.begin());
  vertex_count_ = other.vertex_count_;
  triangle_count_ = other.triangle_count_;
  ++topology_version_;
  return ok_status();
}

std::uint64_t Mesh::checksum() const {
  std::uint64_t h = kFnvOffset;
  h = fnv_u32(h, static_cast<std::uint32_t>(vertex_count_));
  h = fnv_u32(h, static_cast<std::uint32_t>(triangle_count_));
  for (std::size_t i = 0; i < vertex_count_; ++i) {
    h = fnv_u32(h, std::bit_cast<std::uint32_t>(x_[i]));
    h = fnv_u32(h, std::bit_cast<std::uint32_t>(y_[i]));
    h = fnv_u32(h, std::bit_cast<std::uint32_t>(z_[i]));
  }
  for (std::size_t i = 0; i < 3 * triangle_count_; ++i) h = fnv_u32(h, indices_[i]);
  return h;
}

}  // namespace twister::mesh
