// The overlay's draw list, without GL: what a Fig. 8 squeeze frame holds (patches with their rim
// bands on the cylinder's surface, one dot per SGO where the snapshot puts it, normals and force
// arrows pointing away from the surface, proxies drawn first so the patches show through, ghosts
// and springs), what the switches leave out, and that a rebuild is the same.
#include "render/draw_list.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "app/scene/data_folder.hpp"
#include "app/scene/scene_file.hpp"
#include "render/geometry.hpp"
#include "sim/world.hpp"

namespace gf::render {
namespace {

struct Fig8Frame {
  app::SessionDesc session = app::loadSceneFile(app::resolveScenePath("fig8-pinch-oscillation"));
  sim::Snapshot snapshot;
  std::vector<std::shared_ptr<const sim::Mesh>> surfaces;
  Fig8Frame() {
    sim::World world(session.scene);
    const std::vector<sim::DeviceTrack> devices = sim::deviceTracks(session.scene);
    std::vector<sim::DeviceSample> samples(devices.size());
    for (int k = 0; k < 800; ++k) {  // squeezing, before the lift
      for (std::size_t i = 0; i < devices.size(); ++i) samples[i] = devices[i].sample(world.time());
      world.step(0.001, samples);
    }
    world.snapshot(snapshot);
    for (const sim::BodyDesc& b : session.scene.bodies) surfaces.push_back(bodyRenderMesh(b));
  }
};

std::vector<const DrawItem*> itemsOf(const DrawList& list, DrawPass pass) {
  std::vector<const DrawItem*> out;
  for (const DrawItem& item : list.items) {
    if (item.pass == pass) out.push_back(&item);
  }
  return out;
}

TEST(DrawList, AFig8SqueezeFrameHoldsEveryPartOfTheOverlay) {
  const Fig8Frame frame;
  ASSERT_EQ(frame.snapshot.fingers.size(), 2u);
  DrawListBuilder builder(frame.session.scene, frame.surfaces);
  DrawList list;
  builder.build(frame.snapshot, DrawSettings{}, list);
  // Two proxies; per finger a fill, a rim band, its lines, the contact point and 8 SGO dots, a
  // normal and the force (two pieces each); then two ghosts and one set of spring lines.
  EXPECT_EQ(itemsOf(list, DrawPass::kPatchFill).size(), 2u);
  EXPECT_EQ(itemsOf(list, DrawPass::kPatchRim).size(), 2u);
  EXPECT_EQ(itemsOf(list, DrawPass::kPatchLines).size(), 2u);
  EXPECT_EQ(itemsOf(list, DrawPass::kMarks).size(), 2u * 9u);
  EXPECT_EQ(itemsOf(list, DrawPass::kArrows).size(), 2u * 4u);
  EXPECT_EQ(itemsOf(list, DrawPass::kProxies).size(), 2u);
  EXPECT_EQ(itemsOf(list, DrawPass::kGhosts).size(), 2u);
  ASSERT_EQ(itemsOf(list, DrawPass::kSprings).size(), 1u);
  EXPECT_EQ(itemsOf(list, DrawPass::kSprings)[0]->count, 2 * 2 * 96);  // two coils of 96 segments
  // Drawing order: the proxies (they write no depth, so the patches drawn after show through
  // them), finger 0's patch items, finger 1's, then ghosts, springs.
  EXPECT_EQ(list.items[0].pass, DrawPass::kProxies);
  EXPECT_EQ(list.items[1].pass, DrawPass::kProxies);
  EXPECT_EQ(list.items[2].pass, DrawPass::kPatchFill);
  EXPECT_EQ(list.items.back().pass, DrawPass::kSprings);
  // The force arrow points from the proxy away from the surface: it is the force rendered to the
  // device, against the squeeze (the outward normal of each finger's contact).
  const std::vector<const DrawItem*> arrows = itemsOf(list, DrawPass::kArrows);
  for (std::size_t i = 0; i < 2; ++i) {
    const sim::FingerSnapshot& f = frame.snapshot.fingers[i];
    const sim::Vec3 arrow = forceArrow(f, DrawSettings{});
    EXPECT_GT(arrow.normalized().dot(f.contacts.front().outward_normal_world), 0.5) << "finger " << i;
    const DrawItem* shaft = arrows[4 * i + 2];  // after the normal's shaft and head
    const Eigen::Vector3f from = shaft->model.block<3, 1>(0, 3);
    EXPECT_LT((from.cast<double>() - f.proxy).norm(), 1e-6);
  }
  // The fill and rim lie on the cylinder (radius 3 cm about the y axis through its centre),
  // lifted 0.2 mm.
  const sim::Pose cylinder = frame.snapshot.bodies[1];
  std::vector<const DrawItem*> surfaces = itemsOf(list, DrawPass::kPatchFill);
  for (const DrawItem* rim : itemsOf(list, DrawPass::kPatchRim)) surfaces.push_back(rim);
  for (const DrawItem* fill : surfaces) {
    EXPECT_EQ(fill->shape, DrawShape::kTriangles);
    EXPECT_EQ(fill->count % 3, 0);
    EXPECT_GT(fill->count, 0);
    for (int v = fill->first; v < fill->first + fill->count; ++v) {
      const float* p = list.vertices[static_cast<std::size_t>(v)].position;
      const sim::Vec3 local = cylinder.orientation.conjugate() * (sim::Vec3(p[0], p[1], p[2]) - cylinder.position);
      EXPECT_NEAR(std::hypot(local.x(), local.z()), 0.03, 1e-3) << "vertex " << v;
    }
  }
  // Each SGO dot where the snapshot has the SGO, in its finger's colour.
  std::size_t mark = 0;
  const std::vector<const DrawItem*> marks = itemsOf(list, DrawPass::kMarks);
  for (std::size_t i = 0; i < 2; ++i) {
    for (const sim::ContactSnapshot& c : frame.snapshot.fingers[i].contacts) {
      ++mark;  // the contact point
      for (const sim::Vec3& s : c.sgos_world) {
        const Eigen::Vector3f at = marks[mark]->model.block<3, 1>(0, 3);
        EXPECT_LT((at.cast<double>() - s).norm(), 1e-6);
        EXPECT_EQ(marks[mark]->colour, fingerColour(static_cast<int>(i)));
        ++mark;
      }
    }
  }
  EXPECT_EQ(mark, marks.size());
  // The same snapshot builds the same list, in the storage it already has.
  const std::size_t capacity = list.vertices.capacity();
  const std::vector<Vertex> first_vertices = list.vertices;
  builder.build(frame.snapshot, DrawSettings{}, list);
  EXPECT_EQ(list.vertices.capacity(), capacity);
  ASSERT_EQ(list.vertices.size(), first_vertices.size());
  for (std::size_t v = 0; v < first_vertices.size(); ++v) {
    EXPECT_EQ(list.vertices[v].position[0], first_vertices[v].position[0]);
  }
}

TEST(DrawList, SwitchesLeaveTheirPartsOut) {
  const Fig8Frame frame;
  DrawListBuilder builder(frame.session.scene, frame.surfaces);
  DrawList list;
  DrawSettings settings;
  settings.patch_highlight = false;
  builder.build(frame.snapshot, settings, list);
  for (const DrawItem& item : list.items) {
    EXPECT_TRUE(item.pass == DrawPass::kProxies || item.pass == DrawPass::kGhosts || item.pass == DrawPass::kSprings);
  }
  settings.patch_highlight = true;
  settings.fingers = false;
  builder.build(frame.snapshot, settings, list);
  for (const DrawItem& item : list.items) {
    EXPECT_FALSE(item.pass == DrawPass::kProxies || item.pass == DrawPass::kGhosts || item.pass == DrawPass::kSprings);
  }
  EXPECT_FALSE(list.items.empty());
}

}  // namespace
}  // namespace gf::render
