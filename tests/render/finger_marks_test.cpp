// The marks of a finger's device in the overlay's draw list, without GL: the pad's outline and
// the tilt marker turn with the device, a disc finger's marker shows only a turned device, and
// the fingertip is drawn only on request, as one closed capsule wound outward.
#include "render/scene/finger_marks.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "render/scene/draw_list.hpp"

namespace gf::render {
namespace {

using sim::Vec3;

constexpr double kRadius = 0.008;  // m: the proxy's
const Vec3 kProxy(0.01, 0.05, -0.02);

// One finger at kProxy whose device is turned by `turn`, with an oriented or a disc pad.
struct OneFinger {
  sim::SceneDesc scene;
  sim::Snapshot snapshot;
  OneFinger(const sim::Quat& turn, sim::PadModel pad) {
    sim::FingerDesc f;
    f.proxy.radius = kRadius;
    f.patch.pad_model = pad;
    scene.fingers.push_back(f);
    sim::FingerSnapshot& s = snapshot.fingers.emplace_back();
    s.proxy = kProxy;
    s.device = kProxy;
    s.device_orientation = turn;
    s.patch = f.patch;
  }
  DrawList build(const DrawSettings& settings = {}) const {
    DrawListBuilder builder(scene, {});
    DrawList list;
    builder.build(snapshot, settings, list);
    return list;
  }
};

std::vector<const DrawItem*> itemsOf(const DrawList& list, DrawPass pass, DrawShape shape) {
  std::vector<const DrawItem*> out;
  for (const DrawItem& item : list.items) {
    if (item.pass == pass && item.shape == shape) out.push_back(&item);
  }
  return out;
}

Vec3 positionOf(const Vertex& v) { return Vec3(v.position[0], v.position[1], v.position[2]); }

sim::Quat aboutX(double degrees) { return sim::Quat(Eigen::AngleAxisd(degrees * std::numbers::pi / 180.0, Vec3::UnitX())); }

// The stalk's unit cylinder runs along its model's y column from its translation.
Vec3 stalkAxis(const DrawItem& stalk) { return stalk.model.block<3, 1>(0, 1).cast<double>().normalized(); }
Vec3 stalkBase(const DrawItem& stalk) { return stalk.model.block<3, 1>(0, 3).cast<double>(); }

// Flat and tilted 75 degrees about x (orientation-track's end): the stalk leaves the sphere along
// the device's up axis, the pad's outline lies across it on the pad's side, narrowing as it
// turns: seen from above (y), the flat ring is round, the tilted one a quarter as deep.
TEST(FingerMarks, TheTiltMarkerAndPadOutlineTurnWithTheDevice) {
  for (const double degrees : {0.0, 75.0}) {
    const sim::Quat turn = aboutX(degrees);
    const Vec3 up = turn * Vec3::UnitY();
    const DrawList list = OneFinger(turn, sim::PadModel::kOriented).build();
    const std::vector<const DrawItem*> stalks = itemsOf(list, DrawPass::kMarks, DrawShape::kCylinder);
    ASSERT_EQ(stalks.size(), 1u) << degrees;
    EXPECT_NEAR((stalkAxis(*stalks[0]) - up).norm(), 0.0, 1e-6) << degrees;
    EXPECT_NEAR((stalkBase(*stalks[0]) - (kProxy + kRadius * up)).norm(), 0.0, 1e-8) << degrees;
    EXPECT_EQ(itemsOf(list, DrawPass::kMarks, DrawShape::kCone).size(), 1u);
    EXPECT_EQ(itemsOf(list, DrawPass::kMarks, DrawShape::kDot).size(), 1u) << "the twist bead";
    const std::vector<const DrawItem*> rings = itemsOf(list, DrawPass::kMarks, DrawShape::kTriangles);
    ASSERT_EQ(rings.size(), 1u) << degrees;
    Vec3 centre = Vec3::Zero();
    double depth_z = 0.0, width_x = 0.0;
    for (int k = rings[0]->first; k < rings[0]->first + rings[0]->count; ++k) {
      const Vec3 p = positionOf(list.vertices[static_cast<std::size_t>(k)]);
      centre += p / rings[0]->count;
      depth_z = std::max(depth_z, std::abs(p.z() - kProxy.z()));
      width_x = std::max(width_x, std::abs(p.x() - kProxy.x()));
    }
    // Its centre on the pad's side at 40 degrees from the axis on a sphere a tube's radius
    // larger than the proxy (the ring lies on it).
    const double tube = kMarkWidthShare * kRadius, lift = kRadius + tube;
    const Vec3 expected_centre = kProxy - lift * std::cos(kPadOutlineAngle) * up;
    EXPECT_NEAR((centre - expected_centre).norm(), 0.0, 1e-6 * kRadius) << degrees;
    // Seen from above: as wide across x always (the ring's radius and its tube); along z the
    // ring's radius shrunk by cos(tilt), plus the centre's shift and the tube. 3 %: the ring is
    // 40 straight pieces, its tube 6.
    const double rho = lift * std::sin(kPadOutlineAngle), tilt = degrees * std::numbers::pi / 180.0;
    EXPECT_NEAR(width_x / (rho + tube), 1.0, 0.03) << degrees;
    const double expected_z = rho * std::cos(tilt) + lift * std::cos(kPadOutlineAngle) * std::sin(tilt) + tube;
    EXPECT_NEAR(depth_z / expected_z, 1.0, 0.03) << degrees;
  }
}

// A twist about the pad axis moves the bead around the outline and leaves the stalk alone.
TEST(FingerMarks, ATwistTurnsTheBead) {
  const auto bead = [](const sim::Quat& turn) {
    const DrawList list = OneFinger(turn, sim::PadModel::kOriented).build();
    const std::vector<const DrawItem*> dots = itemsOf(list, DrawPass::kMarks, DrawShape::kDot);
    EXPECT_EQ(dots.size(), 1u);
    return Vec3(dots[0]->model.block<3, 1>(0, 3).cast<double>() - kProxy);
  };
  const Vec3 flat = bead(sim::Quat::Identity());
  const Vec3 twisted = bead(sim::Quat(Eigen::AngleAxisd(0.5 * std::numbers::pi, Vec3::UnitY())));
  EXPECT_GT(flat.x(), 0.5 * kRadius) << "on the device's +x side";
  // A quarter turn about y takes +x to -z.
  EXPECT_NEAR(twisted.z(), -flat.x(), 1e-8);
  EXPECT_NEAR(twisted.x(), 0.0, 1e-8);
}

// A disc pad's contact ignores the device's turn: no outline, and a marker only while the
// device is turned (then along its up axis); no mark at all while it is not.
TEST(FingerMarks, ADiscFingerShowsOnlyATurnedDevice) {
  const DrawList flat = OneFinger(sim::Quat::Identity(), sim::PadModel::kDisc).build();
  EXPECT_TRUE(itemsOf(flat, DrawPass::kMarks, DrawShape::kCylinder).empty());
  EXPECT_TRUE(itemsOf(flat, DrawPass::kMarks, DrawShape::kTriangles).empty());
  const sim::Quat turn = aboutX(30.0);
  const DrawList turned = OneFinger(turn, sim::PadModel::kDisc).build();
  const std::vector<const DrawItem*> stalks = itemsOf(turned, DrawPass::kMarks, DrawShape::kCylinder);
  ASSERT_EQ(stalks.size(), 1u);
  EXPECT_NEAR((stalkAxis(*stalks[0]) - turn * Vec3::UnitY()).norm(), 0.0, 1e-6);
  EXPECT_TRUE(itemsOf(turned, DrawPass::kMarks, DrawShape::kTriangles).empty()) << "no pad outline";
}

// The proxy is a sphere unless a fingertip is asked for; then one translucent capsule whose
// lower end is the proxy sphere and whose body goes up the device's axis 2.5 radii, every
// triangle facing outward (the proxies' pass culls back faces), a nail on its back (the
// device's -z side), and no stalk (the body shows the tilt).
TEST(FingerMarks, TheFingertipIsDrawnOnlyOnRequest) {
  const sim::Quat turn = aboutX(40.0);
  const Vec3 up = turn * Vec3::UnitY();
  const OneFinger finger(turn, sim::PadModel::kOriented);
  const DrawList spheres = finger.build();
  EXPECT_EQ(itemsOf(spheres, DrawPass::kProxies, DrawShape::kSphere).size(), 1u);
  EXPECT_TRUE(itemsOf(spheres, DrawPass::kProxies, DrawShape::kTriangles).empty());
  DrawSettings settings;
  settings.proxy = view::ProxyLook::kFingertip;
  const DrawList tip = finger.build(settings);
  const std::vector<const DrawItem*> capsule = itemsOf(tip, DrawPass::kProxies, DrawShape::kTriangles);
  ASSERT_EQ(capsule.size(), 1u);
  const std::vector<const DrawItem*> nail = itemsOf(tip, DrawPass::kProxies, DrawShape::kSphere);
  ASSERT_EQ(nail.size(), 1u);
  const Vec3 nail_at = nail[0]->model.block<3, 1>(0, 3).cast<double>() - kProxy;
  EXPECT_GT(nail_at.dot(turn * -Vec3::UnitZ()), 0.8 * kRadius) << "on the device's -z side";
  EXPECT_TRUE(itemsOf(tip, DrawPass::kMarks, DrawShape::kCylinder).empty());
  double lowest = 1.0, highest = -1.0;
  int inward = 0;
  for (int k = capsule[0]->first; k < capsule[0]->first + capsule[0]->count; k += 3) {
    Vec3 p[3];
    for (int c = 0; c < 3; ++c) p[c] = positionOf(tip.vertices[static_cast<std::size_t>(k + c)]) - kProxy;
    for (const Vec3& q : p) {
      // Every point a radius from the axis segment [0, 2.5 r] along up.
      const double along = std::clamp(q.dot(up), 0.0, kFingertipLengthShare * kRadius);
      EXPECT_NEAR((q - along * up).norm(), kRadius, 1e-6);
      lowest = std::min(lowest, q.dot(up));
      highest = std::max(highest, q.dot(up));
    }
    const Vec3 face = (p[1] - p[0]).cross(p[2] - p[0]);
    const Vec3 mid = (p[0] + p[1] + p[2]) / 3.0;
    const Vec3 out = mid - std::clamp(mid.dot(up), 0.0, kFingertipLengthShare * kRadius) * up;
    inward += face.norm() > 1e-14 && face.dot(out) < 0.0;
  }
  EXPECT_NEAR(lowest, -kRadius, 1e-6);
  EXPECT_NEAR(highest, (1.0 + kFingertipLengthShare) * kRadius, 1e-6);
  EXPECT_EQ(inward, 0);
  EXPECT_NEAR(fingerReach(finger.snapshot.fingers[0], kRadius, view::ProxyLook::kFingertip),
              (1.0 + kFingertipLengthShare) * kRadius, 1e-12);
}

// Without fingers (close-ups) nothing of a finger is drawn, its marks included.
TEST(FingerMarks, CloseUpsLeaveThemOut) {
  DrawSettings settings;
  settings.fingers = false;
  settings.proxy = view::ProxyLook::kFingertip;
  const DrawList list = OneFinger(aboutX(75.0), sim::PadModel::kOriented).build(settings);
  EXPECT_TRUE(list.items.empty());
}

}  // namespace
}  // namespace gf::render
