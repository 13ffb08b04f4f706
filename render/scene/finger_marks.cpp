#include "render/scene/finger_marks.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace gf::render {
namespace {

using sim::Vec3;

constexpr double kTurnedRad = 0.5 * std::numbers::pi / 180.0;  // a device turned less is not turned
constexpr int kOutlineSegments = 40;   // straight pieces around the pad's outline
constexpr int kTubeSides = 6;          // around the outline's tube
constexpr double kMarkMinPx = 0.9;        // a mark's least radius (pixels)
constexpr double kBeadShare = 2.4;        // the twist bead's radius, in mark radii
constexpr int kCapsuleSegments = 28;      // around a fingertip
constexpr int kCapsuleRings = 7;          // from each pole to its cap's rim
const Eigen::Vector3f kNailColour(0.95f, 0.88f, 0.86f);
constexpr float kNailAlpha = 0.55f;

// A unit vector across `axis` (unit) from `v`, or any one across it when v runs along it.
Vec3 across(const Vec3& v, const Vec3& axis) {
  const Vec3 w = v - v.dot(axis) * axis;
  return w.norm() > 1e-6 ? w.normalized() : axis.unitOrthogonal();
}

// Metres a pixel spans at `at` in `view` (0 without a view).
double metresPerPixel(const std::optional<DrawView>& view, const Vec3& at) {
  if (!view) return 0.0;
  const double depth = (view->view_proj * at.homogeneous()).w();
  return 2.0 * std::max(depth, 0.002) * view->tan_half_fov / std::max(1, view->height_px);
}

// A ring of tube radius `tube` (m): centre `c`, radius `rho` (m), in the plane across unit `n`,
// as triangles wound outward.
void appendRing(const Vec3& c, const Vec3& n, double rho, double tube, std::vector<Vertex>& out) {
  const Vec3 a = n.unitOrthogonal(), b = n.cross(a);
  const auto point = [&](int j, int k) {
    const double theta = 2.0 * std::numbers::pi * j / kOutlineSegments, psi = 2.0 * std::numbers::pi * k / kTubeSides;
    const Vec3 e = std::cos(theta) * a + std::sin(theta) * b;
    const Vec3 normal = std::cos(psi) * e + std::sin(psi) * n;
    return makeVertex(c + rho * e + tube * normal, normal);
  };
  for (int j = 0; j < kOutlineSegments; ++j) {
    for (int k = 0; k < kTubeSides; ++k) {
      const Vertex v0 = point(j, k), v1 = point(j + 1, k), v2 = point(j + 1, k + 1), v3 = point(j, k + 1);
      out.insert(out.end(), {v0, v1, v2, v0, v2, v3});
    }
  }
}

// The rotation taking the unit shapes' y onto `up` and their z onto `back` (both unit, across).
sim::Quat frameOf(const Vec3& up, const Vec3& back) {
  Eigen::Matrix3d m;
  m.col(0) = up.cross(back);
  m.col(1) = up;
  m.col(2) = back;
  return sim::Quat(m);
}

}  // namespace

Vec3 deviceUp(const sim::FingerSnapshot& f) {
  const Vec3 axis = f.patch.pad_axis.norm() > 0.0 ? f.patch.pad_axis.normalized() : Vec3(0.0, -1.0, 0.0);
  return -(f.pad.nodes.empty() ? f.device_orientation * axis : axis);
}

Vec3 deviceSide(const sim::FingerSnapshot& f) { return f.device_orientation * Vec3::UnitX(); }

bool drawsPadOutline(const sim::FingerSnapshot& f) {
  return f.pad.nodes.empty() && f.patch.pad_model == sim::PadModel::kOriented;
}

bool drawsTiltMarker(const sim::FingerSnapshot& f) {
  return drawsPadOutline(f) || (f.pad.nodes.empty() && f.device_orientation.angularDistance(sim::Quat::Identity()) > kTurnedRad);
}

double fingerReach(const sim::FingerSnapshot& f, double proxy_radius, view::ProxyLook look) {
  if (look == view::ProxyLook::kFingertip && f.pad.nodes.empty()) return (1.0 + kFingertipLengthShare) * proxy_radius;
  return drawsTiltMarker(f) ? (1.0 + kTiltMarkerShare) * proxy_radius : proxy_radius;
}

