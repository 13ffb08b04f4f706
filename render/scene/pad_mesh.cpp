#include "render/scene/pad_mesh.hpp"

#include <algorithm>
#include <array>

namespace gf::render {
namespace {

using sim::Vec3;

}  // namespace

void PadMeshBuilder::build(const sim::PadSnapshot& pad, std::vector<Vertex>& out) {
  if (pad.nodes.empty() || !pad.skin) return;
  build(pad.nodes, *pad.skin, out);
}

void PadMeshBuilder::build(const std::vector<Vec3>& nodes, const std::vector<std::array<int, 3>>& triangles, std::vector<Vertex>& out) {
  const auto node = [&](int n) -> const Vec3& { return nodes[static_cast<std::size_t>(n)]; };
  // Each triangle's cross product is twice its area along its normal: summed per node, the
  // larger triangles weigh more.
  normals_.assign(nodes.size(), Vec3::Zero());
  for (const std::array<int, 3>& t : triangles) {
    const Vec3 area = (node(t[1]) - node(t[0])).cross(node(t[2]) - node(t[0]));
    for (const int n : t) normals_[static_cast<std::size_t>(n)] += area;
  }
  for (Vec3& n : normals_) {
    const double length = n.norm();
    n = length > 0.0 ? Vec3(n / length) : Vec3::UnitY();
  }
  for (const std::array<int, 3>& t : triangles) {
    for (const int n : t) out.push_back(makeVertex(node(n), normals_[static_cast<std::size_t>(n)]));
  }
}

double padReach(const sim::PadSnapshot& pad, const Vec3& centre) {
  double reach = 0.0;
  for (const Vec3& p : pad.nodes) reach = std::max(reach, (p - centre).norm());
  return reach;
}

}  // namespace gf::render
