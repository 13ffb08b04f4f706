// The overlay's draw list, without GL: what a Fig. 8 squeeze frame holds (patches with their rim
// bands on the cylinder's surface, one dot per SGO where the snapshot puts it, normals and force
// arrows pointing away from the surface, proxies drawn first so the patches show through, the
// springs before the patches so these cover them, ghosts as outlines), dots coloured by load with
// slipping ones ringed, arrows kept inside the view, what the switches leave out, that a
// rebuild is the same, a fem_pad finger drawn as its deformed pad on its bone, and the pixels
// the list can cover (render/scene/screen_bounds.hpp).
#include "render/scene/draw_list.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "app/scene/data_folder.hpp"
#include "app/scene/scene_file.hpp"
#include "render/scene/camera.hpp"
#include "render/state/contact_load.hpp"
#include "render/scene/geometry.hpp"
#include "render/scene/screen_bounds.hpp"
#include "sim/world/world.hpp"

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
    for (sim::FingerSnapshot& f : snapshot.fingers) {
      for (sim::ContactSnapshot& c : f.contacts) c.loads.clear();  // uniform dots (tests below add loads)
    }
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
  // Two proxies and one set of spring lines; per finger a fill, a rim band, its lines, the contact
  // point and 8 SGO dots, a normal and the force (two pieces each); then two ghost outlines.
  EXPECT_EQ(itemsOf(list, DrawPass::kPatchFill).size(), 2u);
  EXPECT_EQ(itemsOf(list, DrawPass::kPatchRim).size(), 2u);
  EXPECT_EQ(itemsOf(list, DrawPass::kPatchLines).size(), 2u);
  EXPECT_EQ(itemsOf(list, DrawPass::kMarks).size(), 2u * 9u);
  EXPECT_EQ(itemsOf(list, DrawPass::kArrows).size(), 2u * 4u);
  EXPECT_EQ(itemsOf(list, DrawPass::kProxies).size(), 2u);
  ASSERT_EQ(itemsOf(list, DrawPass::kGhosts).size(), 2u);
  for (const DrawItem* ghost : itemsOf(list, DrawPass::kGhosts)) {
    EXPECT_EQ(ghost->shape, DrawShape::kTriangles) << "an outline, not a second sphere";
  }
  ASSERT_EQ(itemsOf(list, DrawPass::kSprings).size(), 1u);
  EXPECT_EQ(itemsOf(list, DrawPass::kSprings)[0]->count, 2 * 2 * 96);  // two coils of 96 segments
  // Drawing order: the proxies (they write no depth, so the patches drawn after show through
  // them), the springs (the patches cover the coil where it runs to the device inside the body),
  // finger 0's patch items, finger 1's, then the ghosts.
  EXPECT_EQ(list.items[0].pass, DrawPass::kProxies);
  EXPECT_EQ(list.items[1].pass, DrawPass::kProxies);
  EXPECT_EQ(list.items[2].pass, DrawPass::kSprings);
  EXPECT_EQ(list.items[3].pass, DrawPass::kPatchFill);
  EXPECT_EQ(list.items.back().pass, DrawPass::kGhosts);
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

