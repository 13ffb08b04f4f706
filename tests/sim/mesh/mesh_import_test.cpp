#include "sim/mesh/mesh_import.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include "tests/scratch.hpp"

namespace gf::sim {
namespace {

namespace fs = std::filesystem;

// The tetrahedron (0,0,0) (1,0,0) (0,1,0) (0,0,1), outward winding, in each format.
const char* kObj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
const char* kOff = "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
const char* kPly =
    "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
    "property float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n"
    "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
const char* kGltf =
    R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
    R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],"buffers":[{"byteLength":72,)"
    R"("uri":"data:application/octet-stream;base64,)"
    R"(AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAAAAAAAAAAAAIA/AAACAAEAAAABAAMAAAADAAIAAQACAAMA"}],)"
    R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":48},{"buffer":0,"byteOffset":48,)"
    R"("byteLength":24}],"accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3",)"
    R"("min":[0,0,0],"max":[1,1,1]},{"bufferView":1,"componentType":5123,"count":12,"type":"SCALAR"}]})";

std::string stlText() {
  const double v[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const int f[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  std::string s = "solid tet\n";
  for (const auto& t : f) {
    s += "facet normal 0 0 0\nouter loop\n";
    for (int k : t) {
      s += "vertex " + std::to_string(v[k][0]) + " " + std::to_string(v[k][1]) + " " +
           std::to_string(v[k][2]) + "\n";
    }
    s += "endloop\nendfacet\n";
  }
  return s + "endsolid tet\n";
}

class MeshImport : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = gf::test::scratchRoot() /
           ("gf_mesh_import_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string write(const std::string& name, const std::string& text) {
    const fs::path p = dir_ / name;
    std::ofstream(p) << text;
    return p.string();
  }
  // The refusal of `text` written as `name`, after the file's path; "accepted" if it loads.
  std::string message(const std::string& name, const std::string& text) {
    try {
      loadMesh(write(name, text));
    } catch (const MeshLoadError& e) {
      return std::string(e.what()).substr((dir_ / name).string().size());
    }
    return std::string("accepted");
  }
  fs::path dir_;
};

TEST_F(MeshImport, ReadsEveryFormatAsTheSameClosedTetrahedron) {
  const std::pair<const char*, std::string> files[] = {
      {"tet.obj", kObj}, {"tet.off", kOff}, {"tet.ply", kPly}, {"tet.stl", stlText()}, {"tet.gltf", kGltf}};
  for (const auto& [name, text] : files) {
    SCOPED_TRACE(name);
    const Mesh m = loadMesh(write(name, text), 2.0);
    EXPECT_EQ(m.vertexCount(), 4) << "STL repeats vertices per facet: welding joins them";
    EXPECT_EQ(m.faceCount(), 4);
    EXPECT_EQ(m.report().boundary_edges, 0);
    EXPECT_NEAR(std::abs(m.signedVolume()), 8.0 / 6.0, 1e-6) << "scale 2 gives volume 8/6";
  }
}

TEST_F(MeshImport, MissingFileNamesThePath) {
  const std::string path = (dir_ / "nope.obj").string();
  try {
    loadMesh(path);
    FAIL() << "expected MeshLoadError";
  } catch (const MeshLoadError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

TEST_F(MeshImport, FileWithoutTrianglesIsAnError) {
  EXPECT_THROW(loadMesh(write("points.obj", "v 0 0 0\nv 1 0 0\n")), MeshLoadError);
}

TEST_F(MeshImport, AllDegenerateTrianglesIsAnError) {
  EXPECT_THROW(loadMesh(write("flat.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n")), MeshLoadError);
}

// Headers that lie about what the file holds are rejected with the file, line and the first bad
// element before anything is allocated for them (the importer would abort the process on some,
// and reserve gigabytes for others); a face naming a vertex the file lacks is rejected too.
TEST_F(MeshImport, LyingHeadersAndBadIndicesAreRejectedNamingTheElement) {
  const std::string pad = "# padding so the size check alone does not catch it ............................\n";
  EXPECT_EQ(message("huge.off", "OFF\n1000000000 1000000000 0\n"),
            ":2: OFF header promises 1000000000 vertices and 1000000000 faces, more than its 28 bytes can hold");
  EXPECT_EQ(message("short.off", "OFF\n" + pad + "4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n3 0 1 3\n"),
            ": OFF header counts 4 vertices and 4 faces; the file holds 4 and 2");
  EXPECT_EQ(message("index.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n"), ":6: OFF face 0 names vertex 7 of 3");
  std::string stl(84, '\0');
  const std::uint32_t count = 1000000;
  std::memcpy(stl.data() + 80, &count, 4);
  EXPECT_EQ(message("huge.stl", stl), ": binary STL header promises 1000000 triangles, more than its 84 bytes hold");
  EXPECT_EQ(message("huge.ply", "ply\nformat ascii 1.0\nelement vertex 900000000\nproperty float x\nend_header\n"),
            ": PLY header promises 900000000 elements, more than its 74 bytes hold");
}

// OFF as CGAL's data set writes it: comments before the keyword, after the counts, among the
// vertices and faces and after a value on its line, blank lines anywhere, colours after a face.
TEST_F(MeshImport, OffCommentsAnywhereAreRead) {
  const std::string text =
      "# Output of a tool\n#CBP\n\nOFF # keyword\n4 4 0\n\n# 4 vertices\n# ----\n0 0 0\n1 0 0 # red\n"
      "\n0 1 0\n# a comment among the vertices\n0 0 1\n# 4 facets\n3 0 2 1 0.9 0 0\n# among the faces\n"
      "3 0 1 3\n3 0 3 2#blue\n3 1 2 3\n# after the faces\n";
  const Mesh m = loadMesh(write("cgal.off", text));
  EXPECT_EQ(m.vertexCount(), 4);
  EXPECT_EQ(m.faceCount(), 4);
  EXPECT_NEAR(massProperties(m).volume, 1.0 / 6.0, 1e-12) << "outward winding kept";
  const MeshFileInfo info = describeMeshFile(write("info.off", text));
  ASSERT_EQ(info.parts.size(), 1u);
  EXPECT_EQ(info.parts[0].vertices, 4);
  EXPECT_EQ(info.parts[0].triangles, 4);
}

// Counts that disagree with the lines an OFF file holds are refused both ways, naming the line:
// a vertex more than the header counts (read as a face it is not), a face more, a vertex or
// face fewer.
TEST_F(MeshImport, OffCountsThatDisagreeWithTheFileAreRefusedBothWays) {
  const std::string vertices = "0 0 0\n1 0 0\n0 1 0\n0 0 1\n";
  const std::string faces = "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  const std::string pad = "# padding so the size check alone does not catch it ..............................\n";
  EXPECT_EQ(message("fewer-v.off", "OFF\n3 4 0\n" + vertices + faces), ":6: OFF face 0: expected a vertex count, got '0'")
      << "the fourth vertex line read as a face";
  EXPECT_EQ(message("fewer-v2.off", "OFF\n3 4 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n" + faces),
            ":8: OFF face 2 names vertex 3 of 3")
      << "a fourth vertex that reads as a line face (skipped) still leaves a face naming a vertex beyond the count";
  EXPECT_EQ(message("fewer-f.off", "OFF\n4 3 0\n" + vertices + faces),
            ":10: OFF header counts 4 vertices and 3 faces; the file holds more (this line is beyond them)");
  EXPECT_EQ(message("more-v.off", "OFF\n" + pad + "5 4 0\n" + vertices + faces),
            ": OFF header counts 5 vertices and 4 faces; the file holds 5 and 3")
      << "a face line read as the fifth vertex";
  EXPECT_EQ(message("more-f.off", "OFF\n" + pad + "4 5 0\n" + vertices + faces),
            ": OFF header counts 4 vertices and 5 faces; the file holds 4 and 4");
  EXPECT_EQ(message("exact.off", "OFF\n4 4 0\n" + vertices + faces), "accepted");
}

// Polygons of any size are split into triangles: an L-shaped (non-convex) hexagon of area 3 by
// ear clipping, so no triangle lies outside it; a point and a line face are skipped.
TEST_F(MeshImport, OffPolygonsOfAnySizeAreSplitIntoTriangles) {
  const std::string l_shape = "OFF\n6 3 0\n0 0 0\n2 0 0\n2 1 0\n1 1 0\n1 2 0\n0 2 0\n6 0 1 2 3 4 5\n1 0\n2 0 1\n";
  const Mesh m = loadMesh(write("l.off", l_shape));
  EXPECT_EQ(m.faceCount(), 4);
  double area = 0.0;
  for (int f = 0; f < m.faceCount(); ++f) {
    const Vec3 n = (m.corner(f, 1) - m.corner(f, 0)).cross(m.corner(f, 2) - m.corner(f, 0));
    EXPECT_GT(n.z(), 0.0) << "every triangle wound as the polygon";
    area += 0.5 * n.norm();
  }
  EXPECT_NEAR(area, 3.0, 1e-12);
  std::string twelve = "OFF\n12 1 0\n";
  for (int k = 0; k < 12; ++k) twelve += std::to_string(std::cos(k * 0.5235987755982988)) + " " + std::to_string(std::sin(k * 0.5235987755982988)) + " 0\n";
  twelve += "12 0 1 2 3 4 5 6 7 8 9 10 11\n";
  EXPECT_EQ(loadMesh(write("twelve.off", twelve)).faceCount(), 10) << "the importer skipped faces of more than 9";
}

// Binary STL and PLY element counts against the data, both ways.
TEST_F(MeshImport, StlAndPlyCountsThatDisagreeWithTheDataAreRefusedBothWays) {
  std::string stl(84 + 2 * 50, '\0');
  const std::uint32_t one = 1;
  std::memcpy(stl.data() + 80, &one, 4);
  const float tri[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  for (int t = 0; t < 2; ++t) std::memcpy(stl.data() + 84 + 50 * t + 12, tri, sizeof tri);
  EXPECT_EQ(message("more.stl", stl),
            ": binary STL header counts 1 triangles; the file holds 50 bytes more, room for 1 more (a wrong count would drop them)");
  EXPECT_EQ(message("one.stl", stl.substr(0, 84 + 50)), "accepted");
  const std::string head = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                           "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  EXPECT_EQ(message("more.ply", head + "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n"),
            ": PLY header counts 4 elements (vertex 3, face 1); the file holds 5 lines of them");
  EXPECT_EQ(message("fewer.ply", head + "0 0 0\n1 0 0\n3 0 1 2\n"),
            ": PLY header counts 4 elements (vertex 3, face 1); the file holds 3 lines of them");
  EXPECT_EQ(message("exact.ply", head + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n\n"), "accepted");
  std::string bin = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                    "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  bin.append(reinterpret_cast<const char*>(tri), sizeof tri);
  const unsigned char face[13] = {3, 0, 0, 0, 0, 1, 0, 0, 0, 2, 0, 0, 0};
  bin.append(reinterpret_cast<const char*>(face), sizeof face);
  EXPECT_EQ(message("exact-bin.ply", bin), "accepted");
  EXPECT_EQ(message("more-bin.ply", bin + std::string(reinterpret_cast<const char*>(face), sizeof face)),
            ": PLY header counts vertex 3, face 1; the file holds 13 bytes more after them (a wrong count would drop them)");
  EXPECT_EQ(message("fewer-bin.ply", bin.substr(0, bin.size() - 4)),
            ": PLY header counts vertex 3, face 1; the file ends before the last of them (4 bytes short)");
}

// An FBX file's own unit is applied on reading: UnitScaleFactor counts centimetres, so 2.54 is
// an inch and a tetrahedron 10 units on a side is 0.254 m on a side, at scale 1 and as
// describeMeshFile reports it (mesh-info and run read the same metres).
TEST_F(MeshImport, FbxDeclaredUnitIsApplied) {
  const std::string fbx = R"(; FBX 7.4.0 project file
FBXHeaderExtension:  {
	FBXHeaderVersion: 1003
	FBXVersion: 7400
}
GlobalSettings:  {
	Version: 1000
	Properties70:  {
		P: "UpAxis", "int", "Integer", "",1
		P: "UpAxisSign", "int", "Integer", "",1
		P: "UnitScaleFactor", "double", "Number", "",2.54
	}
}
Objects:  {
	Geometry: 100, "Geometry::tet", "Mesh" {
		Vertices: *12 {
			a: 0,0,0,10,0,0,0,10,0,0,0,10
		}
		PolygonVertexIndex: *12 {
			a: 0,2,-2,0,1,-4,0,3,-3,1,2,-4
		}
		GeometryVersion: 124
	}
	Model: 200, "Model::tet", "Mesh" {
		Version: 232
	}
}
Connections:  {
	C: "OO",200,0
	C: "OO",100,200
}
)";
  const std::string path = write("inch.fbx", fbx);
  const Mesh m = loadMesh(path);
  EXPECT_NEAR((m.boundsMax() - m.boundsMin()).maxCoeff(), 0.254, 1e-7);
  EXPECT_NEAR(massProperties(m).volume, 0.254 * 0.254 * 0.254 / 6.0, 1e-8);
  EXPECT_NEAR((loadMesh(path, 0.5).boundsMax()).maxCoeff(), 0.127, 1e-7) << "scale multiplies the declared unit";
  const MeshFileInfo info = describeMeshFile(path);
  EXPECT_NEAR(info.declared_unit_m, 0.0254, 1e-9);  // the importer keeps the factor as a float
  EXPECT_TRUE(info.unit_applied);
  EXPECT_FALSE(info.unit_and_up_applied) << "the up axis is not applied";
}

TEST_F(MeshImport, BadScaleIsAnError) {
  EXPECT_THROW(loadMesh(write("tet.obj", kObj), 0.0), MeshLoadError);
  EXPECT_THROW(loadMesh(write("tet2.obj", kObj), NAN), MeshLoadError);
}

// A file used twice at one scale is read once; another scale is another mesh. The cached mesh
// stays usable after the file is gone (the World and the renderer never read it again).
TEST_F(MeshImport, CacheReadsEachFileOncePerScale) {
  const std::string path = write("tet.obj", kObj);
  MeshCache cache;
  const std::shared_ptr<const Mesh> a = cache.load(path, 1.0), b = cache.load(path, 1.0);
  EXPECT_EQ(a.get(), b.get());
  EXPECT_EQ(cache.filesRead(), 1);
  const std::shared_ptr<const Mesh> c = cache.load(path, 2.0);
  EXPECT_NE(a.get(), c.get());
  EXPECT_EQ(cache.filesRead(), 2);
  fs::remove(path);
  EXPECT_EQ(cache.load(path, 1.0).get(), a.get());
  EXPECT_EQ(a->faceCount(), 4);
  EXPECT_THROW(cache.load((dir_ / "missing.obj").string(), 1.0), MeshLoadError);
}

}  // namespace
}  // namespace gf::sim
