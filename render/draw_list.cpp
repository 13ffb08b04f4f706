#include "render/draw_list.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace gf::render {
namespace {

using sim::Vec3;

constexpr float kGhostAlpha = 0.28f;
constexpr float kPatchAlpha = 0.65f;
constexpr float kRimAlpha = 0.95f;
constexpr float kProxyAlpha = 0.45f;
constexpr int kSpringSegments = 96;  // a coil of 8 turns
constexpr int kSpringTurns = 8;
const Eigen::Vector3f kWhite(0.95f, 0.95f, 0.95f);
const Eigen::Vector3f kForceColour(1.0f, 0.75f, 0.1f);
const Eigen::Vector3f kSpringColour = Eigen::Vector3f::Constant(0.1f);
constexpr float kSpringAlpha = 0.85f;

// Rotation taking +y onto `direction` (unit).
sim::Quat fromY(const Vec3& direction) { return sim::Quat::FromTwoVectors(Vec3::UnitY(), direction); }

DrawItem shapeItem(DrawPass pass, DrawShape shape, const Eigen::Matrix4f& model, const Eigen::Vector3f& colour,
                   float alpha) {
  DrawItem item;
  item.pass = pass;
  item.shape = shape;
  item.model = model;
  item.colour = colour;
  item.alpha = alpha;
  return item;
}

// Appends `vertices` to the list as one range item (nothing when empty).
void addRange(DrawList& out, DrawPass pass, DrawShape shape, const std::vector<Vertex>& vertices,
              const Eigen::Vector3f& colour, float alpha) {
  if (vertices.empty()) return;
  DrawItem item;
  item.pass = pass;
  item.shape = shape;
  item.colour = colour;
  item.alpha = alpha;
  item.first = static_cast<int>(out.vertices.size());
  item.count = static_cast<int>(vertices.size());
  out.vertices.insert(out.vertices.end(), vertices.begin(), vertices.end());
  out.items.push_back(item);
}

}  // namespace

Eigen::Vector3f fingerColour(int finger) {
  static const Eigen::Vector3f kPalette[] = {{0.10f, 0.35f, 0.95f}, {0.90f, 0.12f, 0.30f},
                                             {0.10f, 0.70f, 0.25f}, {0.85f, 0.65f, 0.05f}};
  return kPalette[static_cast<std::size_t>(finger) % 4];
}

Eigen::Matrix4f modelMatrix(const Vec3& position, const sim::Quat& orientation, const Vec3& scale) {
  Eigen::Affine3d a = Eigen::Translation3d(position) * orientation * Eigen::Scaling(scale);
  return a.matrix().cast<float>();
}

Vec3 forceArrow(const sim::FingerSnapshot& f, const DrawSettings& settings) {
  const double n = f.feedback_force.norm();
  if (n < 1e-9) return Vec3::Zero();
  return std::min(settings.max_arrow_m, n * settings.force_arrow_m_per_n) / n * f.feedback_force;
}

DrawListBuilder::DrawListBuilder(const sim::SceneDesc& scene, std::vector<std::shared_ptr<const sim::Mesh>> surfaces)
    : surfaces_(std::move(surfaces)) {
  for (const sim::FingerDesc& f : scene.fingers) {
    proxy_radius_.push_back(f.proxy.radius);
    r_max_.push_back(f.patch.r_max);
  }
}

// Proxies first: they write no depth, so the patch each one stands on is drawn over it (it
// shows through), then the patches, then the ghosts and springs.
void DrawListBuilder::build(const sim::Snapshot& snapshot, const DrawSettings& settings, DrawList& out) {
  out.clear();
  if (settings.fingers) addProxies(snapshot, out);
  if (settings.patch_highlight) addPatches(snapshot, settings, out);
  if (settings.fingers) addFingers(snapshot, out);
}