// With per-point loads each dot takes its load's colour on the viridis scale (centred on the
// mean, the most loaded point at the top) and a slipping point a white ring (a flat cylinder
// along the normal) around its dot.
TEST(DrawList, DotsAreColouredByLoadAndSlippingOnesRinged) {
  Fig8Frame frame;
  sim::ContactSnapshot& c = frame.snapshot.fingers[0].contacts.front();
  ASSERT_EQ(c.sgos_world.size(), 8u);
  c.loads.assign(8, sim::PointLoad{});
  for (sim::PointLoad& l : c.loads) l.normal = 0.4;
  c.point_load.normal = 0.4;
  c.loads[3].normal = 1.2;  // 4.4 N over 9 points: mean 0.489 N, this one 2.45x: the top (1.45 off the mean)
  c.loads[5].slipping = true;
  DrawListBuilder builder(frame.session.scene, frame.surfaces);
  DrawList list;
  builder.build(frame.snapshot, DrawSettings{}, list);
  const std::vector<const DrawItem*> marks = itemsOf(list, DrawPass::kMarks);
  std::vector<const DrawItem*> dots, rings;
  for (const DrawItem* m : marks) (m->shape == DrawShape::kDot ? dots : rings).push_back(m);
  ASSERT_EQ(dots.size(), 2u * 9u);
  ASSERT_EQ(rings.size(), 1u);
  const double mean = 4.4 / 9.0;
  const double half_span = 1.2 / mean - 1.0;
  EXPECT_TRUE(dots[0]->colour.isApprox(viridis(0.5 + (0.4 / mean - 1.0) / (2.0 * half_span))));  // the contact point
  EXPECT_TRUE(dots[1 + 0]->colour.isApprox(viridis(0.5 + (0.4 / mean - 1.0) / (2.0 * half_span))));
  EXPECT_EQ(dots[1 + 3]->colour, viridis(1.0));
  EXPECT_EQ(rings[0]->shape, DrawShape::kCylinder);
  EXPECT_EQ(rings[0]->colour, Eigen::Vector3f::Ones());
  // The ring sits on SGO 5, flat along the contact normal, wider than the dot.
  const Eigen::Vector3f at = rings[0]->model.block<3, 1>(0, 3);
  EXPECT_LT((at.cast<double>() - c.sgos_world[5]).norm(), 1e-3);
  const Eigen::Vector3f axis = rings[0]->model.block<3, 1>(0, 1);  // the unit cylinder's +y, scaled
  EXPECT_GT(std::abs(axis.normalized().cast<double>().dot(c.outward_normal_world)), 0.999);
  const float ring_radius = rings[0]->model.block<3, 1>(0, 0).norm(), dot_radius = dots[1 + 5]->model.block<3, 1>(0, 0).norm();
  EXPECT_GT(ring_radius, dot_radius);
  // Finger 1 has no loads: its dots are uniform, the contact point white, the SGOs its colour.
  EXPECT_EQ(dots[9]->colour, Eigen::Vector3f(0.95f, 0.95f, 0.95f));
  EXPECT_EQ(dots[10]->colour, fingerColour(1));
}

// Seen from a camera, the force arrow is at most a quarter of the view's height at its proxy
// and its tip stays inside the frame less a 4 % margin; a proxy behind the camera draws none.
TEST(DrawList, ForceArrowsStayInsideTheView) {
  const sim::Vec3 eye(0.0, 0.0, 0.3), target = sim::Vec3::Zero();
  DrawView view;
  view.view_proj = (perspective(40.0, 16.0 / 9.0, 0.002, 10.0) * lookAt(eye, target, sim::Vec3::UnitY())).cast<double>();
  view.eye = eye;
  view.tan_half_fov = std::tan(20.0 * M_PI / 180.0);
  view.height_px = 360;
  const double half_height = 0.3 * view.tan_half_fov;  // at the target's depth (m)
  constexpr double kFloat = 1e-7;                       // m: the GL matrices are single precision
  // Near the right edge, pointing right: stopped at the margin.
  const sim::Vec3 edge(0.8 * half_height * 16.0 / 9.0, 0.0, 0.0);
  const double to_margin = longestArrowInView(view, edge, sim::Vec3::UnitX(), 10.0);
  const Eigen::Vector4d tip = view.view_proj * (edge + to_margin * sim::Vec3::UnitX()).homogeneous();
  EXPECT_NEAR(tip.x() / tip.w(), 0.92, 1e-9);
  // In the middle: a quarter of the view's height.
  EXPECT_NEAR(longestArrowInView(view, target, sim::Vec3::UnitY(), 0.25), 0.25 * 2.0 * half_height, kFloat);
  // Towards the camera: at most the share, and short of the near plane.
  EXPECT_LE(longestArrowInView(view, target, sim::Vec3::UnitZ(), 0.25), 0.25 * 2.0 * half_height + kFloat);
  EXPECT_EQ(longestArrowInView(view, eye + sim::Vec3(0, 0, 0.1), -sim::Vec3::UnitZ(), 0.25), 0.0);
  // forceArrow() applies it: 20 N at 1 cm/N would be 20 cm, capped at 8 cm, then at the view.
  sim::FingerSnapshot finger;
  finger.proxy = target;
  finger.feedback_force = sim::Vec3(0.0, 20.0, 0.0);
  DrawSettings settings;
  EXPECT_NEAR(forceArrow(finger, settings).norm(), 0.08, 1e-12);
  settings.view = view;
  EXPECT_NEAR(forceArrow(finger, settings).norm(), 0.25 * 2.0 * half_height, kFloat);
  EXPECT_GT(forceArrow(finger, settings).y(), 0.0);
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
  EXPECT_FALSE(itemsOf(list, DrawPass::kArrows).empty());
  settings.contact_arrows = false;  // a close-up down the normal: no arrow at the camera
  builder.build(frame.snapshot, settings, list);
  EXPECT_TRUE(itemsOf(list, DrawPass::kArrows).empty());
  EXPECT_FALSE(itemsOf(list, DrawPass::kMarks).empty());
}