// Rings of latitude from the pad's pole (the proxy sphere's lower half about deviceUp()) to the
// top's, the body's straight side between the two middle rings.
void appendFingertip(const sim::FingerSnapshot& f, double r, std::vector<Vertex>& out) {
  if (!f.pad.nodes.empty()) return;
  const Vec3 up = deviceUp(f), a = up.unitOrthogonal(), b = up.cross(a);
  const double length = kFingertipLengthShare * r;
  const auto point = [&](int ring, int j) {
    const bool top = ring > kCapsuleRings;
    const double phi = 0.5 * std::numbers::pi * (top ? ring - kCapsuleRings - 1 : ring - kCapsuleRings) / kCapsuleRings;
    const double theta = 2.0 * std::numbers::pi * j / kCapsuleSegments;
    const Vec3 normal = std::cos(phi) * (std::cos(theta) * a + std::sin(theta) * b) + std::sin(phi) * up;
    return makeVertex(f.proxy + (top ? length : 0.0) * up + r * normal, normal);
  };
  for (int ring = 0; ring <= 2 * kCapsuleRings; ++ring) {
    for (int j = 0; j < kCapsuleSegments; ++j) {
      const Vertex v0 = point(ring, j), v1 = point(ring, j + 1), v2 = point(ring + 1, j + 1), v3 = point(ring + 1, j);
      out.insert(out.end(), {v0, v1, v2, v0, v2, v3});
    }
  }
}

// The nail first (translucent, with the proxies), then the opaque marks: outline, bead, stalk.
void addFingerMarks(const sim::FingerSnapshot& f, int index, double r, view::ProxyLook look,
                    const std::optional<DrawView>& view, std::vector<Vertex>& scratch, DrawList& out) {
  const Vec3 up = deviceUp(f);
  const bool fingertip = look == view::ProxyLook::kFingertip && f.pad.nodes.empty();
  if (fingertip) {
    const Vec3 back = across(f.device_orientation * -Vec3::UnitZ(), up);
    const sim::Quat nail = frameOf(up, back);
    out.items.push_back(shapeItem(DrawPass::kProxies, DrawShape::kSphere,
                                 modelMatrix(f.proxy + 1.6 * r * up + 0.9 * r * back, nail, Vec3(0.55 * r, 0.8 * r, 0.18 * r)),
                                 kNailColour, kNailAlpha));
  }
  const Eigen::Vector3f colour = fingerColour(index);
  const double width = std::max(kMarkWidthShare * r, kMarkMinPx * metresPerPixel(view, f.proxy));
  if (drawsPadOutline(f)) {
    // The pad's outline on the sphere (a little outside, clear of its surface) and the bead.
    const double lift = r + width;
    const Vec3 centre = f.proxy - lift * std::cos(kPadOutlineAngle) * up;
    const double rho = lift * std::sin(kPadOutlineAngle);
    scratch.clear();
    appendRing(centre, up, rho, width, scratch);
    DrawItem ring = shapeItem(DrawPass::kMarks, DrawShape::kTriangles, Eigen::Matrix4f::Identity(), colour, 1.0f);
    ring.first = static_cast<int>(out.vertices.size());
    ring.count = static_cast<int>(scratch.size());
    out.vertices.insert(out.vertices.end(), scratch.begin(), scratch.end());
    out.items.push_back(ring);
    const Vec3 bead = centre + rho * across(deviceSide(f), up);
    out.items.push_back(shapeItem(DrawPass::kMarks, DrawShape::kDot,
                                 modelMatrix(bead, sim::Quat::Identity(), Vec3::Constant(kBeadShare * width)),
                                 Eigen::Vector3f::Constant(0.95f), 1.0f));
  }
  if (!drawsTiltMarker(f) || fingertip) return;
  // The stalk: from the sphere's surface along deviceUp(), its head the last third.
  const double length = kTiltMarkerShare * r, head = std::min(length / 3.0, 5.0 * width);
  const sim::Quat along = sim::Quat::FromTwoVectors(Vec3::UnitY(), up);
  out.items.push_back(shapeItem(DrawPass::kMarks, DrawShape::kCylinder,
                               modelMatrix(f.proxy + r * up, along, Vec3(width, length - head, width)), colour, 1.0f));
  out.items.push_back(shapeItem(DrawPass::kMarks, DrawShape::kCone,
                               modelMatrix(f.proxy + (r + length - head) * up, along, Vec3(2.5 * width, head, 2.5 * width)),
                               colour, 1.0f));
}

}  // namespace gf::render
