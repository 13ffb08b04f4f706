// What a mesh file holds before welding, and the error a file that cannot be used raises: the
// types the file readers (mesh_import.hpp, off_file.hpp) share.
#pragma once

#include <array>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "sim/math.hpp"

namespace gf::sim {

/// A mesh file that cannot be used; what() names the file and the reason.
class MeshLoadError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Positions and triangles as read from a file, before welding (metres after `scale`).
struct RawMesh {
  std::vector<Vec3> positions;
  std::vector<std::array<std::int32_t, 3>> triangles;
};

}  // namespace gf::sim