// A fem_pad finger pressing the puck: its skin drawn first, opaque, one corner per skin
// triangle's node where the snapshot has it (flattened on the puck's top), smooth normals that
// agree with each triangle's winding; its bone, not the skin-sized proxy, as the translucent
// sphere; its pressed nodes as dots. Without the fingers, no pad.
TEST(DrawList, AFemPadFingerIsDrawnAsItsPadOnItsBone) {
  const std::vector<std::string> overrides = {"fingers.index.contact_model=fem_pad"};
  const app::SessionDesc session = app::loadSceneFile(app::resolveScenePath("pressed-puck"), overrides);
  sim::World world(session.scene);
  const std::vector<sim::DeviceTrack> devices = sim::deviceTracks(session.scene);
  std::vector<sim::DeviceSample> samples(devices.size());
  for (int k = 0; k < 400; ++k) {  // pressed from 0.3 s, before the torque
    for (std::size_t i = 0; i < devices.size(); ++i) samples[i] = devices[i].sample(world.time());
    world.step(0.001, samples);
  }
  sim::Snapshot snapshot;
  world.snapshot(snapshot);
  ASSERT_EQ(snapshot.fingers.size(), 1u);
  const sim::FingerSnapshot& f = snapshot.fingers[0];
  ASSERT_FALSE(f.pad.nodes.empty());
  ASSERT_TRUE(f.pad.skin);
  const double proxy_radius = session.scene.fingers[0].proxy.radius;  // the skin's: 8 mm
  ASSERT_GT(f.pad.bone_radius, 0.0);
  ASSERT_LT(f.pad.bone_radius, proxy_radius);
  std::vector<std::shared_ptr<const sim::Mesh>> surfaces;
  for (const sim::BodyDesc& b : session.scene.bodies) surfaces.push_back(bodyRenderMesh(b));
  DrawListBuilder builder(session.scene, surfaces);
  DrawList list;
  builder.build(snapshot, DrawSettings{}, list);
  const std::vector<const DrawItem*> pads = itemsOf(list, DrawPass::kPads);
  ASSERT_EQ(pads.size(), 1u);
  EXPECT_EQ(&list.items[0], pads[0]) << "drawn first: the translucent bone goes over it";
  EXPECT_EQ(pads[0]->shape, DrawShape::kTriangles);
  EXPECT_EQ(pads[0]->colour, kPadColour);
  EXPECT_EQ(pads[0]->alpha, 1.0f);
  const std::vector<std::array<int, 3>>& skin = *f.pad.skin;
  ASSERT_EQ(pads[0]->count, 3 * static_cast<int>(skin.size()));
  double lowest = 1.0;
  for (std::size_t t = 0; t < skin.size(); ++t) {
    const Vertex* corner = &list.vertices[static_cast<std::size_t>(pads[0]->first) + 3 * t];
    const auto at = [&](int k) { return Eigen::Map<const Eigen::Vector3f>(corner[k].position).cast<double>(); };
    const sim::Vec3 face = (at(1) - at(0)).cross(at(2) - at(0));
    for (int k = 0; k < 3; ++k) {
      EXPECT_LT((at(k) - f.pad.nodes[static_cast<std::size_t>(skin[t][static_cast<std::size_t>(k)])]).norm(), 1e-6);
      const sim::Vec3 normal = Eigen::Map<const Eigen::Vector3f>(corner[k].normal).cast<double>();
      EXPECT_NEAR(normal.norm(), 1.0, 1e-5);
      EXPECT_GT(normal.dot(face), 0.0) << "triangle " << t << " corner " << k;
      lowest = std::min(lowest, at(k).y());
    }
  }
  // The undeformed skin would reach 8 mm below the proxy, into the puck (its top at y = 4 cm):
  // the pad drawn stops at the top, flattened.
  EXPECT_LT(f.proxy.y() - proxy_radius, 0.04 - 2e-4);
  EXPECT_NEAR(lowest, 0.04, 5e-4);
  // The bone, at the proxy, of its own radius.
  const std::vector<const DrawItem*> bones = itemsOf(list, DrawPass::kProxies);
  ASSERT_EQ(bones.size(), 1u);
  EXPECT_EQ(bones[0]->shape, DrawShape::kSphere);
  const float bone_scale = bones[0]->model.block<3, 1>(0, 0).norm();
  EXPECT_NEAR(bone_scale, f.pad.bone_radius, 1e-7);
  const Eigen::Vector3f bone_at = bones[0]->model.block<3, 1>(0, 3);
  EXPECT_LT((bone_at.cast<double>() - f.proxy).norm(), 1e-6);
  EXPECT_EQ(proxySphereRadius(f, proxy_radius), f.pad.bone_radius);
  EXPECT_EQ(proxySphereRadius(sim::FingerSnapshot{}, proxy_radius), proxy_radius);
  // The pressed skin nodes are the SGO dots; the spring and the ghost are still there.
  EXPECT_FALSE(itemsOf(list, DrawPass::kMarks).empty());
  EXPECT_EQ(itemsOf(list, DrawPass::kSprings).size(), 1u);
  EXPECT_EQ(itemsOf(list, DrawPass::kGhosts).size(), 1u);
  DrawSettings no_fingers;
  no_fingers.fingers = false;
  builder.build(snapshot, no_fingers, list);
  EXPECT_TRUE(itemsOf(list, DrawPass::kPads).empty());
}

