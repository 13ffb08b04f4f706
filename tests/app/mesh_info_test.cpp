// `godfinger mesh-info` on files with several parts, a declared unit and up axis, and a size in
// millimetres, against what the files hold by construction.
#include "app/commands/mesh_info.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "app/scene/scene_file.hpp"
#include "app/session/session.hpp"
#include "sim/mesh/mesh_import.hpp"
#include "tests/scratch.hpp"

namespace gf::app {
namespace {

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
  const fs::path dir = gf::test::scratchRoot() / "gf_mesh_info";
  fs::create_directories(dir);
  return dir / name;
}

// A Collada file in centimetres, Z up, whose one tetrahedron (legs 10 units) two nodes place
// 30 units apart: two parts, unit 0.01 m, up Z, applied on reading; a body made of it lists its
// two parts in summary.json.
TEST(MeshInfo, ColladaPartsUnitAndUpAxis) {
  const fs::path path = scratch("two-tetrahedra.dae");
  std::ofstream(path) << R"(<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit name="centimeter" meter="0.01"/><up_axis>Z_UP</up_axis></asset>
  <library_geometries><geometry id="g" name="tetra"><mesh>
    <source id="p"><float_array id="pa" count="12">0 0 0 10 0 0 0 10 0 0 0 10</float_array>
      <technique_common><accessor source="#pa" count="4" stride="3"><param name="X" type="float"/>
      <param name="Y" type="float"/><param name="Z" type="float"/></accessor></technique_common></source>
    <vertices id="v"><input semantic="POSITION" source="#p"/></vertices>
    <triangles count="4"><input semantic="VERTEX" source="#v" offset="0"/><p>0 2 1 0 1 3 0 3 2 1 2 3</p></triangles>
  </mesh></geometry></library_geometries>
  <library_visual_scenes><visual_scene id="s">
    <node id="a" name="a"><instance_geometry url="#g"/></node>
    <node id="b" name="b"><translate>30 0 0</translate><instance_geometry url="#g"/></node>
  </visual_scene></library_visual_scenes>
  <scene><instance_visual_scene url="#s"/></scene>
</COLLADA>
)";
  const nlohmann::json info = meshInfoJson({path.string(), 1.0, 0.0, 1000.0});
  EXPECT_EQ(info["part_count"], 2);
  EXPECT_EQ(info["parts"][1]["node"], "b");
  // The file's numbers are single precision: 1e-7 m.
  EXPECT_NEAR(info["parts"][1]["translation"][0].get<double>(), 0.3, 1e-7);  // 30 cm, in metres
  EXPECT_DOUBLE_EQ(info["declared"]["unit_m"].get<double>(), 0.01);
  EXPECT_EQ(info["declared"]["up_axis"], "Z");
  EXPECT_TRUE(info["declared"]["applied_by_the_importer"].get<bool>());
  EXPECT_TRUE(info["checks"]["closed"].get<bool>());
  EXPECT_TRUE(info["checks"]["outward"].get<bool>());
  // Two tetrahedra with 0.1 m legs: 2 (0.1^3 / 6) m^3.
  EXPECT_NEAR(info["solid"]["volume_m3"].get<double>(), 2.0 * 1e-3 / 6.0, 1e-6 * 2.0 * 1e-3 / 6.0);
  EXPECT_TRUE(info["suggested_scale"].is_null());
  // The size in metres: 0.1 up (Z up turned to Y), 0.4 along x.
  EXPECT_NEAR(info["bounds_m"]["size"][0].get<double>(), 0.4, 1e-7);
  EXPECT_NEAR(info["bounds_m"]["size"][1].get<double>(), 0.1, 1e-7);

