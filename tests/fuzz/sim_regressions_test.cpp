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

}  // namespace
}  // namespace gf::sim
