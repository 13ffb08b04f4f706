#include "sim/mesh_import.hpp"

#include <gtest/gtest.h>

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
  const auto message = [&](const std::string& name, const std::string& text) {
    try {
      loadMesh(write(name, text));
    } catch (const MeshLoadError& e) {
      return std::string(e.what()).substr((dir_ / name).string().size());
    }
    return std::string("accepted");
  };
  const std::string pad = "# padding so the size check alone does not catch it ............................\n";
  EXPECT_EQ(message("huge.off", "OFF\n1000000000 1000000000 0\n"),
            ":2: OFF header promises 1000000000 vertices and 1000000000 faces, more than its 28 bytes can hold");
  EXPECT_EQ(message("short.off", "OFF\n" + pad + "4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n3 0 1 3\n"),
            ": OFF header promises 4 vertices and 4 faces; the file holds 4 and 2");
  EXPECT_EQ(message("index.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n"), ":6: OFF face 0 names vertex 7 of 3");
  std::string stl(84, '\0');
  const std::uint32_t count = 1000000;
  std::memcpy(stl.data() + 80, &count, 4);
  EXPECT_EQ(message("huge.stl", stl), ": binary STL header promises 1000000 triangles, more than its 84 bytes hold");
  EXPECT_EQ(message("huge.ply", "ply\nformat ascii 1.0\nelement vertex 900000000\nproperty float x\nend_header\n"),
            ": PLY header promises 900000000 elements, more than its 74 bytes hold");
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
