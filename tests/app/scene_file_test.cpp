// Scene files: fields, overrides, and a clear error (file, line, field) for each bad input.
#include "app/scene/scene_file.hpp"
#include "app/scene/data_folder.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include "render/scene/geometry.hpp"
#include "sim/loop/haptic_loop.hpp"
#include "sim/mesh/mesh_import.hpp"
#include "sim/world/world.hpp"
#include "tests/app/scene_text.hpp"
#include "tests/scratch.hpp"

namespace gf::app {
namespace {

namespace fs = std::filesystem;

// `density` instead of `mass`: the mass is the density times the shape's volume (a sphere's
// 4/3 pi r^3; a closed mesh's enclosed volume); with mass, on a static body, on an open mesh or
// giving a mass outside the mass range, it is an error naming the field.
TEST(SceneFile, DensityGivesTheMassFromTheVolume) {
  const SessionDesc s = parseSceneText(replaced("mass = 0.1", "density = 1000"), "scene.toml", "");
  EXPECT_NEAR(s.scene.bodies[1].mass, 1000.0 * 4.0 / 3.0 * std::numbers::pi * 0.03 * 0.03 * 0.03, 1e-12);
  const fs::path dir = gf::test::scratchRoot() / "gf_density";
  fs::create_directories(dir);
  std::ofstream(dir / "cube.obj") << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
                                     "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\n"
                                     "f 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n";
  const std::string cube = replaced("shape = \"sphere\"\nradius = 0.03\nmass = 0.1",
                                    "shape = \"mesh\"\ncollision = \"convex_hull\"\nmesh = \"cube.obj\"\nscale = 0.04\ndensity = 500");
  const SessionDesc c = parseSceneText(cube, "scene.toml", dir.string());
  EXPECT_NEAR(c.scene.bodies[1].mass, 500.0 * 0.04 * 0.04 * 0.04, 1e-12);
  EXPECT_EQ(errorOf(replaced("mass = 0.1", "mass = 0.1\ndensity = 1000")).field(), "bodies.ball.density");
  EXPECT_EQ(errorOf(replaced("mass = 0.1", "density = 0.5")).field(), "bodies.ball.density");  // below 1 kg/m^3
  EXPECT_NE(errorOf(replaced("radius = 0.03\nmass = 0.1", "radius = 0.001\ndensity = 1")).reason().find("gives a mass of"),
            std::string::npos);
  // Too light for the proxies: the error names density, the field the user wrote.
  EXPECT_EQ(errorOf(replaced("mass = 0.1", "density = 1")).field(), "bodies.ball.density");
  EXPECT_EQ(errorOf(replaced("mass = 0.1", "static = true\ndensity = 1000")).field(), "bodies.ball.density");
}

// `up_axis`: a mesh drawn with +z up (a 1 x 1 x 3 box, tall along z) stands 3 units tall along
// +y with up_axis = "z", and its top (z = 3) ends at +y; an unknown axis is named.
TEST(SceneFile, UpAxisTurnsTheMeshUp) {
  const fs::path dir = gf::test::scratchRoot() / "gf_up_axis";
  fs::create_directories(dir);
  std::ofstream(dir / "tall.obj") << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 3\nv 1 0 3\nv 1 1 3\nv 0 1 3\n"
                                     "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\n"
                                     "f 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n";
  const auto scene = [&](const std::string& up) {
    return replaced("shape = \"sphere\"\nradius = 0.03\nmass = 0.1",
                    "shape = \"mesh\"\ncollision = \"convex_hull\"\nmesh = \"tall.obj\"\nscale = 0.01\nmass = 0.1" + up);
  };
  const SessionDesc as_read = parseSceneText(scene(""), "scene.toml", dir.string());
  EXPECT_NEAR(as_read.scene.bodies[1].mesh->boundsMax().y(), 0.01, 1e-12);
  const SessionDesc z_up = parseSceneText(scene("\nup_axis = \"z\""), "scene.toml", dir.string());
  const sim::Mesh& m = *z_up.scene.bodies[1].mesh;
  EXPECT_NEAR(m.boundsMax().y() - m.boundsMin().y(), 0.03, 1e-12);
  EXPECT_NEAR(m.boundsMax().y(), 0.03, 1e-12);  // the top, z = 3, is up
  EXPECT_NEAR(m.boundsMax().z() - m.boundsMin().z(), 0.01, 1e-12);
  EXPECT_GT(sim::massProperties(m).volume, 0.0);  // still outward: a proper rotation
  try {
    parseSceneText(scene("\nup_axis = \"up\""), "scene.toml", dir.string());
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "bodies.ball.up_axis");
  }
}

TEST(SceneFile, ReadsBodiesFingersAndEffectsInFileOrder) {
  const SessionDesc s = parseSceneText(kMinimal, "scene.toml", "");
  ASSERT_EQ(s.scene.bodies.size(), 2u);
  EXPECT_EQ(s.scene.bodies[0].name, "ground");
  EXPECT_EQ(s.scene.bodies[1].name, "ball");
  EXPECT_EQ(s.scene.bodies[0].mass, 0.0);
  EXPECT_DOUBLE_EQ(s.scene.bodies[1].radius, 0.03);
  ASSERT_EQ(s.scene.fingers.size(), 1u);
  EXPECT_EQ(s.scene.fingers[0].device.keyframes.size(), 2u);
  EXPECT_TRUE(s.scene.effects.gravity);
  EXPECT_TRUE(s.scene.effects.god_finger);
  EXPECT_FALSE(s.scene.effects.tangential_stretch) << "not listed, so not run";
  EXPECT_FALSE(s.scene.effects.force_feedback);
}

TEST(SceneFile, OverridesSetAnyField) {
  const std::vector<std::string> o = {"fingers.left.n_sgo=0", "bodies.ball.mass=0.25", "name=other",
                                      "fingers.left.tau_a=30"};
  const SessionDesc s = parseSceneText(kMinimal, "scene.toml", "", o);
  EXPECT_EQ(s.scene.fingers[0].patch.n_sgo, 0);
  EXPECT_DOUBLE_EQ(s.scene.bodies[1].mass, 0.25);
  EXPECT_EQ(s.scene.name, "other");
  EXPECT_NEAR(s.scene.fingers[0].patch.tau_a, 30.0 * std::numbers::pi / 180.0, 1e-12);
}

TEST(SceneFile, ErrorsNameFileLineAndField) {
  struct Case {
    std::string text;
    int line;
    std::string field, reason;
  };
  const Case cases[] = {
      {replaced("radius = 0.03", "radius = 0.03\ncolor = [1, 0, 0]"), 9, "bodies.ball.color", "unknown field"},
      {replaced("mass = 0.1", "mass = \"heavy\""), 9, "bodies.ball.mass", "expected a number, got a string"},
      {replaced("mass = 0.1", "mass = nan"), 9, "bodies.ball.mass", "must be finite"},
      {replaced("n_sgo = 8", "n_sgo = 2"), 12, "fingers.left.n_sgo", "must be 0 (god-object) or 3..64"},
      {replaced("n_sgo = 8", "n_sgo = 8.5"), 12, "fingers.left.n_sgo", "expected an integer"},
      {replaced("\"god_finger\"]", "\"god_fingers\"]"), 3, "effects", "unknown effect 'god_fingers'"},
      {replaced("shape = \"sphere\"", "shape = \"cone\""), 7, "bodies.ball.shape", "unknown value 'cone'"},
      {replaced("duration = 0.2", "duration = "), 2, "", ""},  // TOML syntax error
      {replaced("{ t = 0.2,", "{ t = 0.0,"), 14, "fingers.left.device.keyframes.t", "increase strictly"},
  };
  for (const Case& c : cases) {
    const InputError e = errorOf(c.text);
    EXPECT_EQ(e.file(), "scene.toml");
    EXPECT_EQ(e.line(), c.line) << e.what();
    EXPECT_EQ(e.field(), c.field) << e.what();
    EXPECT_NE(std::string(e.what()).find(c.reason), std::string::npos) << e.what();
  }
}

TEST(SceneFile, MissingAndEmptyMeshesAreNamed) {
  const fs::path dir = gf::test::scratchRoot() / "gf_scene_file_test";
  fs::create_directories(dir);
  std::ofstream(dir / "empty.obj") << "# no triangle\nv 0 0 0\n";
  const std::string body = "shape = \"sphere\"\nradius = 0.03";
  for (const char* mesh : {"missing.obj", "empty.obj"}) {
    const std::string text = replaced(body, "shape = \"mesh\"\nmesh = \"" + std::string(mesh) + "\"");
    try {
      parseSceneText(text, "scene.toml", dir.string());
      ADD_FAILURE() << mesh << " accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(e.line(), 8) << e.what();
      EXPECT_EQ(e.field(), "bodies.ball.mesh");
      EXPECT_NE(std::string(e.what()).find(mesh), std::string::npos) << e.what();
    }
  }
}

// An open mesh encloses no volume, so a dynamic body cannot take its mass distribution from it:
// refused naming the scene file, the mesh line and field, as mesh-info calls it "static only"; a
// static body of it is fine, and a slab whose top is split at T-junctions (open edges whose faces
// still close up in space) encloses a volume and may be dynamic.
TEST(SceneFile, AnOpenMeshAsADynamicBodyIsRefusedNamingFileLineAndField) {
  const fs::path dir = gf::test::scratchRoot() / "gf_scene_file_open_mesh";
  fs::create_directories(dir);
  std::ofstream(dir / "open-box.obj") << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
                                         "f 1 3 2\nf 1 4 3\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\n"
                                         "f 4 1 5\nf 4 5 8\n";
  // A unit cube whose top face is split at the midpoint of one edge (a T-junction): 2 boundary edges.
  std::ofstream(dir / "t-cube.obj") << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
                                       "v 0.5 0 1\nf 1 3 2\nf 1 4 3\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 3 4 8\n"
                                       "f 3 8 7\nf 4 1 5\nf 4 5 8\nf 5 9 8\nf 9 6 7\nf 9 7 8\n";
  const std::string ball = "shape = \"sphere\"\nradius = 0.03";
  const std::string dynamic = replaced(ball, "shape = \"mesh\"\nmesh = \"open-box.obj\"\nscale = 0.05");
  try {
    parseSceneText(dynamic, "scene.toml", dir.string());
    ADD_FAILURE() << "an open mesh accepted as a dynamic body";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "scene.toml");
    EXPECT_EQ(e.line(), 8) << e.what();
    EXPECT_EQ(e.field(), "bodies.ball.mesh");
    EXPECT_NE(e.reason().find("not closed (4 boundary and 0 non-manifold edges)"), std::string::npos) << e.what();
    EXPECT_NE(e.reason().find("static = true"), std::string::npos) << e.what();
  }
  std::string still = dynamic;
  still.replace(still.find("mass = 0.1"), 10, "static = true");
  EXPECT_NO_THROW(parseSceneText(still, "scene.toml", dir.string()));
  std::string cracked = dynamic;
  cracked.replace(cracked.find("open-box.obj"), 12, "t-cube.obj");
  EXPECT_NO_THROW(parseSceneText(cracked, "scene.toml", dir.string()));
}

