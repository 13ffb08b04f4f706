// The fem_pad fingers' soft pads in the World: each pad built on its finger's proxy (the bone),
// stepped before Bullet's step against the bodies' walk meshes, its contacts' forces put on the
// bodies for that step and the bone's velocity given to the proxy, which Bullet then moves (its
// own contacts stop a bone pressed through the pad). The pad follows the proxy at the next
// step's start. Rigid scenes build none of this.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "sim/world/world_impl.hpp"

namespace gf::sim {

// The World's bodies as a pad asks for them: their Bullet bounds, their walk meshes (in the body
// frame, bodyFrame) and their velocities.
class World::Impl::PadBodies final : public PadSurfaces {
 public:
  explicit PadBodies(const Impl& w) : w_(w) {}

  void near(const Vec3& lo, const Vec3& hi, std::vector<int>& out) const override {
    out.clear();
    for (std::size_t i = 0; i < w_.bodies.size(); ++i) {
      btVector3 a, b;
      w_.bodies[i].rigid->getAabb(a, b);
      if ((toEigen(a).cwiseMax(lo).array() <= toEigen(b).cwiseMin(hi).array()).all()) out.push_back(static_cast<int>(i));
    }
  }

  bool inside(int body, const Vec3& p, double& depth, Vec3& normal) const override {
    const Mesh& mesh = *w_.bodies[static_cast<std::size_t>(body)].shapes.walk_mesh;
    const Pose frame = w_.bodyFrame(body);
    const Vec3 local = frame.orientation.conjugate() * (p - frame.position);
    const SurfacePoint hit = mesh.closestPoint(local, kFeatureTolerance);
    if (hit.face < 0) return false;
    const Vec3 d = local - hit.point;
    if (!below(mesh, hit, d)) return false;
    depth = d.norm();
    const Vec3 n = hit.feature == Feature::kFace || depth < kFeatureTolerance ? mesh.faceNormal(hit.face) : Vec3(-d / depth);
    normal = frame.orientation * n;
    return depth > 0.0;
  }

  Pose frame(int body) const override { return w_.bodyFrame(body); }

  double mass(int body) const override {
    const double inverse = w_.bodies[static_cast<std::size_t>(body)].rigid->getInvMass();
    return inverse > 0.0 ? 1.0 / inverse : 0.0;
  }

  Vec3 velocity(int body) const override { return toEigen(w_.bodies[static_cast<std::size_t>(body)].rigid->getLinearVelocity()); }

  Vec3 velocityAt(int body, const Vec3& p) const override {
    const btRigidBody& r = *w_.bodies[static_cast<std::size_t>(body)].rigid;
    return toEigen(r.getVelocityInLocalPoint(toBt(p) - r.getCenterOfMassPosition()));
  }

 private:
  static constexpr double kFeatureTolerance = 1e-9;  // m

  // `d` (from the closest point to the query, body frame) points into the solid: below every
  // face at the closest feature (one face, an edge's two, a corner's fan).
  static bool below(const Mesh& mesh, const SurfacePoint& hit, const Vec3& d) {
    const auto under = [&](int face) { return face < 0 || d.dot(mesh.faceNormal(face)) < 0.0; };
    if (!under(hit.face)) return false;
    if (hit.feature == Feature::kEdge) return under(mesh.link(hit.face, hit.feature_index).face);
    if (hit.feature == Feature::kVertex) {
      const int v = mesh.triangles()[static_cast<std::size_t>(hit.face)][static_cast<std::size_t>(hit.feature_index)];
      return std::all_of(mesh.vertexFacesBegin(v), mesh.vertexFacesEnd(v), under);
    }
    return true;
  }