// A scene's targets: a body's ghost is the body's surface at the target pose (every triangle,
// translucent, lit, in the target colour), a zone its box's six faces, wound outward, and its
// twelve edges, each along one axis. Without targets in the settings, nothing of them.
TEST(DrawList, TargetsAreAGhostAtTheirPoseAndAZoneBox) {
  const Fig8Frame frame;
  DrawListBuilder builder(frame.session.scene, frame.surfaces);
  const auto body = std::find_if(frame.session.scene.bodies.begin(), frame.session.scene.bodies.end(),
                                 [](const sim::BodyDesc& b) { return b.shape != sim::ShapeKind::kPlane; });
  ASSERT_NE(body, frame.session.scene.bodies.end());
  const int b = static_cast<int>(body - frame.session.scene.bodies.begin());
  const sim::Mesh& surface = *frame.surfaces[static_cast<std::size_t>(b)];
  std::vector<view::Target> targets(2);
  targets[0].body = b;
  targets[0].position = sim::Vec3(0.1, 0.2, -0.05);
  targets[0].orientation = sim::Quat(Eigen::AngleAxisd(0.7, sim::Vec3(1, 2, 3).normalized()));
  targets[1].has_zone = true;
  targets[1].zone_min = sim::Vec3(-0.01, 0.02, 0.03);
  targets[1].zone_max = sim::Vec3(0.04, 0.05, 0.09);
  DrawSettings settings;
  DrawList none, list;
  builder.build(frame.snapshot, settings, none);
  settings.targets = &targets;
  builder.build(frame.snapshot, settings, list);
  const auto targetItems = [](const DrawList& l) {
    std::vector<const DrawItem*> out;
    for (const DrawItem& item : l.items) {
      if ((item.colour - kTargetColour).norm() < 1e-6f || (item.colour - 0.6f * kTargetColour).norm() < 1e-6f) out.push_back(&item);
    }
    return out;
  };
  EXPECT_TRUE(targetItems(none).empty());
  const std::vector<const DrawItem*> items = targetItems(list);
  ASSERT_EQ(items.size(), 3u);  // the ghost, the zone's faces, its edges
  EXPECT_EQ(list.items.size(), none.items.size() + 3);
  const auto at = [&](const DrawItem& item, int k) {
    const Vertex& v = list.vertices[static_cast<std::size_t>(item.first + k)];
    return sim::Vec3(v.position[0], v.position[1], v.position[2]);
  };
  const auto normalAt = [&](const DrawItem& item, int k) {
    const Vertex& v = list.vertices[static_cast<std::size_t>(item.first + k)];
    return sim::Vec3(v.normal[0], v.normal[1], v.normal[2]);
  };
  const DrawItem& ghost = *items[0];
  EXPECT_EQ(ghost.pass, DrawPass::kTargets);
  EXPECT_EQ(ghost.shape, DrawShape::kTriangles);
  EXPECT_LT(ghost.alpha, 1.0f);
  ASSERT_EQ(ghost.count, 3 * surface.faceCount());
  for (int f = 0; f < surface.faceCount(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const sim::Vec3 expected = targets[0].position + targets[0].orientation * surface.corner(f, k);
      EXPECT_LT((at(ghost, 3 * f + k) - expected).norm(), 1e-6) << f;
    }
  }
  const DrawItem& faces = *items[1];
  EXPECT_EQ(faces.pass, DrawPass::kTargets);
  ASSERT_EQ(faces.count, 36);
  const sim::Vec3 centre = 0.5 * (targets[1].zone_min + targets[1].zone_max);
  for (int t = 0; t < 12; ++t) {
    const sim::Vec3 a = at(faces, 3 * t), c = at(faces, 3 * t + 1), d = at(faces, 3 * t + 2);
    const sim::Vec3 wound = (c - a).cross(d - a);
    EXPECT_GT(wound.dot(a - centre), 0.0) << "triangle " << t << " wound outward";
    EXPECT_GT(wound.normalized().dot(normalAt(faces, 3 * t)), 0.999) << t;
    for (const sim::Vec3& p : {a, c, d}) {
      EXPECT_TRUE((p.array() >= targets[1].zone_min.array() - 1e-6).all() && (p.array() <= targets[1].zone_max.array() + 1e-6).all());
    }
  }
  const DrawItem& edges = *items[2];
  EXPECT_EQ(edges.pass, DrawPass::kPatchLines);
  EXPECT_EQ(edges.shape, DrawShape::kLines);
  ASSERT_EQ(edges.count, 24);
  for (int e = 0; e < 12; ++e) {
    const sim::Vec3 d = (at(edges, 2 * e + 1) - at(edges, 2 * e)).cwiseAbs();
    EXPECT_EQ((d.array() > 1e-6).count(), 1) << "edge " << e << " runs along one axis";
  }
}