// Bundled meshes and folders are found by their repository name from any working directory,
// like bundled scenes; a path that exists where the command runs comes first.
TEST(SceneFile, BundledMeshesAndFoldersAreFoundFromAnywhere) {
  const fs::path here = fs::current_path();
  const fs::path elsewhere = gf::test::scratchRoot() / "gf_data_path_elsewhere";
  fs::remove_all(elsewhere);
  fs::create_directories(elsewhere / "assets" / "meshes");
  fs::current_path(elsewhere);
  const std::string mesh = resolveDataPath("assets/meshes/bunny.obj");
  const std::string scenes = resolveDataPath("assets/scenes");
  const std::string short_name = resolveDataPath("meshes/bunny.obj");
  std::ofstream("assets/meshes/bunny.obj") << "v 0 0 0\n";
  const std::string local = resolveDataPath("assets/meshes/bunny.obj");
  const std::string missing = resolveDataPath("assets/meshes/none.obj");
  fs::current_path(here);
  EXPECT_TRUE(fs::is_regular_file(mesh)) << mesh;
  EXPECT_EQ(fs::path(mesh).filename(), "bunny.obj");
  EXPECT_TRUE(fs::is_directory(scenes)) << scenes;
  EXPECT_TRUE(fs::is_regular_file(fs::path(scenes) / "concave-mesh.toml")) << scenes;
  EXPECT_EQ(short_name, mesh);
  EXPECT_EQ(local, "assets/meshes/bunny.obj") << "the working directory's file wins";
  EXPECT_EQ(missing, "assets/meshes/none.obj") << "unchanged, for the caller's error";
}

