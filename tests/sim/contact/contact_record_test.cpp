// The contact record and the one function that puts it into a snapshot: every part of it is
// transformed with the same pose.
#include "sim/contact/contact_record.hpp"

#include <gtest/gtest.h>

#include "sim/mesh/primitives.hpp"

namespace gf::sim {
namespace {

// A real patch on the top face of a box, in the box's frame.
ContactRecord pressedBoxRecord() {
  static const Mesh box = tessellateBox(Vec3(0.05, 0.02, 0.05), 4);
  ContactRecord r;
  r.body = 3;
  r.contact = {Vec3(0.01, 0.02, -0.005), Vec3::UnitY(), -2e-4};
  const Vec3 v(0.001, -0.004, 0.0);
  r.press_depth = pressDepth(v, r.contact.outward_normal_local);
  computePatch(box, r.contact, v, PatchSettings{}, r.patch);
  return r;
}

TEST(ContactRecord, OnePoseMovesPointNormalSgosAndPathsTogether) {
  const ContactRecord r = pressedBoxRecord();
  ASSERT_EQ(r.patch.sgos.size(), 8u);
  Pose pose;
  pose.position = Vec3(0.3, -0.1, 0.2);
  pose.orientation = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized());
  ContactSnapshot c;
  toContactSnapshot(r, pose, c);
  EXPECT_EQ(c.body, 3);
  EXPECT_DOUBLE_EQ(c.press_depth, 0.004);
  EXPECT_DOUBLE_EQ(c.separation, -2e-4);
  EXPECT_DOUBLE_EQ(c.radius, r.patch.radius);
  EXPECT_NEAR((c.point_world - (pose.orientation * r.contact.point_local + pose.position)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((c.outward_normal_world - pose.orientation * Vec3::UnitY()).norm(), 0.0, 1e-15);
  ASSERT_EQ(c.sgos_world.size(), r.patch.sgos.size());
  ASSERT_EQ(c.path_points_world.size(), r.patch.path_points.size());
  ASSERT_EQ(c.path_offsets, r.patch.path_offsets);
  for (std::size_t k = 0; k < c.sgos_world.size(); ++k) {
    // The SGO is the end of its walked path, in the world as on the body.
    EXPECT_EQ(c.sgos_world[k], c.path_points_world[static_cast<std::size_t>(c.path_offsets[k + 1] - 1)]);
    // Distances within the patch are kept: the transform is rigid.
    EXPECT_NEAR((c.sgos_world[k] - c.point_world).norm(), (r.patch.sgos[k].position - r.contact.point_local).norm(),
                1e-15);
  }
}

TEST(ContactRecord, AGodObjectContactHasPressDepthButNoPatch) {
  ContactRecord r = pressedBoxRecord();
  clearPatch(r.patch);
  ContactSnapshot c = {};
  c.sgos_world.assign(4, Vec3::Ones());  // left from an earlier use of the same storage
  toContactSnapshot(r, Pose{}, c);
  EXPECT_DOUBLE_EQ(c.press_depth, 0.004);
  EXPECT_EQ(c.radius, 0.0);
  EXPECT_TRUE(c.sgos_world.empty());
  EXPECT_TRUE(c.path_points_world.empty());
  EXPECT_TRUE(c.path_offsets.empty());
}

}  // namespace
}  // namespace gf::sim
