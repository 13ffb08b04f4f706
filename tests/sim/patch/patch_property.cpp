#include "patch_property.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <sstream>
#include <vector>

#include "sim/patch/god_finger.hpp"
#include "sim/mesh/primitives.hpp"
#include "sim/patch/warm_walk.hpp"

namespace gf::sim::testing {
namespace {

using Triangles = std::vector<std::array<std::int32_t, 3>>;

// Builds without welding or dropping anything: the patch must cope with what a raw file holds.
const MeshBuildSettings kRaw{0.0, 0.0};

struct Generator {
  std::mt19937_64 rng;
  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); }
  int integer(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); }
  bool chance(double p) { return uniform(0.0, 1.0) < p; }
  // Log-uniform in [lo, hi].
  double logUniform(double lo, double hi) { return std::exp(uniform(std::log(lo), std::log(hi))); }
  Vec3 unit() {
    std::normal_distribution<double> g;
    const Vec3 v(g(rng), g(rng), g(rng));
    return v.norm() > 1e-9 ? Vec3(v.normalized()) : Vec3::UnitY();
  }
};

// Flips the winding of each triangle with probability p (1: inside-out; 0.5: mixed).
Triangles flipped(Triangles tris, Generator& g, double p) {
  for (auto& t : tris) {
    if (g.chance(p)) std::swap(t[1], t[2]);
  }
  return tris;
}

// Triangle soup: slivers, non-manifold edges, inconsistent winding, boundaries.
Mesh soupMesh(Generator& g, double scale) {
  std::vector<Vec3> pos;
  Triangles tris;
  const int n = g.integer(4, 60);
  for (int i = 0; i < n; ++i) pos.emplace_back(scale * g.unit() * g.uniform(0.2, 1.0));
  for (int i = 0, m = g.integer(1, 3 * n); i < m; ++i) tris.push_back({g.integer(0, n - 1), g.integer(0, n - 1), g.integer(0, n - 1)});
  return buildMesh(pos, tris, g.chance(0.5) ? kRaw : MeshBuildSettings{});
}

// Every vertex duplicated per triangle: no face shares an edge (all boundaries).
Mesh unweldedBox(Generator& g, double scale) {
  const Mesh box = tessellateBox(scale * Vec3(g.uniform(0.1, 1), g.uniform(0.1, 1), g.uniform(0.1, 1)), g.integer(1, 3));
  std::vector<Vec3> pos;
  Triangles tris;
  for (int f = 0; f < box.faceCount(); ++f) {
    const auto base = static_cast<std::int32_t>(pos.size());
    for (int k = 0; k < 3; ++k) pos.push_back(box.corner(f, k));
    tris.push_back({base, base + 1, base + 2});
  }
  return buildMesh(pos, tris, kRaw);
}

// A plane with zero-area and sliver triangles between its cells.
Mesh sliverPlane(Generator& g, double scale) {
  std::vector<Vec3> pos;
  Triangles tris;
  const int cells = g.integer(1, 6);
  const double h = scale / cells;
  for (int i = 0; i <= cells; ++i) {
    for (int j = 0; j <= cells; ++j) pos.emplace_back(i * h, 0.0, j * h);
  }
  const auto id = [&](int i, int j) { return static_cast<std::int32_t>(i * (cells + 1) + j); };
  for (int i = 0; i < cells; ++i) {
    for (int j = 0; j < cells; ++j) {
      // Split each cell's diagonal with a point a hair off it: a sliver on each side.
      const auto mid = static_cast<std::int32_t>(pos.size());
      pos.push_back(0.5 * (pos[id(i, j)] + pos[id(i + 1, j + 1)]) + Vec3(g.logUniform(1e-15, 1e-6) * h, 0, 0));
      tris.push_back({id(i, j), id(i, j + 1), mid});
      tris.push_back({mid, id(i, j + 1), id(i + 1, j + 1)});
      tris.push_back({id(i, j), mid, id(i + 1, j)});
      tris.push_back({mid, id(i + 1, j + 1), id(i + 1, j)});
      tris.push_back({id(i, j), id(i + 1, j + 1), mid});  // zero-area (or nearly) over the diagonal
    }
  }
  return buildMesh(pos, flipped(tris, g, g.chance(0.3) ? 0.5 : 0.0), kRaw);
}

