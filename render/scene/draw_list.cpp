#include "render/scene/draw_list.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "render/state/contact_load.hpp"
#include "render/scene/finger_marks.hpp"
#include "render/scene/load_marks.hpp"
#include "render/scene/overlap_region.hpp"

namespace gf::render {
namespace {

using sim::Vec3;

constexpr float kGhostAlpha = 0.9f;
constexpr int kGhostDashes = 16;          // dashes around a device's outline
constexpr int kGhostDashSegments = 3;     // straight pieces per dash
constexpr double kGhostDashShare = 0.55;  // of each dash's arc that is drawn
constexpr double kGhostWidthShare = 0.1;  // the outline's width, of the proxy radius...
constexpr double kGhostMinWidthPx = 1.6;  // ...and at least this many pixels
constexpr double kSlipRingShare = 1.8;    // a slip ring's outer radius, in dot radii
constexpr double kSlipRingThickness = 0.1;  // its height along the normal, in dot radii
constexpr double kSlipRingLiftM = 0.0003;   // m above the surface: clear of the patch fill (0.2 mm)
constexpr double kFrameMargin = 0.04;     // of the frame each side that an arrow's tip stays out of
constexpr double kNearM = 0.002;          // m: the near plane (scene_renderer's)
constexpr float kPatchAlpha = 0.65f;
constexpr float kRimAlpha = 0.95f;
constexpr float kOverlapAlpha = 0.6f;
// The overlap region's height above the surface, in proxy radii: over the SGO dots (0.12), which
// show through it, tinted.
constexpr double kOverlapLiftShare = 0.15;
constexpr float kProxyAlpha = 0.45f;
constexpr int kSpringSegments = 96;  // a coil of 8 turns
constexpr int kSpringTurns = 8;
const Eigen::Vector3f kWhite(0.95f, 0.95f, 0.95f);
const Eigen::Vector3f kForceColour(1.0f, 0.75f, 0.1f);
const Eigen::Vector3f kSlipColour(1.0f, 1.0f, 1.0f);  // white: outside viridis and every finger colour
const Eigen::Vector3f kSpringColour = Eigen::Vector3f::Constant(0.1f);
constexpr float kSpringAlpha = 0.85f;
constexpr float kTargetGhostAlpha = 0.35f;  // a body's ghost at its target pose
constexpr float kTargetZoneAlpha = 0.15f;   // a zone's faces; its edges are opaque

// Rotation taking +y onto `direction` (unit).
sim::Quat fromY(const Vec3& direction) { return sim::Quat::FromTwoVectors(Vec3::UnitY(), direction); }

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

Eigen::Vector3f fingerColour(int finger) {
  static const Eigen::Vector3f kPalette[] = {{0.10f, 0.35f, 0.95f}, {0.90f, 0.12f, 0.30f},
                                             {0.10f, 0.70f, 0.25f}, {0.85f, 0.65f, 0.05f}};
  return kPalette[static_cast<std::size_t>(finger) % 4];
}

Eigen::Matrix4f modelMatrix(const Vec3& position, const sim::Quat& orientation, const Vec3& scale) {
  Eigen::Affine3d a = Eigen::Translation3d(position) * orientation * Eigen::Scaling(scale);
  return a.matrix().cast<float>();
}

double longestArrowInView(const DrawView& view, const Vec3& from, const Vec3& direction, double share) {
  // Clip coordinates along the arrow are linear in its length t: c(t) = a + t b.
  const Eigen::Vector4d a = view.view_proj * from.homogeneous();
  const Eigen::Vector4d b = view.view_proj * Eigen::Vector4d(direction.x(), direction.y(), direction.z(), 0.0);
  if (a.w() <= kNearM) return 0.0;
  double longest = share * 2.0 * a.w() * view.tan_half_fov;  // w is the depth for a perspective view
  const double k = 1.0 - 2.0 * kFrameMargin;
  // Each side of the frame less its margin, and the near plane, as g0 + t g1 >= 0.
  const std::array<std::pair<double, double>, 5> sides = {{{k * a.w() - a.x(), k * b.w() - b.x()},
                                                           {k * a.w() + a.x(), k * b.w() + b.x()},
                                                           {k * a.w() - a.y(), k * b.w() - b.y()},
                                                           {k * a.w() + a.y(), k * b.w() + b.y()},
                                                           {a.w() - kNearM, b.w()}}};
  for (const auto& [g0, g1] : sides) {
    if (g0 < 0.0) return longest;  // it starts outside: only the share applies
  }
  for (const auto& [g0, g1] : sides) {
    if (g1 < 0.0) longest = std::min(longest, -g0 / g1);
  }
  return longest;
}

// A shaft and a head, drawn without depth: the part nearer the camera goes last (the head of an
// arrow pointing at the camera covers its shaft; the shaft of one pointing away covers the head's
// base).
void addArrowItems(DrawList& out, const Vec3& from, const Vec3& vector, double radius, const Eigen::Vector3f& colour,
                   const std::optional<Vec3>& eye) {
  const double length = vector.norm();
  if (length < 1e-6) return;
  const Vec3 dir = vector / length;
  const double head = std::min(0.45 * length, 5.0 * radius);
  const sim::Quat q = fromY(dir);
  const DrawItem shaft = shapeItem(DrawPass::kArrows, DrawShape::kCylinder,
                                   modelMatrix(from, q, Vec3(radius, length - head, radius)), colour, 1.0f);
  const DrawItem cone = shapeItem(DrawPass::kArrows, DrawShape::kCone,
                                  modelMatrix(from + (length - head) * dir, q, Vec3(2.5 * radius, head, 2.5 * radius)),
                                  colour, 1.0f);
  const bool away = eye && dir.dot(*eye - from) < 0.0;
  out.items.push_back(away ? cone : shaft);
  out.items.push_back(away ? shaft : cone);
}

double proxySphereRadius(const sim::FingerSnapshot& f, double proxy_radius) {
  return f.pad.nodes.empty() ? proxy_radius : f.pad.bone_radius;
}

Vec3 forceArrow(const sim::FingerSnapshot& f, const DrawSettings& settings) {
  const double n = f.feedback_force.norm();
  if (n < 1e-9) return Vec3::Zero();
  const Vec3 direction = f.feedback_force / n;
  double length = std::min(settings.max_arrow_m, n * settings.force_arrow_m_per_n);
  if (settings.view) length = std::min(length, longestArrowInView(*settings.view, f.proxy, direction, settings.max_arrow_view_share));
  return length * direction;
}

DrawListBuilder::DrawListBuilder(const sim::SceneDesc& scene, std::vector<std::shared_ptr<const sim::Mesh>> surfaces)
    : surfaces_(std::move(surfaces)) {
  for (const sim::BodyDesc& b : scene.bodies) body_colour_.push_back(b.colour.cast<float>());
  for (const sim::FingerDesc& f : scene.fingers) {
    proxy_radius_.push_back(f.proxy.radius);
    r_max_.push_back(f.patch.r_max);
    friction_.push_back(f.patch.friction);
  }
}

// Pads first: opaque, they hide what is behind them, the bones included. The proxies next: they
// write no depth, so the patch each one stands on is drawn over it (it shows through); the
// springs next, so the patches and dots cover the coil where it runs through them to the device
// inside the body; then the patches, then the ghosts' outlines.
void DrawListBuilder::build(const sim::Snapshot& snapshot, const DrawSettings& settings, DrawList& out) {
  out.clear();
  view_eye_.reset();
  if (settings.view) view_eye_ = settings.view->eye;
  addSoftBodies(snapshot, out);
  if (settings.fingers) addPads(snapshot, out);
  if (settings.targets) addTargets(*settings.targets, out);  // translucent: after the opaque pads
  if (settings.fingers) {
    addProxies(snapshot, settings, out);
    addSprings(snapshot, out);
  }
  if (settings.patch_highlight) addPatches(snapshot, settings, out);
  if (settings.fingers) addGhosts(snapshot, settings, out);
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
    for (const sim::ContactSnapshot& c : f.contacts) addMarks(c, colour, dot, out);
    for (const sim::ContactSnapshot& c : f.contacts) {
      if (settings.load_arrows) {
        addLoadArrows(out, c, loadArrowScale(c, r_max_[i]), settings.contact_arrows, 0.2 * dot, view_eye_);
      }
      if (!settings.torsion_arcs) continue;
      if (const std::optional<TorsionArc> arc = torsionArc(c, friction_[i], r_max_[i])) {
        addTorsionArc(out, *arc, 0.3 * dot, kForceColour, view_eye_);
      }
    }
    if (!settings.contact_arrows) continue;
    for (const sim::ContactSnapshot& c : f.contacts) {
      const double length = std::max(c.radius, 0.6 * r_max_[i]);
      addArrowItems(out, c.point_world, length * c.outward_normal_world, 0.3 * dot, kWhite, view_eye_);
    }
    // The force rendered to the device, from the proxy: it points away from what is touched.
    if (!f.contacts.empty()) addArrowItems(out, f.proxy, forceArrow(f, settings), 0.6 * dot, kForceColour, view_eye_);
  }
  addOverlaps(snap, out);
}

// The region each two fingers' patches on one body both cover, over the patches, in its tint.
void DrawListBuilder::addOverlaps(const sim::Snapshot& snap, DrawList& out) {
  fill_.clear();
  lines_.clear();
  for (std::size_t i = 0; i < snap.fingers.size(); ++i) {
    for (std::size_t j = i + 1; j < snap.fingers.size(); ++j) {
      for (const sim::ContactSnapshot& a : snap.fingers[i].contacts) {
        for (const sim::ContactSnapshot& b : snap.fingers[j].contacts) {
          const std::size_t body = static_cast<std::size_t>(a.body);
          if (a.body != b.body || body >= surfaces_.size() || !surfaces_[body]) continue;
          const double lift = kOverlapLiftShare * std::min(proxy_radius_[i], proxy_radius_[j]);
          buildOverlapRegion(a, b, *surfaces_[body], snap.bodies[body], lift, fill_, lines_);
        }
      }
    }
  }
  const Eigen::Vector3f tint(kOverlapColour[0], kOverlapColour[1], kOverlapColour[2]);
  addRange(out, DrawPass::kPatchRim, DrawShape::kTriangles, fill_, tint, kOverlapAlpha);
  addRange(out, DrawPass::kPatchLines, DrawShape::kLines, lines_, 0.5f * tint, 1.0f);
}

// The contact point and the SGOs (and a filled patch's points) of one contact. With per-point
// loads each dot takes its load's colour on the viridis scale (contact_load.hpp) and a slipping
// point a white ring around its dot, lying in the tangent plane; without them the contact point
// is white and the SGOs are in the finger's colour.
void DrawListBuilder::addMarks(const sim::ContactSnapshot& c, const Eigen::Vector3f& colour, double dot, DrawList& out) {
  const ContactLoads loads = contactLoads(c);
  const sim::Quat along_normal = fromY(c.outward_normal_world);
  const auto mark = [&](const Vec3& at, double radius, const Eigen::Vector3f& uniform, const sim::PointLoad* load) {
    if (loads.shown && load && load->slipping) {
      const double ring = kSlipRingShare * dot;
      out.items.push_back(shapeItem(DrawPass::kMarks, DrawShape::kCylinder,
                                    modelMatrix(at + kSlipRingLiftM * c.outward_normal_world, along_normal,
                                                Vec3(ring, kSlipRingThickness * dot, ring)),
                                    kSlipColour, 1.0f));
    }
    out.items.push_back(shapeItem(DrawPass::kMarks, DrawShape::kDot,
                                  modelMatrix(at, sim::Quat::Identity(), Vec3::Constant(radius)),
                                  loads.shown && load ? loads.colour(load->normal) : uniform, 1.0f));
  };
  // The god-object's contact point; with n_SGO = 0 it is the whole patch.
  mark(c.point_world, 1.3 * dot, kWhite, c.point_loaded || !loads.shown ? &c.point_load : nullptr);
  for (std::size_t k = 0; k < c.sgos_world.size(); ++k) {
    mark(c.sgos_world[k], dot, colour, loads.shown ? &c.loads[k] : nullptr);
  }
}

// Each fem_pad finger's skin as it is, one range per pad.
void DrawListBuilder::addPads(const sim::Snapshot& snap, DrawList& out) {
  for (const sim::FingerSnapshot& f : snap.fingers) {
    fill_.clear();
    pad_builder_.build(f.pad, fill_);
    addRange(out, DrawPass::kPads, DrawShape::kTriangles, fill_, kPadColour, 1.0f);
  }
}

// Each soft body's surface as it is, in its colour, with the pads: opaque, lit and shadowed.
void DrawListBuilder::addSoftBodies(const sim::Snapshot& snap, DrawList& out) {
  for (const sim::SoftBodySnapshot& s : snap.soft_bodies) {
    if (!s.surface || s.body < 0 || static_cast<std::size_t>(s.body) >= body_colour_.size()) continue;
    fill_.clear();
    pad_builder_.build(s.nodes, *s.surface, fill_);
    addRange(out, DrawPass::kPads, DrawShape::kTriangles, fill_, body_colour_[static_cast<std::size_t>(s.body)], 1.0f);
  }
}

// Each target: the ghost of its body (the body's surface at the target pose), and its zone's
// faces, translucent, lit and depth-tested (a body in front hides them, one inside shows
// through; pulled towards the eye, so a ghost's face lying on its body's shows without
// flicker), with the zone's twelve edges over them. Drawn before the proxies.
void DrawListBuilder::addTargets(const std::vector<view::Target>& targets, DrawList& out) {
  for (const view::Target& t : targets) {
    const std::size_t b = static_cast<std::size_t>(t.body);
    if (t.body >= 0 && b < surfaces_.size() && surfaces_[b]) {
      const sim::Mesh& m = *surfaces_[b];
      fill_.clear();
      for (int f = 0; f < m.faceCount(); ++f) {
        const Vec3 n = t.orientation * m.faceNormal(f);
        for (int k = 0; k < 3; ++k) fill_.push_back(makeVertex(t.position + t.orientation * m.corner(f, k), n));
      }
      addRange(out, DrawPass::kTargets, DrawShape::kTriangles, fill_, kTargetColour, kTargetGhostAlpha);
    }
    if (!t.has_zone) continue;
    const auto corner = [&](int i) {
      return Vec3((i & 1) ? t.zone_max.x() : t.zone_min.x(), (i & 2) ? t.zone_max.y() : t.zone_min.y(),
                  (i & 4) ? t.zone_max.z() : t.zone_min.z());
    };
    // The six faces, wound outward (counter-clockwise seen from outside), two triangles each.
    static constexpr int kFaces[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
    static constexpr double kNormals[6][3] = {{-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {0, 0, -1}, {0, 0, 1}};
    fill_.clear();
    lines_.clear();
    for (int f = 0; f < 6; ++f) {
      const Vec3 n(kNormals[f][0], kNormals[f][1], kNormals[f][2]);
      const Vertex v[4] = {makeVertex(corner(kFaces[f][0]), n), makeVertex(corner(kFaces[f][1]), n),
                           makeVertex(corner(kFaces[f][2]), n), makeVertex(corner(kFaces[f][3]), n)};
      fill_.insert(fill_.end(), {v[0], v[1], v[2], v[0], v[2], v[3]});
    }
    for (int i = 0; i < 8; ++i) {
      for (int axis = 1; axis <= 4; axis <<= 1) {
        if (i & axis) continue;  // each edge once, from its lower corner
        lines_.push_back(makeVertex(corner(i), Vec3::UnitY()));
        lines_.push_back(makeVertex(corner(i | axis), Vec3::UnitY()));
      }
    }
    addRange(out, DrawPass::kTargets, DrawShape::kTriangles, fill_, kTargetColour, kTargetZoneAlpha);
    addRange(out, DrawPass::kPatchLines, DrawShape::kLines, lines_, 0.6f * kTargetColour, 1.0f);
  }
}

// The proxies: translucent, drawn before the patches without writing depth, so the patch under
// the finger shows through. A pad's bone, inside its skin, in the proxy's place; on request a
// fingertip, the proxy sphere its pad's end. Then each finger's marks of its device's
// orientation (finger_marks.hpp).
void DrawListBuilder::addProxies(const sim::Snapshot& snap, const DrawSettings& settings, DrawList& out) {
  for (std::size_t i = 0; i < snap.fingers.size(); ++i) {
    const Eigen::Vector3f colour = fingerColour(static_cast<int>(i)) * 0.8f + Eigen::Vector3f::Constant(0.15f);
    const double r = proxySphereRadius(snap.fingers[i], proxy_radius_[i]);
    fill_.clear();
    if (settings.proxy == view::ProxyLook::kFingertip) appendFingertip(snap.fingers[i], r, fill_);
    if (!fill_.empty()) {
      addRange(out, DrawPass::kProxies, DrawShape::kTriangles, fill_, colour, kProxyAlpha);
      continue;
    }
    out.items.push_back(shapeItem(DrawPass::kProxies, DrawShape::kSphere,
                                  modelMatrix(snap.fingers[i].proxy, sim::Quat::Identity(), Vec3::Constant(r)), colour,
                                  kProxyAlpha));
  }
  for (std::size_t i = 0; i < snap.fingers.size(); ++i) {
    const double r = proxySphereRadius(snap.fingers[i], proxy_radius_[i]);
    addFingerMarks(snap.fingers[i], static_cast<int>(i), r, settings.proxy, settings.view, fill_, out);
  }
}

// The coupling springs, which see through bodies: the device sits inside the object while
// pressing. One range for all fingers.
void DrawListBuilder::addSprings(const sim::Snapshot& snap, DrawList& out) {
  lines_.clear();
  for (std::size_t i = 0; i < snap.fingers.size(); ++i) {
    addSpring(snap.fingers[i].proxy, snap.fingers[i].device, 0.5 * proxy_radius_[i]);
  }
  addRange(out, DrawPass::kSprings, DrawShape::kLines, lines_, kSpringColour, kSpringAlpha);
}

// Each device as a dashed outline of the proxy's size facing the camera, in the finger's
// colour, seen through bodies: unlike the proxy (a translucent ball) it reads as a place, not a
// second finger.
void DrawListBuilder::addGhosts(const sim::Snapshot& snap, const DrawSettings& settings, DrawList& out) {
  for (std::size_t i = 0; i < snap.fingers.size(); ++i) {
    const Vec3& centre = snap.fingers[i].device;
    const double r = proxy_radius_[i];
    Vec3 facing = Vec3::UnitZ();
    double width = kGhostWidthShare * r;
    if (settings.view) {
      const Vec3 to_eye = settings.view->eye - centre;
      if (to_eye.norm() > 1e-9) facing = to_eye.normalized();
      const double depth = (settings.view->view_proj * centre.homogeneous()).w();
      const double m_per_px = 2.0 * std::max(depth, kNearM) * settings.view->tan_half_fov / std::max(1, settings.view->height_px);
      width = std::max(width, kGhostMinWidthPx * m_per_px);
    }
    const Vec3 u = facing.unitOrthogonal(), v = facing.cross(u);
    fill_.clear();
    const double dash = 2.0 * std::numbers::pi / kGhostDashes;
    for (int d = 0; d < kGhostDashes; ++d) {
      for (int s = 0; s < kGhostDashSegments; ++s) {
        const double a0 = dash * (d + kGhostDashShare * s / kGhostDashSegments);
        const double a1 = dash * (d + kGhostDashShare * (s + 1) / kGhostDashSegments);
        const Vec3 e0 = std::cos(a0) * u + std::sin(a0) * v, e1 = std::cos(a1) * u + std::sin(a1) * v;
        const Vertex o0 = makeVertex(centre + r * e0, facing), o1 = makeVertex(centre + r * e1, facing);
        const Vertex i0 = makeVertex(centre + (r - width) * e0, facing), i1 = makeVertex(centre + (r - width) * e1, facing);
        fill_.insert(fill_.end(), {o0, o1, i1, o0, i1, i0});
      }
    }
    addRange(out, DrawPass::kGhosts, DrawShape::kTriangles, fill_, fingerColour(static_cast<int>(i)), kGhostAlpha);
  }
}

// A coil from the proxy centre to the device, into lines_ (joined to the list after all fingers).
void DrawListBuilder::addSpring(const Vec3& a, const Vec3& b, double coil_radius) {
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
