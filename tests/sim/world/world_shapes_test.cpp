// Every body shape builds, collides with a proxy and receives SGOs on its walk mesh.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "sim/loop/haptic_loop.hpp"
#include "sim/mesh/primitives.hpp"
#include "sim/scene/settings.hpp"
#include "sim/world/world.hpp"
#include "tests/scratch.hpp"

namespace gf::sim {
namespace {

// Writes an L-shaped (concave) prism, 6 cm x 6 cm x 2 cm, as OBJ; returns its path.
std::string writeLShapeObj() {
  const std::filesystem::path path = gf::test::scratchRoot() / "gf_world_shapes_l.obj";
  const double outline[6][2] = {{-0.03, -0.03}, {0.03, -0.03}, {0.03, 0.0},
                                {0.0, 0.0},     {0.0, 0.03},   {-0.03, 0.03}};
  std::ofstream f(path);
  for (double y : {-0.01, 0.01}) {
    for (const auto& p : outline) f << "v " << p[0] << " " << y << " " << p[1] << "\n";
  }
  // Bottom (y = -0.01, facing down) and top (facing up) as fans split at the re-entrant corner.
  f << "f 1 2 3\nf 1 3 4\nf 1 4 5\nf 1 5 6\n";
  f << "f 7 10 9\nf 7 9 8\nf 7 11 10\nf 7 12 11\n";
  for (int i = 0; i < 6; ++i) {  // sides
    const int a = i + 1, b = (i + 1) % 6 + 1;
    f << "f " << a << " " << b + 6 << " " << b << "\nf " << a << " " << a + 6 << " " << b + 6 << "\n";
  }
  return path.string();
}

SceneDesc pressScene(const BodyDesc& body, double top_y) {
  SceneDesc s;
  s.name = "press-" + body.name;
  BodyDesc ground;
  ground.name = "ground";
  ground.shape = ShapeKind::kPlane;
  ground.mass = 0.0;
  s.bodies = {ground, body};
  FingerDesc f;
  f.name = "index";
  f.device.keyframes = {{0.0, Vec3(-0.012, top_y + 0.02, -0.012)},
                        {0.3, Vec3(-0.012, top_y + 0.008 - 0.005, -0.012)}};
  s.fingers = {f};
  return s;
}

TEST(WorldShapes, EveryShapeTakesSgosWhenPressed) {
  const std::string l_shape = writeLShapeObj();
  std::vector<BodyDesc> bodies(6);
  bodies[0].name = "sphere", bodies[0].shape = ShapeKind::kSphere, bodies[0].radius = 0.03;
  bodies[1].name = "box", bodies[1].shape = ShapeKind::kBox;
  bodies[2].name = "cylinder", bodies[2].shape = ShapeKind::kCylinder;
  bodies[3].name = "capsule", bodies[3].shape = ShapeKind::kCapsule, bodies[3].radius = 0.03;
  bodies[4].name = "hull", bodies[4].shape = ShapeKind::kConvexHull, bodies[4].mesh_path = l_shape;
  bodies[5].name = "concave", bodies[5].shape = ShapeKind::kConcaveMesh, bodies[5].mesh_path = l_shape;
  const double half_height[6] = {0.03, 0.05, 0.05, 0.08, 0.01, 0.01};
  for (int i = 0; i < 6; ++i) {
    SCOPED_TRACE(bodies[i].name);
    bodies[i].mass = 0.0;  // static: the finger presses without pushing it away
    bodies[i].position = Vec3(0, half_height[i], 0);
    World world(pressScene(bodies[i], 2 * half_height[i]));
    std::vector<DeviceTrack> devices = {world.desc().fingers[0].device};
    int max_sgo = 0;
    runHapticLoop(world, devices, {1000.0, 0.5}, [&](const World& w) {
      max_sgo = std::max(max_sgo, w.sgoCount(0));
    });
    EXPECT_EQ(max_sgo, 8);
    EXPECT_EQ(world.counters().nan_recoveries, 0);
    // The spring pulls the proxy into the surface, which holds it: force on the proxy is down.
    EXPECT_LT(world.couplingForce(0).y(), -0.5);
    Snapshot snap;
    world.snapshot(snap);
    ASSERT_EQ(snap.fingers[0].contacts.size(), 1u);
    for (const Vec3& p : snap.fingers[0].contacts[0].sgos_world) {
      EXPECT_NEAR(p.y(), 2 * half_height[i], 0.01) << "SGOs lie on the touched top";
    }
  }
  std::filesystem::remove(l_shape);
}

TEST(WorldShapes, DynamicMeshBodiesNeedAClosedMesh) {
  const std::filesystem::path path = gf::test::scratchRoot() / "gf_open_square.obj";
  std::ofstream(path) << "v 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nf 1 3 2\nf 1 4 3\n";
  BodyDesc sheet;
  sheet.name = "sheet";
  sheet.shape = ShapeKind::kConcaveMesh;
  sheet.mesh_path = path.string();
  sheet.mass = 0.1;
  try {
    World w(pressScene(sheet, 0.0));
    FAIL();
  } catch (const DescriptionError& e) {
    EXPECT_NE(std::string(e.what()).find("body 'sheet'"), std::string::npos) << e.what();
    EXPECT_EQ(e.error().field, "mesh");
    EXPECT_NE(std::string(e.what()).find("encloses no volume"), std::string::npos) << e.what();
  }
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace gf::sim
