// Inputs the fuzz targets (tests/fuzz) crashed on, in the simulation library: each now gives a
// clean result or a named error. Run by gf_sim_tests (GCC); the inputs are inline or in
// tests/fuzz/regressions/.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <filesystem>
#include <fstream>
#include <random>
#include <stdexcept>
#include <string>

#include "sim/god_finger.hpp"
#include "sim/mesh.hpp"
#include "sim/mesh_import.hpp"

namespace gf::sim {
namespace {

std::string regression(const std::string& name) { return std::string(GF_SOURCE_DIR) + "/tests/fuzz/regressions/" + name; }

// fuzz_mesh: a binary PLY whose first vertex byte is '\n' (the float -0.02), which assimp's
// header reader swallows; it then reads faces without vertices, and its triangulation asserted,
// aborting the process. The same tetrahedron with another first vertex loads.
TEST(FuzzRegression, BinaryPlyFacesWithoutVerticesAreAnErrorNotAnAbort) {
  try {
    loadMesh(regression("mesh-binary-ply-misread-faces.ply"));
    FAIL() << "expected MeshLoadError";
  } catch (const MeshLoadError& e) {
    EXPECT_NE(std::string(e.what()).find("face 0 of mesh 0 has no vertex"), std::string::npos) << e.what();
  }
  const Mesh tetrahedron = loadMesh(regression("mesh-binary-ply-tetrahedron.ply"));
  EXPECT_EQ(tetrahedron.faceCount(), 4);
  EXPECT_EQ(tetrahedron.vertexCount(), 4);
}

// fuzz_patch: welding put a micrometre mesh 100 km from the origin in grid cells counted from
// the origin, p / 1.4e-12 m past the range of int64 (undefined behaviour, reported by UBSan in
// the fuzz and asan-ubsan builds). Cells now count from the mesh's lower bounds.
TEST(FuzzRegression, MicrometreMeshFarFromTheOriginWelds) {
  const Vec3 far(1e8, -1e8, 1e8);
  const Mesh m = buildMesh({far, far + Vec3(1e-6, 0, 0), far + Vec3(0, 1e-6, 0), far + Vec3(1e-6, 1e-6, 0),
                            far + Vec3(1e-6, 0, 0)},
                           {{0, 1, 2}, {4, 3, 2}});
  EXPECT_EQ(m.vertexCount(), 4) << "vertex 4 repeats vertex 1";
  EXPECT_EQ(m.report().welded_vertices, 1);
  EXPECT_EQ(m.faceCount(), 2);
}

// Coordinates whose squares overflow are refused, naming the vertex.
TEST(FuzzRegression, CoordinatesBeyond1e150AreRefused) {
  try {
    buildMesh({Vec3::Zero(), Vec3(1, 0, 0), Vec3(0, 1e200, 0)}, {{0, 1, 2}});
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "mesh vertex 2 lies beyond 1e150 m of the origin");
  }
}

}  // namespace
}  // namespace gf::sim
