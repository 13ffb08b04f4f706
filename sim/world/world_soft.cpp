// Soft bodies in the World (SoftBody, sim/soft/): each stepped before Bullet's step, its surface
// nodes against the rigid bodies, its surface pressed by the fingers whose proxies touch it. A
// finger with a god-finger patch presses at the contact point and at every point of its patch,
// computed by computePatch on the deformed surface (Algorithm 1 over the surface's triangles as
// they are this step); a god-object presses at its one point. Each press holds its point of the
// surface out of the finger's pad: the plane through the proxy's lowest point across the contact
// normal (a finger's flat pad), or with `imprint` round the proxy's sphere. The finger's
// translation is solved with the body (SoftBody), and the presses' forces then put on the proxy
// for Bullet's step, which moves it on at the velocity the body's step found. A soft body has a
// Bullet body too, which collides with nothing: a placeholder whose index keeps the bodies'
// numbering. Rigid scenes build none of this.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "sim/world/pad_bodies.hpp"

namespace gf::sim {
namespace {

// Barycentric coordinates of `p` (on or near face `f`) in that face, clamped into it.
Vec3 barycentric(const Mesh& mesh, int f, const Vec3& p) {
  const Vec3 a = mesh.corner(f, 0), e1 = mesh.corner(f, 1) - a, e2 = mesh.corner(f, 2) - a, d = p - a;
  const double d11 = e1.dot(e1), d12 = e1.dot(e2), d22 = e2.dot(e2), det = d11 * d22 - d12 * d12;
  if (!(det > 0.0)) return Vec3(1.0, 0.0, 0.0);
  double v = (d22 * d.dot(e1) - d12 * d.dot(e2)) / det, w = (d11 * d.dot(e2) - d12 * d.dot(e1)) / det;
  v = std::clamp(v, 0.0, 1.0);
  w = std::clamp(w, 0.0, 1.0 - v);
  return Vec3(1.0 - v - w, v, w);
}

}  // namespace

void World::Impl::addSoftBody(int index, const BodyDesc& d) {
  const std::shared_ptr<const TetMesh> rest = softMesh(d);
  TetMesh placed = *rest;
  const Quat q = d.orientation.normalized();
  for (Vec3& p : placed.nodes) p = q * p + d.position;
  std::vector<int> pinned;
  for (std::size_t n = 0; n < rest->nodes.size(); ++n) {
    for (const PinRegion& r : d.soft.pinned) {
      if ((rest->nodes[n].array() >= r.min.array()).all() && (rest->nodes[n].array() <= r.max.array()).all()) {
        pinned.push_back(static_cast<int>(n));
        break;
      }
    }
  }
  double volume = 0.0;
  for (const std::array<int, 4>& t : rest->tets) {
    volume += tetVolume(rest->nodes[t[0]], rest->nodes[t[1]], rest->nodes[t[2]], rest->nodes[t[3]]);
  }
  const SoftBodySettings settings{{d.soft.young, d.soft.poisson, d.mass / volume, d.soft.damping}, d.soft.contact_stiffness,
                                  desc.effects.friction ? d.friction : 0.0};
  Body& b = bodies[static_cast<std::size_t>(index)];
  b.soft = std::make_unique<SoftBody>(placed, settings, pinned, static_cast<int>(desc.fingers.size()));
  b.soft_origin = b.soft->frame().position;
  soft_bodies.push_back(index);
}

Pose World::Impl::softPose(int body) const {
  const Body& b = bodies[static_cast<std::size_t>(body)];
  const BodyDesc& d = desc.bodies[static_cast<std::size_t>(body)];
  const Pose& frame = b.soft->frame();
  return {frame.toWorld(d.position - b.soft_origin), frame.orientation * d.orientation.normalized()};
}

// Finger `fi`'s touch of soft body `body` this step, if its proxy reaches the surface (within
// kSoftTouchMargin: a press whose point is not inside the pad does nothing). A god-object presses
// the surface's point nearest the proxy's centre out of its sphere; a god-finger presses, out of
// its flat pad, every surface node of the faces its patch reached (the contact's, each walk's
// end, a filled patch's inner points and, with walk_fill, points along each walk) that lies
// within the patch's outline; where fewer than three do (a mesh coarser than the patch), every
// node of those faces. Appended to `soft_presses`.
void World::Impl::touchSoft(Finger& f, int fi, int body) {
  const SoftBody& s = *bodies[static_cast<std::size_t>(body)].soft;
  const Mesh& mesh = s.surface();
  const FingerDesc& fd = desc.fingers[static_cast<std::size_t>(fi)];
  const double radius = fd.proxy.radius;
  const Vec3 c = toEigen(f.proxy->getCenterOfMassPosition());
  if (f.pad || f.soft_count == kMaxContactsPerFinger) return;
  const double reach = radius + kSoftTouchMargin;
  if (((c.array() + reach) < mesh.boundsMin().array()).any() || ((c.array() - reach) > mesh.boundsMax().array()).any()) return;
  const SurfacePoint hit = mesh.closestPoint(c, 1e-9);
  if (hit.face < 0) return;
  const Vec3 d = c - hit.point;
  const double dist = d.norm();
  const bool outside = d.dot(mesh.faceNormal(hit.face)) >= 0.0;
  const double separation = outside ? dist - radius : -dist - radius;
  if (!(separation < kSoftTouchMargin)) return;
  // The slot that held this body's touch in the last step, if any, takes this one (its ring's
  // reference and its pressed nodes carry over).
  for (int k = f.soft_count + 1; k < kMaxContactsPerFinger; ++k) {
    if (f.soft[static_cast<std::size_t>(k)].body == body) std::swap(f.soft[static_cast<std::size_t>(k)], f.soft[static_cast<std::size_t>(f.soft_count)]);
  }
  SoftTouch& t = f.soft[static_cast<std::size_t>(f.soft_count++)];
  if (t.body != body) {  // the slot held another body's touch
    t.last_nodes.clear();
    t.ring_tangent = Vec3::Zero();
  }
  t.body = body;
  t.point = hit.point;
  // The surface's normal at rest at the touched point (its corners' normals interpolated), carried
  // by the body: the way the pad presses, which the dent it makes does not turn (the deformed
  // faces under a pad tilt as its points push them) and which turns smoothly from face to face.
  t.normal = s.restNormal(hit.face, barycentric(mesh, hit.face, hit.point));
  t.separation = separation;
  t.feature = hit.feature;
  t.face = hit.face;
  t.weights = barycentric(mesh, hit.face, hit.point);
  t.first_press = static_cast<int>(soft_presses.size());
  t.radius = 0.0;
  t.press_depth = (f.device.position - c).dot(-t.normal);
  t.patch.valid = false;
  const double friction = f.settings.friction_effect ? f.settings.patch.friction : 0.0;
  if (f.settings.patch.model == ContactModel::kGodFinger) {
    PatchContact pc{hit.point, t.normal, separation, 0.0, t.ring_tangent, Vec3::Zero()};
    computePatch(mesh, pc, f.device.position - c, f.settings.patch, t.patch);
  }
  soft_nodes.clear();
  if (t.patch.valid && !t.patch.sgos.empty()) padNodes(t, s, fd.soft_walk_fill);
  // A god-object (or a patch that presses no node): the one point nearest the proxy, out of its
  // sphere.
  if (!t.patch.valid || t.patch.sgos.empty() || soft_nodes.empty()) {
    const Vec3 towards = hit.point - c;
    const Vec3 n = outside && towards.norm() > 1e-12 ? Vec3(towards.normalized()) : Vec3(-t.normal);
    // How far the point must move along n to leave the sphere: r - d outside, r + d with the
    // centre inside the body.
    soft_presses.push_back({fi, hit.face, -1, t.weights, n, radius - towards.dot(n), friction, -1});
    t.press_count = 1;
    t.centre_press = true;
    t.last_nodes.clear();
    return;
  }
  t.centre_press = false;
  t.radius = t.patch.radius;
  t.ring_tangent = t.patch.ring_tangent;
  const bool round = fd.soft_imprint == SoftImprint::kRound;
  for (int node : soft_nodes) {
    const Vec3& x = s.nodes()[static_cast<std::size_t>(node)];
    const Vec3 towards = x - c;
    const Vec3 n = round && towards.norm() > 1e-12 ? Vec3(towards.normalized()) : Vec3(-t.normal);
    const double depth = round ? radius - towards.norm() : towards.dot(t.normal) + radius;
    soft_presses.push_back({fi, -1, node, Vec3(1.0, 0.0, 0.0), n, depth, friction, node});
  }
  t.press_count = static_cast<int>(soft_presses.size()) - t.first_press;
  t.last_nodes.assign(soft_nodes.begin(), soft_nodes.end());
}

// The surface nodes a god-finger's pad presses (into `soft_nodes`): those of the faces its patch
// reached, each within the patch's outline (its walk lengths, interpolated by angle about the
// contact in the pad's plane).
void World::Impl::padNodes(const SoftTouch& t, const SoftBody& s, double walk_fill) {
  const Mesh& mesh = s.surface();
  const Patch& p = t.patch;
  soft_faces.clear();
  soft_faces.push_back(p.hit.face);
  for (const Sgo& g : p.sgos) soft_faces.push_back(g.face);
  for (const Sgo& g : p.inner) soft_faces.push_back(g.face);
  if (walk_fill > 0.0) {  // points every walk_fill along each walked path, located on the surface
    for (std::size_t k = 0; k + 1 < p.path_offsets.size(); ++k) {
      Vec3 from = t.point;
      double carried = 0.0;
      for (std::int32_t i = p.path_offsets[k]; i < p.path_offsets[k + 1]; ++i) {
        const Vec3 to = p.path_points[static_cast<std::size_t>(i)];
        const double length = (to - from).norm();
        for (double at = walk_fill - carried; at < length && soft_faces.size() < kMaxPadFaces; at += walk_fill) {
          soft_faces.push_back(mesh.closestPoint(from + (to - from) * (at / length), 1e-9).face);
        }
        carried = length > 0.0 ? std::fmod(carried + length, walk_fill) : carried;
        from = to;
      }
    }
  }
  // The outline: each SGO's angle about the contact in the pad's plane and its reach across
  // the normal, in order of angle.
  const Vec3 n = t.normal;
  const Vec3 e0 = (p.ring_tangent - p.ring_tangent.dot(n) * n).normalized(), e1 = n.cross(e0);
  const auto polar = [&](const Vec3& x) {
    const Vec3 r = x - t.point, lateral = r - r.dot(n) * n;
    const double angle = std::atan2(lateral.dot(e1), lateral.dot(e0));
    return std::pair<double, double>(angle < 0.0 ? angle + 2.0 * std::numbers::pi : angle, lateral.norm());
  };
  soft_outline.clear();
  for (const Sgo& g : p.sgos) soft_outline.push_back(polar(g.position));
  std::sort(soft_outline.begin(), soft_outline.end());
  const auto within = [&](const Vec3& x, double scale) {
    const auto [angle, distance] = polar(x);
    const auto next = std::lower_bound(soft_outline.begin(), soft_outline.end(), std::pair<double, double>(angle, -1.0));
    const auto& b = next == soft_outline.end() ? soft_outline.front() : *next;
    const auto& a = next == soft_outline.begin() ? soft_outline.back() : *(next - 1);
    double span = b.first - a.first, from = angle - a.first;
    if (span <= 0.0) span += 2.0 * std::numbers::pi;
    if (from < 0.0) from += 2.0 * std::numbers::pi;
    const double u = span > 0.0 ? std::clamp(from / span, 0.0, 1.0) : 0.0;
    return distance <= scale * ((1.0 - u) * a.second + u * b.second) + 1e-9;
  };
  soft_nodes.clear();
  for (int face : soft_faces) {
    if (face < 0) continue;
    for (int k = 0; k < 3; ++k) {
      const int node = s.surfaceNode(mesh.triangles()[static_cast<std::size_t>(face)][static_cast<std::size_t>(k)]);
      if (std::find(soft_nodes.begin(), soft_nodes.end(), node) != soft_nodes.end()) continue;
      // A node the pad pressed in the last step stays pressed within a fifth more of the
      // outline: nodes at its edge would otherwise come and go as the dent moves them.
      const bool kept = std::find(t.last_nodes.begin(), t.last_nodes.end(), node) != t.last_nodes.end();
      if (within(s.nodes()[static_cast<std::size_t>(node)], kept ? 1.2 : 1.0)) soft_nodes.push_back(node);
    }
  }
  if (soft_nodes.size() >= 3) return;
  // A mesh coarser than the patch: every node of the faces it reached (around the contact, they
  // stay the same from step to step where the contact's own face turns about a vertex).
  soft_nodes.clear();
  for (int face : soft_faces) {
    if (face < 0) continue;
    for (int k = 0; k < 3; ++k) {
      const int node = s.surfaceNode(mesh.triangles()[static_cast<std::size_t>(face)][static_cast<std::size_t>(k)]);
      if (std::find(soft_nodes.begin(), soft_nodes.end(), node) == soft_nodes.end()) soft_nodes.push_back(node);
    }
  }
}

void World::Impl::stepSoftBodies(double dt) {
  if (soft_bodies.empty()) return;
  for (Finger& f : fingers) f.soft_count = 0;
  const PadBodies surfaces(*this);
  const Vec3 gravity = desc.effects.gravity ? desc.world.gravity : Vec3::Zero();
  soft_fingers.resize(fingers.size());
  std::vector<char>& given = soft_given;  // the coupling's force goes to the first body a finger presses
  given.assign(fingers.size(), 0);
  for (int body : soft_bodies) {
    SoftBody& s = *bodies[static_cast<std::size_t>(body)].soft;
    soft_presses.clear();
    for (std::size_t i = 0; i < fingers.size(); ++i) {
      Finger& f = fingers[i];
      const int before = f.soft_count;
      touchSoft(f, static_cast<int>(i), body);
      // The coupling's force goes to the first body the finger presses (a press inside its pad),
      // not one it only comes within the touch margin of.
      bool presses = false;
      if (f.soft_count > before) {
        const SoftTouch& t = f.soft[static_cast<std::size_t>(before)];
        for (int p = t.first_press; p < t.first_press + t.press_count; ++p) presses = presses || soft_presses[static_cast<std::size_t>(p)].depth > 0.0;
      }
      const bool first = presses && !given[i];
      soft_fingers[i] = {desc.fingers[i].proxy.mass, toEigen(f.proxy->getLinearVelocity()), first ? f.force : Vec3::Zero()};
      given[i] = given[i] || first;
    }
    s.step(dt, gravity, surfaces, soft_fingers, soft_presses);
    readSoftStep(body, s, dt);
  }
}

// What body `body`'s step did: each touch's loads, the presses' forces on the proxies (Bullet
// then moves them on at the velocity the step solved), the surface's on the rigid bodies.
void World::Impl::readSoftStep(int body, SoftBody& s, double dt) {
  (void)dt;
  counters.soft_resets += s.undone() ? 1 : 0;
  for (std::size_t i = 0; i < fingers.size(); ++i) {
    Finger& f = fingers[i];
    for (int k = 0; k < f.soft_count; ++k) {
      SoftTouch& t = f.soft[static_cast<std::size_t>(k)];
      if (t.body != body) continue;
      t.force = Vec3::Zero();
      t.sgos.clear();
      t.loads.clear();
      t.sliding = true;
      for (int p = t.first_press; p < t.first_press + t.press_count && !s.undone(); ++p) {
        const SoftPressResult& r = s.pressResults()[static_cast<std::size_t>(p)];
        const double load = std::max(0.0, -r.force.dot(t.normal));
        t.sgos.push_back(r.point);
        t.loads.push_back(PointLoad{load, r.force + load * t.normal, r.slipping});
        t.force += r.force;
        t.sliding = t.sliding && (r.slipping || load == 0.0);
      }
      t.indentation = (s.restPoint(t.face, t.weights) - t.point).dot(t.normal);  // sunk: > 0
      if (s.undone()) {  // the step was undone: the fingers that pressed are held where they are
        f.proxy->clearForces();
        f.proxy->setLinearVelocity(btVector3(0, 0, 0));
      } else {
        f.proxy->applyCentralForce(toBt(Vec3(-t.force)));
      }
    }
  }
  for (const PadNodeContact& c : s.surfaceContacts()) {
    btRigidBody& r = *bodies[static_cast<std::size_t>(c.body)].rigid;
    if (r.getInvMass() > 0.0) r.applyForce(toBt(c.force), toBt(c.point) - r.getCenterOfMassPosition());
  }
}

void World::Impl::softSnapshot(const Finger& f, FingerSnapshot& out) const {
  for (int k = 0; k < f.soft_count; ++k) {
    const SoftTouch& t = f.soft[static_cast<std::size_t>(k)];
    ContactSnapshot& s = out.contacts.emplace_back();
    s.body = t.body;
    s.point_world = t.point;
    s.outward_normal_world = t.normal;
    s.separation = t.separation;
    s.press_depth = t.press_depth;
    s.radius = t.radius;
    s.feature = t.feature;
    s.force = t.force;
    s.indentation = t.indentation;
    s.sliding = t.sliding;
    // A god-object's one press is the contact point's; a god-finger's are its pad's nodes.
    const std::size_t first = t.centre_press && !t.loads.empty() ? 1 : 0;
    s.point_load = first ? t.loads.front() : PointLoad{};
    s.point_loaded = first != 0 || t.loads.empty();
    s.sgos_world.assign(t.sgos.begin() + static_cast<std::ptrdiff_t>(first), t.sgos.end());
    s.loads.assign(t.loads.begin() + static_cast<std::ptrdiff_t>(first), t.loads.end());
    s.path_points_world = t.patch.valid ? t.patch.path_points : std::vector<Vec3>{};
    s.path_offsets = t.patch.valid ? t.patch.path_offsets : std::vector<std::int32_t>{};
  }
}

void World::Impl::softBodySnapshot(Snapshot& out) const {
  out.soft_bodies.resize(soft_bodies.size());
  for (std::size_t k = 0; k < soft_bodies.size(); ++k) {
    const SoftBody& s = *bodies[static_cast<std::size_t>(soft_bodies[k])].soft;
    SoftBodySnapshot& o = out.soft_bodies[k];
    o.body = soft_bodies[k];
    o.nodes = s.nodes();
    o.surface = s.surfaceTriangles();
    o.resets = s.resets();
  }
}

}  // namespace gf::sim
