// The vertex every render surface is made of: plain data, no GL (the draw list and the geometry
// builders fill arrays of them; render/gl/gpu.hpp uploads them).
#pragma once

#include <Eigen/Core>

namespace gf::render {

/// Interleaved vertex: position (m) and unit normal.
struct Vertex {
  float position[3];
  float normal[3];
};

/// A vertex from double-precision position and normal.
inline Vertex makeVertex(const Eigen::Vector3d& p, const Eigen::Vector3d& n) {
  return {{static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())},
          {static_cast<float>(n.x()), static_cast<float>(n.y()), static_cast<float>(n.z())}};
}

}  // namespace gf::render
