// Checks the tetrahedral-mesh tests share: a surface closed and wound outward.
#pragma once

#include <gtest/gtest.h>

#include <map>
#include <utility>

#include "sim/mesh/tet_pad.hpp"

namespace gf::sim {

/// Expects `mesh`'s surface closed and wound outward: every edge met once each way, and the volume
/// it encloses (divergence theorem) the tetrahedra's, to 1e-9 relative.
inline void expectClosedAndOutward(const TetMesh& mesh) {
  ASSERT_FALSE(mesh.surface.empty());
  std::map<std::pair<int, int>, int> directed;
  double enclosed = 0.0;
  const auto p = [&](int i) { return mesh.nodes[static_cast<std::size_t>(i)]; };
  for (const auto& [a, b, c] : mesh.surface) {
    ++directed[{a, b}];
    ++directed[{b, c}];
    ++directed[{c, a}];
    enclosed += p(a).dot(p(b).cross(p(c))) / 6.0;
  }
  int twice = 0, open = 0;
  for (const auto& [edge, count] : directed) {
    twice += count != 1;
    open += directed.count({edge.second, edge.first}) != 1;
  }
  EXPECT_EQ(twice, 0) << "edges met twice the same way";
  EXPECT_EQ(open, 0) << "open edges";
  const double volume = tetQuality(mesh).volume;
  EXPECT_GT(enclosed, 0.0);
  EXPECT_NEAR(enclosed, volume, 1e-9 * volume);
}

}  // namespace gf::sim