// A height field with valleys and ridges.
Mesh heightField(Generator& g, double scale) {
  const int cells = g.integer(2, 12);
  const double h = scale / cells, bump = g.logUniform(1e-6, 2.0) * h;
  std::vector<Vec3> pos;
  Triangles tris;
  for (int i = 0; i <= cells; ++i) {
    for (int j = 0; j <= cells; ++j) pos.emplace_back(i * h, bump * g.uniform(-1, 1), j * h);
  }
  const auto id = [&](int i, int j) { return static_cast<std::int32_t>(i * (cells + 1) + j); };
  for (int i = 0; i < cells; ++i) {
    for (int j = 0; j < cells; ++j) {
      tris.push_back({id(i, j), id(i, j + 1), id(i + 1, j + 1)});
      tris.push_back({id(i, j), id(i + 1, j + 1), id(i + 1, j)});
    }
  }
  return buildMesh(pos, tris, MeshBuildSettings{});
}

// One random or adversarial mesh, and a name for failure messages.
Mesh makeMesh(Generator& g, std::string& kind) {
  const double scale = g.logUniform(1e-3, 10.0);
  switch (g.integer(0, 9)) {
    case 0:
      kind = "soup";
      return soupMesh(g, scale);
    case 1: {  // sphere with jittered vertices, maybe inside-out or mixed
      kind = "jittered sphere";
      const Mesh sphere = tessellateSphere(scale, g.integer(1, 3));
      std::vector<Vec3> pos = sphere.vertices();
      const double jitter = g.logUniform(1e-9, 0.1) * scale;
      for (Vec3& p : pos) p += jitter * g.unit();
      return buildMesh(pos, flipped(sphere.triangles(), g, g.chance(0.5) ? 1.0 : 0.5), MeshBuildSettings{});
    }
    case 2:
      kind = "unwelded box";
      return unweldedBox(g, scale);
    case 3:
      kind = "slivers";
      return sliverPlane(g, scale);
    case 4: {  // a non-manifold fan: k triangles sharing one edge
      kind = "non-manifold fan";
      std::vector<Vec3> pos{Vec3(0, 0, -scale), Vec3(0, 0, scale)};
      Triangles tris;
      for (int i = 0, k = g.integer(3, 8); i < k; ++i) {
        const double a = g.uniform(0.0, 2.0 * M_PI);
        pos.emplace_back(scale * std::cos(a), scale * std::sin(a), g.uniform(-0.5, 0.5) * scale);
        tris.push_back({0, 1, static_cast<std::int32_t>(pos.size() - 1)});
      }
      return buildMesh(pos, flipped(tris, g, 0.5), kRaw);
    }
    case 5:
      kind = "height field";
      return heightField(g, scale);
    case 6: {  // a tetrahedron, the coarsest closed mesh, maybe flattened to a sliver
      kind = "tetrahedron";
      const double flat = g.chance(0.3) ? g.logUniform(1e-12, 1e-3) : 1.0;
      const std::vector<Vec3> pos{scale * Vec3(1, flat, 0), scale * Vec3(-0.5, flat, 0.87), scale * Vec3(-0.5, flat, -0.87),
                                  scale * Vec3(0, -flat, 0)};
      const Triangles tris{{0, 1, 2}, {0, 3, 1}, {1, 3, 2}, {2, 3, 0}};
      return buildMesh(pos, flipped(tris, g, g.chance(0.5) ? 0.5 : 0.0), kRaw);
    }
    case 7:
      kind = "cylinder";
      return tessellateCylinder(scale * g.uniform(0.05, 1), scale * g.uniform(0.05, 1), g.integer(3, 96));
    case 8:
      kind = "open plane";
      return tessellatePlane(scale, g.integer(1, 8));
    default:
      kind = "capsule";
      return tessellateCapsule(scale * g.uniform(0.05, 1), scale * g.uniform(0.0, 1), g.integer(4, 32));
  }
}