  // As a body, both parts join it, and the run's summary.json says so.
  const std::string scene = R"(name = "two-parts"
duration = 0.01
effects = ["gravity"]
[bodies.ground]
shape = "plane"
[bodies.pair]
shape = "mesh"
mesh = ")" + path.string() + R"("
collision = "convex_hull"
mass = 0.2
position = [0, 0.2, 0]
[fingers.f]
[fingers.f.device]
keyframes = [ { t = 0.0, p = [0, 0.5, 0] } ]
)";
  SessionOptions options;
  options.out_dir = scratch("two-parts-run").string();
  options.progress = false;
  runSession(parseSceneText(scene, "two-parts.toml", ""), options);
  std::ifstream in(fs::path(options.out_dir) / "summary.json");
  const nlohmann::json summary = nlohmann::json::parse(in);
  ASSERT_EQ(summary["meshes"].size(), 1u);
  EXPECT_EQ(summary["meshes"][0]["body"], "pair");
  EXPECT_EQ(summary["meshes"][0]["parts"], 2);
  EXPECT_EQ(summary["meshes"][0]["faces"], 8);
  EXPECT_EQ(summary["meshes"][0]["vertices"], 8);
}

// A 50 mm cube written in millimetres: 50 m across at scale 1, so mesh-info suggests 0.001; at
// that scale with 1000 kg/m^3, 0.125 kg, centre at the cube's centre and moments m a^2 / 6.
TEST(MeshInfo, AMillimetreCubeGetsAScaleAndItsSolid) {
  const fs::path path = scratch("cube-mm.obj");
  std::ofstream(path) << "v 0 0 0\nv 50 0 0\nv 50 50 0\nv 0 50 0\nv 0 0 50\nv 50 0 50\nv 50 50 50\nv 0 50 50\n"
                         "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\n"
                         "f 4 1 5\nf 4 5 8\n";
  const nlohmann::json raw = meshInfoJson({path.string(), 1.0, 0.0, 1000.0});
  ASSERT_FALSE(raw["suggested_scale"].is_null());
  EXPECT_DOUBLE_EQ(raw["suggested_scale"].get<double>(), 0.001);
  EXPECT_NE(raw["suggestion"].get<std::string>().find("millimetres"), std::string::npos);
  EXPECT_TRUE(raw["declared"]["unit_m"].is_null());
  const nlohmann::json info = meshInfoJson({path.string(), 0.001, 0.0, 1000.0});
  EXPECT_TRUE(info["suggested_scale"].is_null());
  const nlohmann::json& s = info["solid"];
  EXPECT_NEAR(s["mass_kg"].get<double>(), 0.125, 1e-12);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(s["centre_of_mass_m"][k].get<double>(), 0.025, 1e-12);
    EXPECT_NEAR(s["principal_moments_kg_m2"][k].get<double>(), 0.125 * 0.05 * 0.05 / 6.0, 1e-12);
  }
  EXPECT_EQ(info["part_count"], 1);
}

// An open mesh (the cube without its top) is reported with its boundary edges and no solid.
TEST(MeshInfo, AnOpenMeshCountsItsBoundaryAndHasNoSolid) {
  const fs::path path = scratch("open-box.obj");
  std::ofstream(path) << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
                         "f 1 3 2\nf 1 4 3\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n";
  const nlohmann::json info = meshInfoJson({path.string(), 0.01, 0.0, 1000.0});
  EXPECT_FALSE(info["checks"]["closed"].get<bool>());
  EXPECT_EQ(info["checks"]["boundary_edges"], 4);
  EXPECT_TRUE(info["solid"].is_null());
  EXPECT_NE(meshInfoText(info).find("closed: no (4 boundary edges"), std::string::npos) << meshInfoText(info);
  EXPECT_NE(info["solid_why_not"].get<std::string>().find("not closed (4 boundary and 0 non-manifold edges)"),
            std::string::npos)
      << "the words the scene reader refuses a dynamic body of it with";
}

// A file that is not a mesh: MeshLoadError naming it.
TEST(MeshInfo, NotAMeshNamesTheFile) {
  const fs::path path = scratch("not-a-mesh.obj");
  std::ofstream(path) << "hello\n";
  try {
    meshInfoJson({path.string(), 1.0, 0.0, 1000.0});
    FAIL() << "no error";
  } catch (const sim::MeshLoadError& e) {
    EXPECT_NE(std::string(e.what()).find("not-a-mesh.obj"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace gf::app