// overlayPixels holds every pixel the overlay can draw on: each vertex of the squeeze frame's
// list, its ranges' and its unit shapes' own mesh vertices placed by their models, projected by
// the scene's camera, falls inside it with the 2 pixels of margin (a restored layer gets depth
// only there). An empty list covers nothing; a point behind the eye, the whole frame.
TEST(DrawList, OverlayPixelsHoldEveryVertexTheOverlayDraws) {
  const Fig8Frame frame;
  DrawListBuilder builder(frame.session.scene, frame.surfaces);
  DrawList list;
  builder.build(frame.snapshot, DrawSettings{}, list);
  ASSERT_FALSE(list.items.empty());
  view::Camera camera;  // three-quarters from the front, the cylinder about a third of the frame's height
  camera.position = sim::Vec3(0.25, 0.2, 0.35);
  camera.target = sim::Vec3(0.0, 0.05, 0.0);
  camera.fov_deg = 40.0;
  const int width = 1280, height = 720;
  const Eigen::Matrix4f view_proj = perspective(camera.fov_deg, double(width) / height, 0.002, 10.0) *
                                    lookAt(camera.position, camera.target, upFor(camera.target - camera.position));
  const std::vector<Vertex> meshes[4] = {unitSphere(3), unitSphere(1), unitCylinder(24), unitCone(24)};
  const std::array<Eigen::AlignedBox3f, 4> boxes{boundsOf(meshes[0]), boundsOf(meshes[1]), boundsOf(meshes[2]),
                                                 boundsOf(meshes[3])};
  const PixelRect r = overlayPixels(list, boxes, view_proj, width, height);
  ASSERT_FALSE(r.empty());
  EXPECT_LT((r.x1 - r.x0) * (r.y1 - r.y0), width * height / 2);  // the contacts, not the frame
  int checked = 0, outside = 0;
  const auto check = [&](const Eigen::Vector3f& p) {
    const Eigen::Vector4f c = view_proj * p.homogeneous();
    ASSERT_GT(c.w(), 0.0f);
    const double x = (0.5 * c.x() / c.w() + 0.5) * width, y = (0.5 * c.y() / c.w() + 0.5) * height;
    ++checked;
    outside += x < std::max(r.x0 + 2, 2) || x > std::min(r.x1 - 2, width - 2) || y < std::max(r.y0 + 2, 2) ||
               y > std::min(r.y1 - 2, height - 2);
  };
  for (const DrawItem& item : list.items) {
    if (item.shape == DrawShape::kTriangles || item.shape == DrawShape::kLines) {
      for (int v = item.first; v < item.first + item.count; ++v) {
        check(Eigen::Map<const Eigen::Vector3f>(list.vertices[static_cast<std::size_t>(v)].position));
      }
    } else {
      for (const Vertex& v : meshes[static_cast<int>(item.shape)]) {
        check((item.model * Eigen::Map<const Eigen::Vector3f>(v.position).homogeneous()).head<3>());
      }
    }
  }
  EXPECT_GT(checked, 1000);
  EXPECT_EQ(outside, 0);
  EXPECT_TRUE(overlayPixels(DrawList{}, boxes, view_proj, width, height).empty());
  DrawList behind = list;
  const Eigen::Vector3f back = (camera.position + 2.0 * (camera.position - camera.target)).cast<float>();
  behind.items.push_back(shapeItem(DrawPass::kMarks, DrawShape::kDot, modelMatrix(back.cast<double>(), sim::Quat::Identity(),
                                                                                  sim::Vec3::Constant(0.001)),
                                   Eigen::Vector3f::Ones()));
  const PixelRect all = overlayPixels(behind, boxes, view_proj, width, height);
  EXPECT_EQ(all.x0, 0);
  EXPECT_EQ(all.y0, 0);
  EXPECT_EQ(all.x1, width);
  EXPECT_EQ(all.y1, height);
}

}  // namespace
}  // namespace gf::render