// Settings anywhere in the ranges the scene validator accepts (sim/scene/settings.cpp).
PatchSettings randomSettings(Generator& g) {
  PatchSettings s;
  s.fill = g.chance(0.3) ? PatchFill::kFilled : PatchFill::kRing;
  s.rings = g.integer(1, kMaxRings);
  s.n_sgo = g.integer(kMinSgo, kMaxSgo);
  s.r_max = g.chance(0.05) ? 0.0 : g.logUniform(1e-6, 1.0);
  s.d0 = g.logUniform(1e-6, 1.0);
  s.alpha = g.chance(0.2) ? 1.0 : g.logUniform(1.0, 100.0);
  s.stretch_length = g.logUniform(1e-6, 1.0);
  s.max_stretch = g.uniform(1.0, 2.0);
  s.tau_a = g.chance(0.1) ? 0.0 : g.chance(0.1) ? M_PI / 2 : g.uniform(0.0, M_PI / 2);
  s.friction = g.chance(0.1) ? 0.0 : g.logUniform(1e-3, 100.0);
  s.tangential_stretch = g.chance(0.8);
  s.angular_threshold = g.chance(0.8);
  s.friction_cone = g.chance(0.8);
  s.max_face_crossings = g.integer(0, 128);
  return s;
}

// The contact on `mesh`: the closest point of a random query, an exact vertex or an edge's
// midpoint, with the face's normal, a random normal or one between two faces.
PatchContact randomContact(const Mesh& mesh, Generator& g) {
  const int f = g.integer(0, mesh.faceCount() - 1);
  const int k = g.integer(0, 2);
  const double d = mesh.diagonal();
  Vec3 at;
  switch (g.integer(0, 3)) {
    case 0: at = mesh.corner(f, k); break;
    case 1: at = 0.5 * (mesh.corner(f, k) + mesh.corner(f, (k + 1) % 3)); break;
    default: at = 0.5 * (mesh.boundsMin() + mesh.boundsMax()) + d * g.uniform(0.0, 1.0) * g.unit();
  }
  const SurfacePoint hit = mesh.closestPoint(at, 1e-7 * d);
  Vec3 n = mesh.faceNormal(hit.face);
  if (g.chance(0.15)) n = g.unit();
  if (g.chance(0.15)) n = (n + mesh.faceNormal(f)).norm() > 1e-6 ? Vec3((n + mesh.faceNormal(f)).normalized()) : n;
  if (g.chance(0.2)) n = -n;  // the inside-out reading of the face
  PatchContact c;
  c.point_local = hit.point;
  c.outward_normal_local = n;
  c.separation = -g.logUniform(1e-9, 1e-2);
  c.rounding = g.chance(0.3) ? g.logUniform(1e-6, 1e-2) * d : 0.0;
  if (g.chance(0.3)) c.ring_reference_local = g.unit();
  return c;
}

Vec3 randomDisplacement(const PatchContact& c, Generator& g) {
  const double press = g.chance(0.1) ? -g.logUniform(1e-9, 1.0) : g.logUniform(1e-12, 10.0);
  return -press * c.outward_normal_local + g.logUniform(1e-12, 10.0) * g.unit();
}

std::string sci(double x) {
  std::ostringstream out;
  out << x;
  return out.str();
}

double meanEdgeShortest(const Mesh& mesh) {
  double shortest = std::numeric_limits<double>::infinity();
  for (int f = 0; f < mesh.faceCount(); ++f) {
    double sum = 0.0;
    for (int k = 0; k < 3; ++k) sum += (mesh.corner(f, (k + 1) % 3) - mesh.corner(f, k)).norm();
    shortest = std::min(shortest, sum / 3.0);
  }
  return shortest;
}