TEST(SceneFile, BadOverridesAreNamed) {
  const InputError a = errorOf(kMinimal, {"fingers.left.n_sgo=lots"});
  EXPECT_EQ(a.file(), "--set fingers.left.n_sgo=lots");
  EXPECT_EQ(a.field(), "fingers.left.n_sgo");
  const InputError b = errorOf(kMinimal, {"fingers.left.nsgo=4"});
  EXPECT_EQ(b.field(), "fingers.left.nsgo");
  EXPECT_NE(std::string(b.what()).find("unknown field"), std::string::npos);
  const InputError c = errorOf(kMinimal, {"fingers.left.n_sgo"});
  EXPECT_NE(std::string(c.what()).find("FIELD=VALUE"), std::string::npos);
}

TEST(SceneFile, DeviceCsvErrorsNameTheLine) {
  const fs::path dir = gf::test::scratchRoot() / "gf_scene_file_test";
  fs::create_directories(dir);
  std::ofstream(dir / "good.csv") << "t,x,y,z\n0,0,0.1,0\n0.5,0,0.05,0\n";
  std::ofstream(dir / "bad.csv") << "t,x,y,z\n0,0,0.1,0\n0.5,0,oops,0\n";
  const sim::DeviceTrack d = readDeviceCsv((dir / "good.csv").string());
  EXPECT_EQ(d.keyframes.size(), 2u);
  EXPECT_NEAR(d.sample(0.25).position.y(), 0.075, 1e-12) << "played back linearly";
  try {
    readDeviceCsv((dir / "bad.csv").string());
    ADD_FAILURE() << "bad CSV accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 3);
    EXPECT_EQ(e.field(), "y");
  }
  // /dev/zero never ends and holds no line break: refused before it is read.
  try {
    readDeviceCsv("/dev/zero");
    ADD_FAILURE() << "/dev/zero accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "/dev/zero");
    EXPECT_NE(std::string(e.what()).find("not a regular file"), std::string::npos) << e.what();
  }
}