// Per finger: the translucent fill on the surface, then the walked paths and rim, then the dots,
// then the arrows (normals and the force).
void DrawListBuilder::addPatches(const sim::Snapshot& snap, const DrawSettings& settings, DrawList& out) {
  for (std::size_t i = 0; i < snap.fingers.size(); ++i) {
    const sim::FingerSnapshot& f = snap.fingers[i];
    const Eigen::Vector3f colour = fingerColour(static_cast<int>(i));
    fill_.clear();
    rim_.clear();
    lines_.clear();
    for (const sim::ContactSnapshot& c : f.contacts) {
      const std::size_t b = static_cast<std::size_t>(c.body);
      if (b < surfaces_.size() && surfaces_[b]) patch_builder_.build(c, *surfaces_[b], snap.bodies[b], fill_, rim_, lines_);
    }
    // The fill in the finger's colour, a pale rim band that reads on any body colour, and dark
    // lines (the walked paths and the edge) over both.
    addRange(out, DrawPass::kPatchFill, DrawShape::kTriangles, fill_, colour, kPatchAlpha);
    addRange(out, DrawPass::kPatchRim, DrawShape::kTriangles, rim_, 0.2f * colour + Eigen::Vector3f::Constant(0.8f), kRimAlpha);
    addRange(out, DrawPass::kPatchLines, DrawShape::kLines, lines_, 0.4f * colour, 1.0f);
    const double dot = 0.12 * proxy_radius_[i];
    for (const sim::ContactSnapshot& c : f.contacts) {
      // The god-object's contact point; with n_SGO = 0 it is the whole patch.
      out.items.push_back(shapeItem(DrawPass::kMarks, DrawShape::kDot,
                                    modelMatrix(c.point_world, sim::Quat::Identity(), Vec3::Constant(1.3 * dot)), kWhite, 1.0f));
      for (const Vec3& s : c.sgos_world) {
        out.items.push_back(shapeItem(DrawPass::kMarks, DrawShape::kDot,
                                      modelMatrix(s, sim::Quat::Identity(), Vec3::Constant(dot)), colour, 1.0f));
      }
    }
    for (const sim::ContactSnapshot& c : f.contacts) {
      const double length = std::max(c.radius, 0.6 * r_max_[i]);
      addArrow(out, c.point_world, length * c.outward_normal_world, 0.3 * dot, kWhite);
    }
    // The force rendered to the device, from the proxy: it points away from what is touched.
    if (!f.contacts.empty()) addArrow(out, f.proxy, forceArrow(f, settings), 0.6 * dot, kForceColour);
  }
}

// The proxies: translucent, drawn before the patches without writing depth, so the patch under
// the finger shows through.
void DrawListBuilder::addProxies(const sim::Snapshot& snap, DrawList& out) {
  for (std::size_t i = 0; i < snap.fingers.size(); ++i) {
    const Eigen::Vector3f colour = fingerColour(static_cast<int>(i)) * 0.8f + Eigen::Vector3f::Constant(0.15f);
    out.items.push_back(shapeItem(DrawPass::kProxies, DrawShape::kSphere,
                                  modelMatrix(snap.fingers[i].proxy, sim::Quat::Identity(), Vec3::Constant(proxy_radius_[i])),
                                  colour, kProxyAlpha));
  }
}

// The device ghosts and the springs, which see through bodies: the device sits inside the
// object while pressing.
void DrawListBuilder::addFingers(const sim::Snapshot& snap, DrawList& out) {
  lines_.clear();
  for (std::size_t i = 0; i < snap.fingers.size(); ++i) {
    const sim::FingerSnapshot& f = snap.fingers[i];
    out.items.push_back(shapeItem(DrawPass::kGhosts, DrawShape::kSphere,
                                  modelMatrix(f.device, sim::Quat::Identity(), Vec3::Constant(proxy_radius_[i])),
                                  fingerColour(static_cast<int>(i)), kGhostAlpha));
    addSpring(out, f.proxy, f.device, 0.5 * proxy_radius_[i]);
  }
  addRange(out, DrawPass::kSprings, DrawShape::kLines, lines_, kSpringColour, kSpringAlpha);
}

void DrawListBuilder::addArrow(DrawList& out, const Vec3& from, const Vec3& vector, double radius,
                               const Eigen::Vector3f& colour) {
  const double length = vector.norm();
  if (length < 1e-6) return;
  const Vec3 dir = vector / length;
  const double head = std::min(0.45 * length, 5.0 * radius);
  const sim::Quat q = fromY(dir);
  out.items.push_back(shapeItem(DrawPass::kArrows, DrawShape::kCylinder,
                                modelMatrix(from, q, Vec3(radius, length - head, radius)), colour, 1.0f));
  out.items.push_back(shapeItem(DrawPass::kArrows, DrawShape::kCone,
                                modelMatrix(from + (length - head) * dir, q, Vec3(2.5 * radius, head, 2.5 * radius)),
                                colour, 1.0f));
}

// A coil from the proxy centre to the device, into lines_ (joined to the list after all fingers).
void DrawListBuilder::addSpring(DrawList&, const Vec3& a, const Vec3& b, double coil_radius) {
  const Vec3 axis = b - a;
  if (axis.norm() < 1e-4) return;
  const sim::Quat q = fromY(axis.normalized());
  Vec3 previous = a;
  for (int s = 1; s <= kSpringSegments; ++s) {
    const double u = double(s) / kSpringSegments, angle = kSpringTurns * 2 * std::numbers::pi * u;
    const double taper = std::min(1.0, std::min(u, 1 - u) * 12);
    const Vec3 p = a + u * axis + q * Vec3(taper * coil_radius * std::cos(angle), 0, taper * coil_radius * std::sin(angle));
    lines_.push_back(makeVertex(previous, Vec3::UnitY()));
    lines_.push_back(makeVertex(p, Vec3::UnitY()));
    previous = p;
  }
}

}  // namespace gf::render
