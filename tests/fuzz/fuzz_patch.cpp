// Fuzzes the god-finger patch (sim::computePatch) on a small decoded mesh: degenerate,
// duplicated, non-manifold and inconsistently wound triangles, tiny or huge (finite)
// coordinates, any contact on or near it and any settings the scene validator accepts. Every
// SGO must be finite and on the surface, and every walk within its crossing budget.
#include <fuzzer/FuzzedDataProvider.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <numbers>
#include <vector>

#include "sim/patch/god_finger.hpp"
#include "sim/mesh/mesh.hpp"

namespace {

using gf::sim::Vec3;

// A signed number of magnitude 10^[lo_exp, hi_exp] (or 0): spans the scales in a few bytes.
double logScaled(FuzzedDataProvider& in, double lo_exp, double hi_exp) {
  const double magnitude = std::pow(10.0, in.ConsumeFloatingPointInRange(lo_exp, hi_exp));
  switch (in.ConsumeIntegralInRange(0, 3)) {
    case 0: return 0.0;
    case 1: return -magnitude;
    default: return magnitude;
  }
}

// A float read from four bytes as a mesh file holds it: any finite value, or 0.
double fileFloat(FuzzedDataProvider& in) {
  const std::uint32_t bits = in.ConsumeIntegral<std::uint32_t>();
  float f = 0.0f;
  std::memcpy(&f, &bits, sizeof f);
  return std::isfinite(f) ? f : 0.0;
}

// Step 1: vertices on a coarse lattice (coincident, collinear, duplicated triangles) or as
// file floats, times a scale of 2^-30 .. 2^30 (a mesh file times `scale` in 1e-9..1e9), plus
// an offset from the origin.
gf::sim::Mesh decodeMesh(FuzzedDataProvider& in) {
  const double scale = std::ldexp(1.0, in.ConsumeIntegralInRange(-30, 30));
  const bool lattice = in.ConsumeBool();
  const Vec3 offset(logScaled(in, -3, 3), logScaled(in, -3, 3), logScaled(in, -3, 3));
  const int nv = in.ConsumeIntegralInRange(3, 40);
  std::vector<Vec3> positions;
  for (int i = 0; i < nv; ++i) {
    Vec3 p;
    for (int k = 0; k < 3; ++k) {
      p[k] = lattice ? in.ConsumeIntegralInRange(-4, 4) / 4.0 : fileFloat(in);
    }
    positions.push_back(offset + scale * p);
  }
  const int nt = in.ConsumeIntegralInRange(1, 80);
  std::vector<std::array<std::int32_t, 3>> triangles;
  for (int t = 0; t < nt; ++t) {
    triangles.push_back({in.ConsumeIntegralInRange(0, nv - 1), in.ConsumeIntegralInRange(0, nv - 1),
                         in.ConsumeIntegralInRange(0, nv - 1)});
  }
  return gf::sim::buildMesh(positions, triangles);
}

// A unit direction from three numbers, or `fallback` when they vanish.
Vec3 direction(FuzzedDataProvider& in, const Vec3& fallback) {
  const Vec3 d(in.ConsumeFloatingPointInRange(-1.0, 1.0), in.ConsumeFloatingPointInRange(-1.0, 1.0),
               in.ConsumeFloatingPointInRange(-1.0, 1.0));
  return d.norm() > 1e-6 ? Vec3(d.normalized()) : fallback;
}

// Step 2: the contact: a point on a face (inside, exactly on an edge or a corner) or anywhere
// near the mesh, a normal along the face's (either side), tilted from it or any direction.
gf::sim::PatchContact decodeContact(FuzzedDataProvider& in, const gf::sim::Mesh& mesh) {
  gf::sim::PatchContact c;
  const int f = in.ConsumeIntegralInRange(0, mesh.faceCount() - 1);
  const Vec3 a = mesh.corner(f, 0), b = mesh.corner(f, 1), d = mesh.corner(f, 2);
  const double size = mesh.diagonal();
  switch (in.ConsumeIntegralInRange(0, 3)) {
    case 0: c.point_local = a; break;
    case 1: c.point_local = a + in.ConsumeProbability<double>() * (b - a); break;
    case 2: {
      const double u = in.ConsumeProbability<double>(), v = in.ConsumeProbability<double>() * (1.0 - u);
      c.point_local = a + u * (b - a) + v * (d - a);
      break;
    }
    default:
      c.point_local = mesh.boundsMin() + Vec3(in.ConsumeFloatingPointInRange(-0.5, 1.5),
                                              in.ConsumeFloatingPointInRange(-0.5, 1.5),
                                              in.ConsumeFloatingPointInRange(-0.5, 1.5))
                                             .cwiseProduct(mesh.boundsMax() - mesh.boundsMin());
  }
  c.point_local += in.ConsumeFloatingPointInRange(-1e-3, 1e-3) * size * mesh.faceNormal(f);
  const Vec3 nf = mesh.faceNormal(f);
  switch (in.ConsumeIntegralInRange(0, 3)) {
    case 0: c.outward_normal_local = nf; break;
    case 1: c.outward_normal_local = -nf; break;
    case 2: c.outward_normal_local = (nf + in.ConsumeFloatingPointInRange(0.0, 2.0) * direction(in, nf)); break;
    default: c.outward_normal_local = direction(in, nf);
  }
  if (!(c.outward_normal_local.norm() > 1e-6)) c.outward_normal_local = nf;
  c.outward_normal_local.normalize();
  c.separation = logScaled(in, -9, -1);
  c.rounding = in.ConsumeBool() ? 0.0 : (in.ConsumeBool() ? 5e-4 : in.ConsumeFloatingPointInRange(0.0, 0.01));
  if (in.ConsumeBool()) c.ring_reference_local = direction(in, Vec3::Zero());
  return c;
}

// Step 3: every live setting within the range sim/scene/settings.cpp accepts (fingerSettings), the
// filled patch's rings, and the effect switches.
gf::sim::PatchSettings decodeSettings(FuzzedDataProvider& in) {
  gf::sim::PatchSettings s;
  s.fill = in.ConsumeBool() ? gf::sim::PatchFill::kFilled : gf::sim::PatchFill::kRing;
  s.rings = in.ConsumeIntegralInRange(1, gf::sim::kMaxRings);
  s.n_sgo = in.ConsumeIntegralInRange(gf::sim::kMinSgo, gf::sim::kMaxSgo);
  s.r_max = in.ConsumeBool() ? 0.01 : in.ConsumeFloatingPointInRange(0.0, 1.0);
  s.d0 = in.ConsumeBool() ? 0.004 : std::pow(10.0, in.ConsumeFloatingPointInRange(-6.0, 0.0));
  s.alpha = in.ConsumeFloatingPointInRange(1.0, 100.0);
  s.stretch_length = std::pow(10.0, in.ConsumeFloatingPointInRange(-6.0, 0.0));
  s.max_stretch = in.ConsumeFloatingPointInRange(1.0, 2.0);
  s.tau_a = in.ConsumeFloatingPointInRange(0.0, 90.0) * std::numbers::pi / 180.0;
  s.friction = in.ConsumeFloatingPointInRange(0.0, 100.0);
  s.tangential_stretch = in.ConsumeBool();
  s.angular_threshold = in.ConsumeBool();
  s.friction_cone = in.ConsumeBool();
  return s;
}

// Aborts (a crash libFuzzer records) when `ok` is false.
void require(bool ok) {
  if (!ok) __builtin_trap();
}

double minEdge(const gf::sim::Mesh& mesh) {
  double shortest = std::numeric_limits<double>::infinity();
  for (int f = 0; f < mesh.faceCount(); ++f) {
    for (int k = 0; k < 3; ++k) shortest = std::min(shortest, (mesh.corner(f, (k + 1) % 3) - mesh.corner(f, k)).norm());
  }
  return shortest;
}

// An SGO (or inner point) of `p`: finite and within 1e-9 of the mesh's scale of its surface.
void requireOnSurface(const gf::sim::Mesh& mesh, const gf::sim::Sgo& sgo, double tolerance) {
  require(sgo.position.allFinite() && std::isfinite(sgo.walked) && std::isfinite(sgo.load_share));
  require(sgo.face >= 0 && sgo.face < mesh.faceCount());
  require(mesh.closestPoint(sgo.position, 0.0).query_distance <= tolerance);
}

// Step 4: the invariants of a computed patch.
void requireSane(const gf::sim::Mesh& mesh, const gf::sim::PatchSettings& s, const gf::sim::Patch& p) {
  require(p.valid);
  require(std::isfinite(p.radius) && p.radius >= 0.0 && p.radius <= s.r_max);
  require(p.sgos.size() <= static_cast<std::size_t>(s.n_sgo));
  // Scale of the mesh: its size and its distance from the origin (coordinates round there).
  const double scale = std::max({mesh.diagonal(), mesh.boundsMin().cwiseAbs().maxCoeff(),
                                 mesh.boundsMax().cwiseAbs().maxCoeff()});
  const double tolerance = 1e-9 * scale;
  const double shortest = minEdge(mesh);
  require(p.path_offsets.size() == (p.sgos.empty() ? (p.radius > 0 ? 1u : 0u) : p.sgos.size() + 1));
  for (std::size_t k = 0; k < p.sgos.size(); ++k) {
    const gf::sim::Sgo& sgo = p.sgos[k];
    requireOnSurface(mesh, sgo, tolerance);
    require(sgo.radial >= 0 && sgo.radial < s.n_sgo);
    const double d = p.d_i[static_cast<std::size_t>(sgo.radial)];
    require(sgo.walked <= d * (1 + 1e-9) + 1e-300);
    // The crossing budget: max_face_crossings plus 8 per mean edge length of the start face
    // (at least the shortest edge), at most 1e6; a path holds its start, one point per
    // crossing and its end.
    const double extra = std::min(1e6, std::ceil(8.0 * d / shortest));
    const int points = p.path_offsets[k + 1] - p.path_offsets[k];
    require(points >= 1 && points <= s.max_face_crossings + 2 + extra);
  }
  for (const gf::sim::Sgo& inner : p.inner) requireOnSurface(mesh, inner, tolerance);
  for (const Vec3& q : p.path_points) require(q.allFinite());
  for (double d : p.d_i) require(std::isfinite(d) && d >= 0.0);
  require(std::isfinite(p.centre_share));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzedDataProvider in(data, size);
  const gf::sim::Mesh mesh = decodeMesh(in);
  if (mesh.faceCount() == 0) return 0;
  const gf::sim::PatchContact contact = decodeContact(in, mesh);
  // v = p_I - p_GO: the device within 1000 m of the proxy, down to sub-nanometre offsets.
  const Vec3 v(logScaled(in, -12, 3), logScaled(in, -12, 3), logScaled(in, -12, 3));
  const gf::sim::PatchSettings settings = decodeSettings(in);
  gf::sim::Patch patch;
  gf::sim::computePatch(mesh, contact, v, settings, patch);
  requireSane(mesh, settings, patch);
  return 0;
}