// A keyframe's q = [w, x, y, z] is the device's orientation, slerped between keyframes; the
// device table's tilt follows every orientation (q_k * R(tilt_axis, tilt_deg)), settable by --set.
TEST(SceneFileOrientation, KeyframesTakeQFollowedByTheTilt) {
  const std::string text = replaced("keyframes = [ { t = 0.0, p = [0, 0.1, 0] }, { t = 0.2, p = [0, 0.06, 0] } ]",
                                    "keyframes = [ { t = 0.0, p = [0, 0.1, 0], q = [1, 0, 0, 0] },\n"
                                    "  { t = 0.2, p = [0, 0.06, 0], q = [0.7071, 0, 0.7071, 0] } ]\n"
                                    "interpolation = \"linear\"");
  const SessionDesc plain = parseSceneText(text, "scene.toml", "", {});
  const auto& k = plain.scene.fingers[0].device.keyframes;
  EXPECT_TRUE(k[0].orientation.isApprox(sim::Quat::Identity(), 1e-15));
  const sim::Quat quarter(Eigen::AngleAxisd(std::numbers::pi / 2.0, sim::Vec3::UnitY()));
  EXPECT_NEAR(k[1].orientation.norm(), 1.0, 1e-15) << "normalised";
  EXPECT_LT(k[1].orientation.angularDistance(quarter), 1e-4);
  const sim::Quat eighth(Eigen::AngleAxisd(std::numbers::pi / 4.0, sim::Vec3::UnitY()));
  EXPECT_LT(plain.scene.fingers[0].device.sample(0.1).orientation.angularDistance(eighth), 1e-4) << "slerped";

  const std::vector<std::string> tilt_overrides = {"fingers.left.device.tilt_deg=30",
                                                   "fingers.left.device.tilt_axis=[0, 0, 2]"};
  const SessionDesc tilted = parseSceneText(text, "scene.toml", "", tilt_overrides);
  const sim::Quat tilt(Eigen::AngleAxisd(std::numbers::pi / 6.0, sim::Vec3::UnitZ()));
  for (std::size_t i = 0; i < 2; ++i) {
    const sim::Quat expected = (k[i].orientation * tilt).normalized();
    EXPECT_LT(tilted.scene.fingers[0].device.keyframes[i].orientation.angularDistance(expected), 1e-12) << i;
  }
  // The default axis is the device's x; no q and no tilt leaves the identity (a 3-DOF device).
  const std::vector<std::string> about_x_overrides = {"fingers.left.device.tilt_deg=-75"};
  const SessionDesc x = parseSceneText(kMinimal, "scene.toml", "", about_x_overrides);
  const sim::Quat about_x(Eigen::AngleAxisd(-75.0 * std::numbers::pi / 180.0, sim::Vec3::UnitX()));
  EXPECT_LT(x.scene.fingers[0].device.keyframes[1].orientation.angularDistance(about_x), 1e-12);
  const SessionDesc plain_minimal = parseSceneText(kMinimal, "scene.toml", "", {});
  for (const auto& kf : plain_minimal.scene.fingers[0].device.keyframes) {
    EXPECT_EQ(kf.orientation.coeffs(), sim::Quat::Identity().coeffs());
  }
}

// A q that is not four finite numbers within 0.001 of unit length, a tilt beyond +-180 deg and a
// zero tilt axis are refused naming the file, line and field.
TEST(SceneFileOrientation, BadOrientationsAndTiltsAreNamed) {
  const std::string second = "{ t = 0.2, p = [0, 0.06, 0] }";
  struct Case {
    std::string text;
    std::vector<std::string> overrides;
    int line;
    std::string field, reason;
  };
  const Case cases[] = {
      {replaced(second, "{ t = 0.2, p = [0, 0.06, 0], q = [1, 0, 0] }"), {}, 14, "fingers.left.device.keyframes.q",
       "[w, x, y, z]"},
      {replaced(second, "{ t = 0.2, p = [0, 0.06, 0], q = [1, 0, 0, 0.1] }"), {}, 14,
       "fingers.left.device.keyframes.q", "unit quaternion"},
      {replaced(second, "{ t = 0.2, p = [0, 0.06, 0], q = [0, 0, 0, 0] }"), {}, 14,
       "fingers.left.device.keyframes.q", "unit quaternion"},
      {replaced(second, "{ t = 0.2, p = [0, 0.06, 0], q = [1, 0, \"y\", 0] }"), {}, 14,
       "fingers.left.device.keyframes.q", "expected a number"},
      {replaced(second, "{ t = 0.2, p = [0, 0.06, 0], q = [1, 0, nan, 0] }"), {}, 14,
       "fingers.left.device.keyframes.q", "finite"},
      {replaced("[fingers.left.device]\n", "[fingers.left.device]\ntilt_deg = 200\n"), {}, 14,
       "fingers.left.device.tilt_deg", "must be in [-180, 180]"},
      {replaced("[fingers.left.device]\n", "[fingers.left.device]\ntilt_axis = [0, 0, 0]\n"), {}, 14,
       "fingers.left.device.tilt_axis", "non-zero axis"},
      {kMinimal, {"fingers.left.device.tilt_deg=\"steep\""}, 0, "fingers.left.device.tilt_deg", "expected a number"},
  };
  for (const Case& c : cases) {
    const InputError e = errorOf(c.text, c.overrides);
    if (c.overrides.empty()) {
      EXPECT_EQ(e.file(), "scene.toml");
      EXPECT_EQ(e.line(), c.line) << e.what();
    }
    EXPECT_EQ(e.field(), c.field) << e.what();
    EXPECT_NE(std::string(e.what()).find(c.reason), std::string::npos) << e.what();
  }
  // Four hand-written decimals are within the tolerance and are normalised.
  const SessionDesc s = parseSceneText(replaced(second, "{ t = 0.2, p = [0, 0.06, 0], q = [0.9659, 0.2588, 0, 0] }"),
                                       "scene.toml", "", {});
  EXPECT_NEAR(s.scene.fingers[0].device.keyframes[1].orientation.norm(), 1.0, 1e-15);
}

