// RefinerBuffer: host-side owner of a core mesh::MeshRefiner's storage (std::vector
// columns) for a mesh of the given capacities, sized once at start-up (the station,
// `twister replay`, benchmarks); the refiner never grows it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "twister/mesh/mesh_refiner.hpp"

namespace twister::meshio {

class RefinerBuffer {
 public:
  RefinerBuffer(std::size_t vertex_capacity, std::size_t triangle_capacity)
      : twins_(3 * triangle_capacity),
        offsets_(vertex_capacity + 1),
        incident_(3 * triangle_capacity),
        wx_(vertex_capacity),
        wy_(vertex_capacity),
        wz_(vertex_capacity),
        stamp_(vertex_capacity),
        edge_state_(3 * triangle_capacity),
        flags_(triangle_capacity),
        queue_(triangle_capacity),
        fx_(vertex_capacity),
        fy_(vertex_capacity),
        fz_(vertex_capacity),
        float_stamp_(vertex_capacity) {}
  RefinerBuffer(const RefinerBuffer&) = delete;
  RefinerBuffer& operator=(const RefinerBuffer&) = delete;

  mesh::MeshRefinerStorage storage() {
    return {{twins_, offsets_, incident_},
            wx_,
            wy_,
            wz_,
            stamp_,
            edge_state_,
            flags_,
            queue_,
            fx_,
            fy_,
            fz_,
            float_stamp_};
  }

 private:
  std::vector<std::uint32_t> twins_, offsets_, incident_;
  std::vector<double> wx_, wy_, wz_;
  std::vector<std::uint32_t> stamp_;
  std::vector<std::uint8_t> edge_state_, flags_;
  std::vector<std::uint32_t> queue_;
  std::vector<float> fx_, fy_, fz_;
  std::vector<std::uint32_t> float_stamp_;
};

}  // namespace twister::meshio