// What is wrong with `p`, or empty.
std::string checkPatch(const Mesh& mesh, double shortest_mean_edge, const PatchSettings& s, const Patch& p, long& points) {
  if (!p.valid) return "rejected legal input";
  if (!std::isfinite(p.radius) || p.radius < 0.0 || p.radius > s.r_max) return "radius outside [0, r_max]";
  if (p.sgos.size() > static_cast<std::size_t>(s.n_sgo)) return "more SGOs than n_sgo";
  const double tolerance = 1e-9 * mesh.diagonal();
  double off = 0.0;  // the last point's distance from the surface (m)
  const auto onSurface = [&](const Sgo& sgo) {
    if (!sgo.position.allFinite()) return false;
    off = mesh.closestPoint(sgo.position, 0.0).query_distance;
    return off <= tolerance;
  };
  double shares = p.sgos.empty() ? 1.0 : p.centre_share;
  for (std::size_t k = 0; k < p.sgos.size(); ++k) {
    const Sgo& sgo = p.sgos[k];
    if (!onSurface(sgo)) return "SGO " + std::to_string(k) + " not finite or off the surface by " + sci(off) + " m";
    const double d = p.d_i[sgo.radial];
    if (!std::isfinite(d) || !(sgo.walked <= d * (1 + 1e-9) + 1e-300)) return "SGO " + std::to_string(k) + " walked beyond d_i";
    const long budget = s.max_face_crossings + static_cast<long>(std::min(1e6, std::ceil(8.0 * d / shortest_mean_edge))) + 2;
    if (p.path_offsets[k + 1] - p.path_offsets[k] > budget) return "SGO " + std::to_string(k) + " walk beyond its crossing budget";
    shares += sgo.load_share;
  }
  for (const Sgo& inner : p.inner) {
    if (!onSurface(inner)) return "filled point not finite or off the surface by " + sci(off) + " m";
    shares += inner.load_share;
  }
  for (const Vec3& q : p.path_points) {
    if (!q.allFinite()) return "path point not finite";
  }
  if (std::abs(shares - 1.0) > 1e-9) return "load shares sum to " + std::to_string(shares);
  points += static_cast<long>(p.sgos.size() + p.inner.size());
  return {};
}

// Warm against cold: the patch computed with its walks carried from the same contact two steps
// and a step earlier (each step moving it 1e-6 of the mesh's diagonal across the normal, turning
// the normal 1e-6 rad, the press moved with it: the first walks from the contact, the second
// checks the carried paths and leaves their slack, this one carries them within it where it
// holds) must put every point and path point within 1e-9 m of the one computed from scratch, `p`.
std::string checkWarm(const Mesh& mesh, const PatchSettings& s, const PatchContact& c, const Vec3& v, const Patch& p,
                      Patch& warm, WalkCache& cache, PropertySweep& sweep) {
  const double nlen = c.outward_normal_local.norm();
  const Vec3 n = std::isfinite(nlen) && nlen > 0.5 ? Vec3(c.outward_normal_local / nlen) : Vec3::UnitY();
  const Vec3 t = n.unitOrthogonal(), step = 1e-6 * mesh.diagonal() * t;
  cache.valid = false;
  for (const double back : {2.0, 1.0}) {
    PatchContact before = c;
    before.point_local -= back * step;
    before.outward_normal_local = c.outward_normal_local + back * 1e-6 * nlen * n.cross(t);
    computePatch(mesh, before, v + back * step, s, warm, &cache);
  }
  const long warm_before = cache.warm_walks, slack_before = cache.slack_walks;
  computePatch(mesh, c, v, s, warm, &cache);
  placePendingCrossings(cache, warm);
  sweep.warm_walks += cache.warm_walks - warm_before;
  sweep.slack_walks += cache.slack_walks - slack_before;
  if (warm.sgos.size() != p.sgos.size() || warm.inner.size() != p.inner.size() ||
      warm.path_points.size() != p.path_points.size()) {
    return "warm patch has other points";
  }
  double worst = 0.0;
  for (std::size_t k = 0; k < p.sgos.size(); ++k) worst = std::max(worst, (warm.sgos[k].position - p.sgos[k].position).norm());
  for (std::size_t k = 0; k < p.inner.size(); ++k) worst = std::max(worst, (warm.inner[k].position - p.inner[k].position).norm());
  for (std::size_t k = 0; k < p.path_points.size(); ++k) worst = std::max(worst, (warm.path_points[k] - p.path_points[k]).norm());
  sweep.warm_error = std::max(sweep.warm_error, worst);
  return worst <= 1e-9 ? std::string() : "warm walk " + sci(worst) + " m from the cold one";
}

}  // namespace