// A device CSV may carry the orientation, qw,qx,qy,qz after the position (all four or none):
// slerped between rows, normalised within 0.001, a bad one named by file, line and column.
TEST(SceneFileOrientation, DeviceCsvTakesAnOrientation) {
  const fs::path dir = gf::test::scratchRoot() / "gf_scene_file_test";
  fs::create_directories(dir);
  std::ofstream(dir / "oriented.csv") << "t,x,y,z,qw,qx,qy,qz\n0,0,0.1,0,1,0,0,0\n1,0,0.05,0,0.7071,0.7071,0,0\n";
  const sim::DeviceTrack d = readDeviceCsv((dir / "oriented.csv").string());
  const sim::Quat eighth(Eigen::AngleAxisd(std::numbers::pi / 4.0, sim::Vec3::UnitX()));
  EXPECT_LT(d.sample(0.5).orientation.angularDistance(eighth), 1e-4);
  EXPECT_NEAR(d.keyframes[1].orientation.norm(), 1.0, 1e-15);
  struct Case {
    std::string text;
    int line, column;
    std::string field, reason;
  };
  const Case cases[] = {
      {"t,x,y,z,qw,qx\n0,0,0,0,1,0\n", 1, 1, "header", "t,x,y,z,qw,qx,qy,qz"},
      {"t,x,y,z,qw,qx,qy,qz\n0,0,0,0,1,0,0\n", 2, 13, "qy", "expected 8 columns"},
      {"t,x,y,z,qw,qx,qy,qz\n0,0,0,0,1,0,0,0,0\n", 2, 15, "qz", "expected 8 columns"},
      {"t,x,y,z,qw,qx,qy,qz\n0,0,0,0,1,0,0,0\n1,0,0,0,2,0,0,0\n", 3, 9, "qw,qx,qy,qz", "unit quaternion"},
      {"t,x,y,z,qw,qx,qy,qz\n0,0,0,0,1,0,nan,0\n", 2, 13, "qy", "expected a finite number"},
      {"t,x,y,z\n0,0,0,0,1,0,0,0\n", 2, 7, "z", "expected 4 columns"},
  };
  for (const Case& c : cases) {
    std::ofstream(dir / "bad_oriented.csv") << c.text;
    try {
      readDeviceCsv((dir / "bad_oriented.csv").string());
      ADD_FAILURE() << "accepted:\n" << c.text;
    } catch (const InputError& e) {
      EXPECT_EQ(e.line(), c.line) << e.what();
      EXPECT_EQ(e.column(), c.column) << e.what();
      EXPECT_EQ(e.field(), c.field) << e.what();
      EXPECT_NE(std::string(e.what()).find(c.reason), std::string::npos) << e.what();
    }
  }
}