  const Impl& w_;
};

void World::Impl::addPad(Finger& f, const FingerDesc& d) {
  f.pad = std::make_unique<FemPad>(d.pad, d.proxy.radius, d.proxy.mass, d.patch.pad_axis, f.device.position);
}

void World::Impl::stepPads(double dt) {
  const PadBodies surfaces(*this);
  const bool push = desc.world.overlap == OverlapMode::kPushApart;
  for (Finger& f : fingers) {
    if (!f.pad) continue;
    const long resets = f.pad->resets();
    f.pad->follow(toEigen(f.proxy->getCenterOfMassPosition()), toEigen(f.proxy->getLinearVelocity()));
    f.pad->step(dt, push ? Vec3(f.force + f.overlap_push) : f.force, f.settings.patch.friction, surfaces);
    counters.pad_resets += f.pad->resets() - resets;
    for (const PadNodeContact& c : f.pad->contacts()) {
      btRigidBody& r = *bodies[static_cast<std::size_t>(c.body)].rigid;
      if (r.getInvMass() > 0.0) r.applyForce(toBt(c.force), toBt(c.point) - r.getCenterOfMassPosition());
    }
    // The coupling pushed the bone in the pad's step; Bullet moves it on at that velocity.
    f.proxy->clearForces();
    f.proxy->setLinearVelocity(toBt(f.pad->boneVelocity()));
  }
}

int World::Impl::padTouches(const Finger& f, std::array<PadTouch, kMaxContactsPerFinger>& out) const {
  int count = 0;
  for (const PadNodeContact& c : f.pad->contacts()) {
    int k = 0;
    while (k < count && out[static_cast<std::size_t>(k)].body != c.body) ++k;
    if (k == count) {
      if (count == kMaxContactsPerFinger) continue;
      out[static_cast<std::size_t>(count++)] = PadTouch{c.body, 0, Vec3::Zero(), 0.0, Vec3::Zero(), Vec3::Zero(), 0.0, Vec3::Zero(), Vec3::UnitY(), 0.0, true};
    }
    PadTouch& t = out[static_cast<std::size_t>(k)];
    const double load = std::max(0.0, -c.force.dot(c.normal));
    ++t.nodes;
    t.force += c.force;
    t.load += load;
    t.point += (load + 1e-12) * c.point;  // weights: the loads, or the count where none
    t.normal += (load + 1e-12) * c.normal;
    if (c.depth >= t.depth) {
      t.depth = c.depth;
      t.deepest_point = c.point + c.depth * c.normal;
      t.deepest_normal = c.normal;
    }
    t.area += c.area;
    t.sliding = t.sliding && c.slipping;
  }
  for (int k = 0; k < count; ++k) {
    PadTouch& t = out[static_cast<std::size_t>(k)];
    t.point /= t.load + 1e-12 * t.nodes;
    t.normal.normalize();
  }
  return count;
}

void World::Impl::padSnapshot(const Finger& f, FingerSnapshot& out) const {
  const FemPad& pad = *f.pad;
  out.pad.nodes = pad.nodes();
  out.pad.skin = pad.skin();
  out.pad.bone_radius = pad.boneRadius();
  out.pad.resets = pad.resets();
  std::array<PadTouch, kMaxContactsPerFinger> touches;
  const int count = padTouches(f, touches);
  const std::size_t first = out.contacts.size();
  out.contacts.resize(first + static_cast<std::size_t>(count));
  for (int k = 0; k < count; ++k) {
    const PadTouch& t = touches[static_cast<std::size_t>(k)];
    ContactSnapshot& s = out.contacts[first + static_cast<std::size_t>(k)];
    s.body = t.body;
    s.point_world = t.point;
    s.outward_normal_world = t.normal;
    s.separation = -t.depth;
    // How far the undeformed skin would reach into the body's tangent plane at the contact.
    s.press_depth = std::max(0.0, pad.boneRadius() + desc.fingers[static_cast<std::size_t>(&f - fingers.data())].pad.thickness -
                                      (pad.boneCentre() - t.point).dot(t.normal));
    s.radius = std::sqrt(t.area / std::numbers::pi);
    s.feature = Feature::kFace;
    s.force = t.force;
    s.point_load = PointLoad{};
    s.rolling_moment = Vec3::Zero();
    s.sliding = t.sliding;
    s.sgos_world.clear();
    s.loads.clear();
    s.path_points_world.clear();
    s.path_offsets.clear();
    for (const PadNodeContact& c : pad.contacts()) {
      if (c.body != t.body) continue;
      const double load = std::max(0.0, -c.force.dot(c.normal));
      s.sgos_world.push_back(c.point);
      s.loads.push_back(PointLoad{load, c.force + load * c.normal, c.slipping});
    }
  }
}

}  // namespace gf::sim
