#include "render/state/same_picture.hpp"

#include "render/state/contact_load.hpp"

#include <algorithm>
#include <cmath>

namespace gf::render {
namespace {

constexpr double kTol = kSamePictureTolerance;

// Lengths and unit vectors; false for NaN (drawn again).
bool near(double a, double b) { return std::abs(a - b) <= kTol; }
bool near(const sim::Vec3& a, const sim::Vec3& b) { return near(a.x(), b.x()) && near(a.y(), b.y()) && near(a.z(), b.z()); }
bool near(const sim::Quat& a, const sim::Quat& b) {
  return near(a.x(), b.x()) && near(a.y(), b.y()) && near(a.z(), b.z()) && near(a.w(), b.w());
}
// Forces and moments, relative to their size.
bool nearLoad(double a, double b) {
  return std::abs(a - b) <= kSameLoadShare * std::max(std::abs(a), std::abs(b)) + kSameLoadFloor;
}
bool nearLoad(const sim::Vec3& a, const sim::Vec3& b) {
  return (a - b).norm() <= kSameLoadShare * std::max(a.norm(), b.norm()) + kSameLoadFloor;
}

// A contact's moment about its normal, relative to the largest of it and its force times its
// radius: the torsion arc shows it against mu F_n r, so a moment far below that (a held pinch's
// 1e-8 N m) drawn again for every rounding of the centre of pressure would redraw nothing seen.
bool nearTorsion(const sim::ContactSnapshot& a, const sim::ContactSnapshot& b) {
  const double ta = contactTorsion(a), tb = contactTorsion(b);
  const double scale = std::max(a.force.norm(), b.force.norm()) * std::max(a.radius, b.radius);
  return std::abs(ta - tb) <= kSameLoadShare * std::max({std::abs(ta), std::abs(tb), scale}) + kSameLoadFloor;
}

template <class T, class Same>
bool all(const std::vector<T>& a, const std::vector<T>& b, Same same) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (!same(a[i], b[i])) return false;
  }
  return true;
}

bool nearVec3s(const std::vector<sim::Vec3>& a, const std::vector<sim::Vec3>& b) {
  return all(a, b, [](const sim::Vec3& x, const sim::Vec3& y) { return near(x, y); });
}

bool sameLoad(const sim::PointLoad& a, const sim::PointLoad& b) {
  return nearLoad(a.normal, b.normal) && nearLoad(a.tangential, b.tangential) && a.slipping == b.slipping;
}
// Without load arrows a point's friction is drawn only through the contact's torsion arc.
bool samePressing(const sim::PointLoad& a, const sim::PointLoad& b) {
  return nearLoad(a.normal, b.normal) && a.slipping == b.slipping;
}

bool sameContact(const sim::ContactSnapshot& a, const sim::ContactSnapshot& b, bool load_arrows) {
  return a.body == b.body && a.feature == b.feature && a.point_loaded == b.point_loaded && a.sliding == b.sliding &&
         near(a.point_world, b.point_world) && near(a.outward_normal_world, b.outward_normal_world) &&
         near(a.separation, b.separation) && near(a.press_depth, b.press_depth) && near(a.radius, b.radius) &&
         nearLoad(a.force, b.force) && nearLoad(a.rolling_moment, b.rolling_moment) &&
         nearLoad(a.torsion_moment, b.torsion_moment) && near(a.indentation, b.indentation) &&
         a.path_offsets == b.path_offsets && nearVec3s(a.sgos_world, b.sgos_world) &&
         nearVec3s(a.path_points_world, b.path_points_world) &&
         (load_arrows ? sameLoad(a.point_load, b.point_load) && all(a.loads, b.loads, sameLoad)
                      : samePressing(a.point_load, b.point_load) && all(a.loads, b.loads, samePressing) &&
                            nearTorsion(a, b));
}

bool samePlace(const sim::FingerSnapshot& a, const sim::FingerSnapshot& b) {
  return a.patch == b.patch && near(a.device, b.device) && near(a.device_orientation, b.device_orientation) &&
         near(a.proxy, b.proxy) && a.pad.skin == b.pad.skin && near(a.pad.bone_radius, b.pad.bone_radius) &&
         nearVec3s(a.pad.nodes, b.pad.nodes);
}

// What a finger draws beyond its place (samePlace): its contacts and forces.
bool sameLoads(const sim::FingerSnapshot& a, const sim::FingerSnapshot& b, bool load_arrows) {
  return a.sgo_count == b.sgo_count && a.pad.resets == b.pad.resets &&
         nearLoad(a.coupling_force, b.coupling_force) && nearLoad(a.feedback_force, b.feedback_force) &&
         all(a.contacts, b.contacts,
             [&](const sim::ContactSnapshot& x, const sim::ContactSnapshot& y) { return sameContact(x, y, load_arrows); });
}

bool sameSoftBody(const sim::SoftBodySnapshot& a, const sim::SoftBodySnapshot& b) {
  return a.body == b.body && a.surface == b.surface && a.resets == b.resets && nearVec3s(a.nodes, b.nodes);
}

bool samePose(const sim::Pose& a, const sim::Pose& b) {
  return near(a.position, b.position) && near(a.orientation, b.orientation);
}

}  // namespace

bool samePlaces(const sim::Snapshot& a, const sim::Snapshot& b) {
  return all(a.bodies, b.bodies, samePose) && all(a.fingers, b.fingers, samePlace) &&
         all(a.soft_bodies, b.soft_bodies, sameSoftBody);
}

bool drawsTheSame(const sim::Snapshot& a, const sim::Snapshot& b, bool load_arrows) {
  return samePlaces(a, b) &&
         all(a.fingers, b.fingers,
             [&](const sim::FingerSnapshot& x, const sim::FingerSnapshot& y) { return sameLoads(x, y, load_arrows); });
}

}  // namespace gf::render