PropertySweep sweepPatchProperties(std::uint32_t seed, long patches, bool warm_vs_cold) {
  PropertySweep sweep;
  Generator g{std::mt19937_64(seed)};
  Patch p, warm;
  WalkCache cache;
  while (sweep.patches < patches) {
    std::string kind;
    const Mesh mesh = makeMesh(g, kind);
    ++sweep.meshes;
    if (mesh.faceCount() == 0) continue;
    const double shortest = meanEdgeShortest(mesh);
    const long per_mesh = std::min<long>(patches - sweep.patches, 50);
    for (long i = 0; i < per_mesh; ++i) {
      const PatchSettings s = randomSettings(g);
      const PatchContact c = randomContact(mesh, g);
      const Vec3 v = randomDisplacement(c, g);
      computePatch(mesh, c, v, s, p);
      ++sweep.patches;
      sweep.valid += p.valid;
      std::string broken = checkPatch(mesh, shortest, s, p, sweep.sgos);
      if (broken.empty() && warm_vs_cold) broken = checkWarm(mesh, s, c, v, p, warm, cache, sweep);
      if (broken.empty()) continue;
      if (++sweep.failures == 1) {
        std::ostringstream what;
        what.precision(17);
        what << broken << " (patch " << sweep.patches << ", seed " << seed << ", " << kind << " of " << mesh.faceCount()
             << " faces, diagonal " << mesh.diagonal() << "; contact " << c.point_local.transpose() << " normal "
             << c.outward_normal_local.transpose() << "; v " << v.transpose() << "; n_sgo " << s.n_sgo << " r_max "
             << s.r_max << " fill " << static_cast<int>(s.fill) << ")";
        sweep.first_failure = what.str();
      }
    }
  }
  return sweep;
}

void expectSweepHolds(std::uint32_t seed, long patches, bool warm_vs_cold) {
  const PropertySweep sweep = sweepPatchProperties(seed, patches, warm_vs_cold);
  EXPECT_EQ(sweep.patches, patches);
  EXPECT_EQ(sweep.failures, 0) << sweep.first_failure;
  // The sweep must exercise the walk, not only reject or skip: most patches carry points.
  EXPECT_GT(sweep.sgos, 10 * sweep.patches);
  std::printf("%ld patches on %ld meshes, %ld points checked, %ld failures\n", sweep.patches, sweep.meshes, sweep.sgos,
              sweep.failures);
  if (!warm_vs_cold) return;
  // Most walks carried, not redone, and many of them within their slack: the comparison is not
  // vacuous for either way of carrying.
  EXPECT_GT(sweep.warm_walks, 3 * sweep.patches);
  EXPECT_GT(sweep.slack_walks, sweep.patches);
  std::printf("warm against cold: %ld walks carried (%ld within their slack), largest difference %.3g m\n",
              sweep.warm_walks, sweep.slack_walks, sweep.warm_error);
}

}  // namespace gf::sim::testing
