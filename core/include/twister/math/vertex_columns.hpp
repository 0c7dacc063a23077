// Structure-of-arrays vertex positions: three float columns of equal length, owned
// by the caller (the mesh storage). Scene units, world frame.
#pragma once

#include <cstddef>
#include <span>

namespace twister::math {

struct VertexColumns {
  std::span<float> x;
  std::span<float> y;
  std::span<float> z;

  std::size_t size() const { return x.size(); }
  // True when the three columns have the same length.
  bool consistent() const { return y.size() == x.size() && z.size() == x.size(); }
};

struct ConstVertexColumns {
  std::span<const float> x;
  std::span<const float> y;
  std::span<const float> z;

  ConstVertexColumns() = default;
  ConstVertexColumns(std::span<const float> xs, std::span<const float> ys,
                     std::span<const float> zs)
      : x(xs), y(ys), z(zs) {}
  ConstVertexColumns(const VertexColumns& c) : x(c.x), y(c.y), z(c.z) {}  // NOLINT

  std::size_t size() const { return x.size(); }
  bool consistent() const { return y.size() == x.size() && z.size() == x.size(); }
};

}  // namespace twister::math