// Two bodies on one mesh file share one loaded mesh; the World and the renderer use it without
// reading the file again (it is gone by then).
TEST(SceneFile, EachMeshFileIsReadOnceAndShared) {
  const fs::path dir = gf::test::scratchRoot() / "gf_scene_file_mesh_once";
  fs::create_directories(dir);
  std::ofstream(dir / "tet.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
  const std::string ball = "shape = \"sphere\"\nradius = 0.03\nmass = 0.1";
  std::string text = replaced(ball, "shape = \"mesh\"\nmesh = \"tet.obj\"\nscale = 0.05\ncollision = \"concave\"\nmass = 0.1");
  text += "[bodies.other]\nshape = \"mesh\"\nmesh = \"tet.obj\"\nscale = 0.05\nstatic = true\n";
  const SessionDesc s = parseSceneText(text, "scene.toml", dir.string());
  ASSERT_EQ(s.scene.bodies.size(), 3u);
  ASSERT_TRUE(s.scene.bodies[1].mesh);
  EXPECT_EQ(s.scene.bodies[1].mesh.get(), s.scene.bodies[2].mesh.get());
  fs::remove_all(dir);
  sim::World world(s.scene);
  EXPECT_NEAR((world.bodyPose(1).position - s.scene.bodies[1].position).norm(), 0.0, 1e-12);
  EXPECT_EQ(render::bodyRenderMesh(s.scene.bodies[2]).get(), s.scene.bodies[2].mesh.get());
}

// Rules of the settings' validators reach the scene file's errors: per-shape ranges, legal
// values of scripted overlay input.
TEST(SceneFile, ValidatorErrorsNameTheField) {
  const InputError a = errorOf(replaced("radius = 0.03", "radius = 0.03\nwalk_resolution = 9"));
  EXPECT_EQ(a.field(), "bodies.ball.walk_resolution");
  EXPECT_EQ(a.line(), 9) << a.what();
  EXPECT_NE(std::string(a.what()).find("1..7 for a sphere"), std::string::npos) << a.what();
  const std::string overlay = replaced("\"god_finger\"]", "\"god_finger\", \"overlay\"]") +
                              "[render]\nactions = [{ t = 0.1, widget = \"left/tau_a\", value = \"200\" }]\n";
  const InputError b = errorOf(overlay);
  EXPECT_EQ(b.field(), "render.actions.value");
  EXPECT_NE(std::string(b.what()).find("tau_a must be in [0, 90], got 200"), std::string::npos) << b.what();
  const InputError c = errorOf(kMinimal, {"fingers.left.coupling_stiffness=0"});
  EXPECT_EQ(c.field(), "fingers.left.coupling_stiffness");
  EXPECT_NE(std::string(c.what()).find("(0, 1e+06]"), std::string::npos) << c.what();
}

TEST(BundledScenes, EveryOneLoadsAndRuns) {
  const std::vector<std::string> paths = bundledScenePaths();
  EXPECT_GE(paths.size(), 6u);
  for (const std::string& p : paths) {
    SessionDesc s = loadSceneFile(p);
    s.scene.duration = 0.05;
    sim::World world(s.scene);
    std::vector<sim::DeviceTrack> devices;
    devices = sim::deviceTracks(s.scene);
    const sim::LoopStats stats = sim::runHapticLoop(world, devices, {1000.0, s.scene.duration}, nullptr);
    EXPECT_EQ(stats.steps, 50) << p;
    EXPECT_EQ(world.counters().nan_recoveries, 0) << p;
  }
}

// [expect] is read with its limits, and a body, finger or value it cannot check is named with
// file, line and field.
TEST(SceneFile, ExpectationsAreReadAndBadOnesNamed) {
  const SessionDesc s = parseSceneText(kMinimal + R"(
[expect]
max_speed = 2.0
energy_growth = 0.01
[expect.bodies.ball]
stays_above = 0.01
max_rotation_deg = 5.0
max_drift = 1e-5
max_tilt_deg = 0.01
after = 0.1
rests_after = 0.5
rest_tilt_rate = 0.01
max_roll_ratio = 0.2
roll_window = [0.05, 0.2]
[expect.fingers.left]
min_sgo = 3
window = [0.1, 0.2]
max_force_change = 0.01
)", "scene.toml", "");
  EXPECT_TRUE(s.expect.finite);
  EXPECT_EQ(*s.expect.max_speed, 2.0);
  EXPECT_EQ(*s.expect.energy_growth, 0.01);
  EXPECT_EQ(*s.expect.bodies.at("ball").stays_above, 0.01);
  EXPECT_EQ(*s.expect.bodies.at("ball").max_rotation_deg, 5.0);
  EXPECT_EQ(s.expect.bodies.at("ball").after, 0.1);
  EXPECT_EQ(*s.expect.bodies.at("ball").max_drift, 1e-5);
  EXPECT_EQ(*s.expect.bodies.at("ball").max_tilt_deg, 0.01);
  EXPECT_EQ(*s.expect.fingers.at("left").max_force_change, 0.01);
  EXPECT_EQ(*s.expect.bodies.at("ball").rests_after, 0.5);
  EXPECT_EQ(s.expect.bodies.at("ball").rest_speed, 1e-3);  // the default
  EXPECT_EQ(s.expect.bodies.at("ball").rest_tilt_rate, 0.01);
  EXPECT_EQ(*s.expect.bodies.at("ball").max_roll_ratio, 0.2);
  EXPECT_EQ(s.expect.bodies.at("ball").roll_from, 0.05);
  EXPECT_EQ(s.expect.bodies.at("ball").roll_to, 0.2);
  EXPECT_EQ(*s.expect.fingers.at("left").min_sgo, 3);
  EXPECT_EQ(s.expect.fingers.at("left").from, 0.1);
  EXPECT_STREQ(errorOf(kMinimal + "[expect.bodies.ground]\nstays_above = 0.0\n").what(),
               "scene.toml:15:1: expect.bodies.ground: no dynamic body called 'ground'");
  EXPECT_STREQ(errorOf(kMinimal + "[expect.fingers.thumb]\nmin_sgo = 1\n").what(),
               "scene.toml:15:1: expect.fingers.thumb: no finger called 'thumb'");
  EXPECT_STREQ(errorOf(kMinimal + "[expect]\nmax_speed = -1.0\n").what(),
               "scene.toml:16:13: expect.max_speed: must be in [0, 1e+06], got -1");
  EXPECT_STREQ(errorOf(kMinimal + "[expect]\nmax_sped = 1.0\n").what(),
               "scene.toml:16:12: expect.max_sped: unknown field");
  EXPECT_STREQ(errorOf(kMinimal + "[expect.bodies.ball]\nroll_window = [0.1, 0.2]\n").what(),
               "scene.toml:16:15: expect.bodies.ball.roll_window: without max_roll_ratio it checks nothing");
  EXPECT_STREQ(errorOf(kMinimal + "[expect.bodies.ball]\nmax_roll_ratio = 0.2\nroll_window = [0.2, 0.1]\n").what(),
               "scene.toml:17:15: expect.bodies.ball.roll_window: expected [from, to] in seconds, 0 <= from < to");
  EXPECT_STREQ(errorOf(kMinimal + "[expect.fingers.left]\nmax_force_change = 0.01\n").what(),
               "scene.toml:16:20: expect.fingers.left.max_force_change: needs window = [from, to]: the change is "
               "counted from the force at `from`");
  EXPECT_STREQ(errorOf(kMinimal + "[expect.bodies.ball]\nmax_tilt_deg = 200.0\n").what(),
               "scene.toml:16:16: expect.bodies.ball.max_tilt_deg: must be in [0, 180], got 200");
  const std::string box =
      replaced("shape = \"sphere\"\nradius = 0.03", "shape = \"box\"\nhalf_extents = [0.03, 0.03, 0.03]");
  EXPECT_STREQ(errorOf(box + "[expect.bodies.ball]\nmax_roll_ratio = 0.2\n").what(),
               "scene.toml:16:18: expect.bodies.ball.max_roll_ratio: 'ball' is not a sphere: a roll ratio needs its radius");
}

// Huge but finite numbers that made every step roll back are rejected with their field: a body
// a kilometre away or more, gravity past 10 g, a device keyframe past a kilometre.
TEST(SceneFile, HugeFiniteNumbersAreRejectedWithTheirField) {
  EXPECT_STREQ(errorOf(replaced("position = [0, 0.03, 0]", "position = [1e155, 0.03, 0]")).what(),
               "scene.toml:10:12: bodies.ball.position: every component must be in [-1000, 1000], got 1e+155");
  EXPECT_STREQ(errorOf(kMinimal + "[world]\ngravity = [0, -1e6, 0]\n").what(),
               "scene.toml:16:11: world.gravity: every component must be in [-100, 100], got -1e+06");
  const InputError keyframe = errorOf(replaced("p = [0, 0.06, 0]", "p = [0, 1e308, 0]"));
  EXPECT_NE(std::string(keyframe.what()).find("fingers.left.device.keyframes"), std::string::npos) << keyframe.what();
  EXPECT_NE(std::string(keyframe.what()).find("[-1000, 1000] m"), std::string::npos) << keyframe.what();
}

// A name that cannot be a file name, a trace.csv column or a --set field is rejected where it is
// given (a finger "sub/finger" used to fail after the run, writing its close-up).
TEST(SceneFile, NamesThatCannotNameFilesAndColumnsAreRejected) {
  for (const std::string bad : {"sub/finger", "a,b", "two words", "dot.ted"}) {
    const InputError e = errorOf(replaced("[fingers.left]\n", "[fingers.\"" + bad + "\"]\n"));
    EXPECT_NE(std::string(e.what()).find("a name may hold only letters, digits"), std::string::npos) << e.what();
  }
}

// The coupling must be stable for the finger's proxy at the scene's rate: stiffness up to
// proxy_mass x rate^2 and damping up to proxy_mass x rate are accepted, more is rejected with the
// limit (the hard cases pinch-coupling-* hold at the limits).
TEST(SceneFile, CouplingBeyondItsStabilityLimitIsRejected) {
  const std::vector<std::string> at_limits = {"fingers.left.coupling_stiffness=100000", "fingers.left.coupling_damping=100"};
  EXPECT_NO_THROW(parseSceneText(kMinimal, "scene.toml", "", at_limits));
  const std::string stiff = errorOf(kMinimal, {"fingers.left.coupling_stiffness=100001"}).what();
  EXPECT_NE(stiff.find("fingers.left.coupling_stiffness: must be at most proxy_mass x haptic_rate^2 = 1e+05 N/m"),
            std::string::npos) << stiff;
  const std::string damped = errorOf(kMinimal, {"fingers.left.proxy_mass=0.01", "fingers.left.coupling_damping=11"}).what();
  EXPECT_NE(damped.find("fingers.left.coupling_damping: must be at most proxy_mass x haptic_rate = 10 N s/m"),
            std::string::npos) << damped;
  const std::string rate = errorOf(kMinimal, {"haptic_rate=50"}).what();
  EXPECT_NE(rate.find("haptic_rate"), std::string::npos) << rate;
}

// push_apart's spring between two proxies must be stable too: up to (proxy_mass x rate^2 -
// coupling_stiffness) / 2 (49 600 N/m for the defaults at 1 kHz; overlap-pinch holds there),
// named at world.overlap_stiffness; the other modes do not use it.
TEST(SceneFile, OverlapStiffnessBeyondItsStabilityLimitIsRejected) {
  const std::string text = kMinimal + "[world]\noverlap = \"push_apart\"\noverlap_stiffness = 49601.0\n";
  const InputError e = errorOf(text);
  EXPECT_EQ(e.field(), "world.overlap_stiffness");
  EXPECT_NE(std::string(e.what()).find("scene.toml:17:21: world.overlap_stiffness: must be at most (proxy_mass x "
                                       "haptic_rate^2 - coupling_stiffness) / 2 = 4.96e+04 N/m for finger 'left'"),
            std::string::npos) << e.what();
  const std::vector<std::string> at_limit = {"world.overlap_stiffness=49600"}, merged = {"world.overlap=merge"};
  EXPECT_NO_THROW(parseSceneText(text, "scene.toml", "", at_limit));
  EXPECT_NO_THROW(parseSceneText(text, "scene.toml", "", merged));
  EXPECT_EQ(errorOf(kMinimal, {"world.overlap=shove"}).field(), "world.overlap");
  EXPECT_EQ(errorOf(kMinimal, {"world.overlap_stiffness=5"}).field(), "world.overlap_stiffness");
}

// The contact is a spring too: at the coupling's clamp it lets the proxy in by max_force /
// contact_stiffness, and a proxy radius not above that depth is rejected (a 1 mm proxy at the
// default 40 N and 20000 N/m went 2 mm into a 1 mm wall); the hard case
// press-thin-wall-1mm-proxy holds with 10 N.
TEST(SceneFile, ProxyRadiusMustExceedTheDeepestPress) {
  const std::vector<std::string> held = {"fingers.left.proxy_radius=0.001", "fingers.left.max_force=10"};
  EXPECT_NO_THROW(parseSceneText(kMinimal, "scene.toml", "", held));
  const std::string small = errorOf(kMinimal, {"fingers.left.proxy_radius=0.001"}).what();
  EXPECT_NE(small.find("fingers.left.proxy_radius: must exceed max_force / contact_stiffness = 0.002 m"), std::string::npos)
      << small;
  const std::string soft = errorOf(kMinimal, {"fingers.left.contact_stiffness=4000"}).what();
  EXPECT_NE(soft.find("= 0.01 m"), std::string::npos) << soft;
}

// [expect] reads the penetration and tunnelling checks scene-wide and per finger.
TEST(SceneFile, ExpectReadsPenetrationAndTunnelling) {
  const SessionDesc s = parseSceneText(kMinimal + "[expect]\nno_tunnelling = true\nmax_penetration = 0.001\n"
                                                  "[expect.fingers.left]\nmax_penetration = 0.002\n",
                                       "scene.toml", "");
  EXPECT_TRUE(s.expect.no_tunnelling);
  EXPECT_EQ(s.expect.max_penetration, 0.001);
  EXPECT_EQ(s.expect.fingers.at("left").max_penetration, 0.002);
  const InputError e = errorOf(kMinimal + "[expect]\nmax_penetration = -1\n");
  EXPECT_EQ(e.field(), "expect.max_penetration");
}

// A dynamic body lighter than 1/100 of the heaviest proxy is rejected at its mass, naming the
// proxy (a 1/1000 one tumbled over in a pinch at any solver iterations); so is one below 0.1 g.
TEST(SceneFile, BodiesLighterThanTheSolverHoldsAreRejected) {
  EXPECT_NO_THROW(parseSceneText(kMinimal, "scene.toml", "", std::vector<std::string>{"bodies.ball.mass=0.001"}));
  const InputError ratio = errorOf(kMinimal, {"bodies.ball.mass=0.0009"});
  EXPECT_EQ(ratio.field(), "bodies.ball.mass");
  EXPECT_NE(std::string(ratio.what()).find("at least 1/100 of the heaviest proxy, 0.001 kg here (fingers.left.proxy_mass 0.1 kg)"),
            std::string::npos) << ratio.what();
  const std::vector<std::string> light_proxy = {"fingers.left.proxy_mass=0.0001", "fingers.left.coupling_stiffness=100",
                                                "fingers.left.coupling_damping=0.1", "bodies.ball.mass=0.0001"};
  EXPECT_NO_THROW(parseSceneText(kMinimal, "scene.toml", "", light_proxy));
  EXPECT_EQ(errorOf(kMinimal, {"fingers.left.proxy_mass=0.0001", "fingers.left.coupling_stiffness=100",
                               "fingers.left.coupling_damping=0.1", "bodies.ball.mass=0.00001"}).field(),
            "bodies.ball.mass");
}

}  // namespace
}  // namespace gf::app
