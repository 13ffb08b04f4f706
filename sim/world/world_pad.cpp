// The fem_pad fingers' soft pads in the World: each pad built on its finger's proxy (the bone),
// stepped before Bullet's step against the bodies' walk meshes, its contacts' forces put on the
// bodies for that step and the bone's velocity given to the proxy, which Bullet then moves (its
// own contacts stop a bone pressed through the pad). The pad follows the proxy at the next
// step's start. Rigid scenes build none of this.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "sim/world/pad_bodies.hpp"

namespace gf::sim {

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
    s.torsion_moment = Vec3::Zero();
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
