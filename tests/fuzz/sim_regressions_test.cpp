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

#include "sim/patch/god_finger.hpp"
#include "sim/mesh/mesh.hpp"
#include "sim/mesh/mesh_import.hpp"
#include "tests/scratch.hpp"

namespace gf::sim {
namespace {

std::string regression(const std::string& name) { return std::string(GF_SOURCE_DIR) + "/tests/fuzz/regressions/" + name; }

// What loading `text` as a mesh file called `name` throws (without the path), or "accepted".
std::string loadError(const std::string& name, const std::string& text) {
  const std::filesystem::path dir = gf::test::scratchRoot() / "gf_fuzz_regressions";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / name).string();
  std::ofstream(path, std::ios::binary) << text;
  try {
    loadMesh(path);
  } catch (const MeshLoadError& e) {
    return std::string(e.what()).substr(path.size());
  }
  return "accepted";
}

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

// fuzz_mesh: assimp's PLY reader looped forever (seeking) on a header without an end_header
// line; "end_headerX" is not one either, nor "end_header" glued to a vertical tab.
TEST(FuzzRegression, PlyHeaderWithoutItsEndIsAnErrorNotAHang) {
  const std::string header = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                             "property float z\n";
  EXPECT_EQ(loadError("open.ply", header + "end_he 1\n0 0 0\n1 0 0\n0 1 0\n"), ": PLY header has no end_header line");
  EXPECT_EQ(loadError("suffix.ply", header + "end_headerX\n0 0 0\n1 0 0\n0 1 0\n"),
            ": PLY header has no end_header line");
  // The importer splits a header line at spaces and tabs only: after a vertical tab or a form
  // feed the word goes on, and no header ends there (regression-ply-vertical-tab-end-header).
  EXPECT_EQ(loadError("vertical-tab.ply", header + "end_header\v0 0 0\n1 0 0\n0 1 0\n"),
            ": PLY header has no end_header line");
  EXPECT_EQ(loadError("form-feed.ply", header + "end_header\f\n0 0 0\n1 0 0\n0 1 0\n"),
            ": PLY header has no end_header line");
  EXPECT_EQ(loadError("tab.ply", header + "element face 1\nproperty\tlist uchar int vertex_indices\nend_header \t\n"
                                           "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"),
            "accepted")
      << "tabs and spaces part a header line's words";
  EXPECT_EQ(loadError("triangle.ply", header + "element face 1\nproperty list uchar int vertex_indices\n  end_header\r\n"
                                                "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"),
            "accepted")
      << "an end_header line may start with spaces and end with a carriage return";
}

// fuzz_mesh: an OFF vertex count of 1e38 was cast to long long for the error message
// (undefined behaviour); counts beyond 1e15 are now written as numbers.
TEST(FuzzRegression, HugeHeaderCountsAreNamedNotCast) {
  EXPECT_EQ(loadError("huge.off", "OFF\n1e38 1 0\n0 0 0\n"),
            ":2: OFF header promises 1e+38 vertices and 1 faces, more than its 19 bytes can hold");
  EXPECT_EQ(loadError("huge.ply", "ply\nformat ascii 1.0\nelement vertex 1e38\nend_header\n"),
            ": PLY header promises 1e+38 elements, more than its 52 bytes hold");
}

// fuzz_mesh: an ASCII PLY face whose list count (uchar) read 42949672953: assimp sized the list by
// it before reading its items, asking for 32 GB (out of memory under ASan, a crash). A list's
// count must now be a whole number its type holds with that many items on its line; a binary
// list's negative count (read unsigned by assimp: 4e9 items) is refused too.
TEST(FuzzRegression, PlyListCountsBeyondTheirLineOrTypeAreRefusedNotAllocated) {
  const std::string header = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                             "property float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n"
                             "0 0 0\n1 0 0\n0 1 0\n0 0 1\n";
  const std::string faces = "3 0 2 1\n3 0 1 3\n3 1 2 3\n";
  EXPECT_EQ(loadError("tetrahedron.ply", header + faces + "3 2 0 3\n"), "accepted");
  EXPECT_EQ(loadError("huge-list.ply", header + "42949672953 0 1 2\n" + faces),
            ":14: PLY face property 1: list count '42949672953' is not a whole number from 0 to 255");
  EXPECT_EQ(loadError("negative-list.ply", header + faces + "-1 2 0 3\n"),
            ":17: PLY face property 1: list count '-1' is not a whole number from 0 to 255");
  EXPECT_EQ(loadError("short-list.ply", header + faces + "4 2 0 3\n"),
            ":17: PLY face property 1: list counts 4 items; the line holds 3");
  // Words assimp reads only in part: its readers stop where they stop taking characters, so
  // "4000000000e-9" is a count of 4e9 to it and "0+4000000000" a 0 followed by a count of 4e9.
  EXPECT_EQ(loadError("exponent-count.ply", header + faces + "4000000000e-9 2 0 3 1\n"),
            ":17: PLY face property 1: list count '4000000000e-9' is not a whole number from 0 to 255");
  EXPECT_EQ(loadError("glued-words.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                         "property float z\nelement face 1\nproperty float q\n"
                                         "property list int int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n"
                                         "0+4000000000 3 0 1 2\n"),
            ":14: PLY face property 1: '0+4000000000' is not a number");
  EXPECT_EQ(loadError("hex-index.ply", header + faces + "3 2 0x1 3\n"),
            ":17: PLY face property 1: item '0x1' is not a whole number");
  EXPECT_EQ(loadError("float-count.ply", "ply\nformat binary_little_endian 1.0\nelement face 1\n"
                                         "property list double int vertex_indices\nend_header\n"),
            ":4: PLY property: a list's count type must be an integer type, got 'double'");
  EXPECT_EQ(loadError("short-vertex.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                                          "property float y\nend_header\n0 0\n1\n0 1\n"),
            ":8: PLY vertex property 2: the line ends before it");
  std::string binary = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                       "property float z\nelement face 1\nproperty list char int vertex_indices\nend_header\n";
  const std::size_t body = binary.size();
  binary += std::string(36, '\0') + std::string(1, '\xff') + std::string(12, '\0');
  EXPECT_EQ(loadError("negative-binary-list.ply", binary),
            ": PLY face 0 (byte " + std::to_string(body + 36) + "): a list's count is negative");
}

// fuzz_mesh: assimp's OFF reader took a missing edge count from the next line, and counted a
// face it skipped (a comment line among the faces, a face of 0 or more than 9 vertices) out of
// the face count without moving on: two wrapped the count around and it read far past its faces,
// a segmentation fault. OFF is read by our own reader now: comments anywhere and long faces are
// read, a face of 0 vertices and counts the file does not hold are refused naming the line.
TEST(FuzzRegression, OffLinesTheImporterMisreadAreReadOrRefusedNotACrash) {
  const std::string triangle = "0 0 0\n1 0 0\n0 1 0\n";
  EXPECT_EQ(loadError("edges.off", "OFF\n1 1 \n 0\n1 0 0\n 0.02\nv 1 2 3\n"),
            ":3: OFF vertex 0: expected 3 coordinates")
      << "the edge count is optional: the counts line ends the header";
  EXPECT_EQ(loadError("comments.off", "OFF\n3 1 0\n" + triangle + "# c\n# d\n3 0 1 2\n"), "accepted");
  EXPECT_EQ(loadError("colours.off", "COFF\n3 1 0\n" + triangle + "# c\n# d\n3 0 1 2\n"), "accepted");
  EXPECT_EQ(loadError("zero.off", "OFF\n3 1 0\n" + triangle + "0\n"), ":6: OFF face 0: expected a vertex count, got '0'");
  EXPECT_EQ(loadError("headless.off", "4294967295 327 0\n0 0 0\n"),
            ":1: OFF header promises 4294967295 vertices and 327 faces, more than its 23 bytes can hold")
      << "without the OFF keyword the counts come first; the importer reserved 3.5 GB for them";
  EXPECT_EQ(loadError("after.off", "OFF\n3 1 0\n" + triangle + "3 0 1 2\n# c\n# d\n"), "accepted");
}

// fuzz_mesh (an out-of-memory stop in CI): "N219647295 327 s" starts neither with the OFF
// keyword nor with a digit; the importer read the N (normals) prefix without a keyword and
// reserved 219 million vertices. Our reader refuses a first word that is neither; nOFF (a
// dimension before the counts) is read when the dimension is 3.
TEST(FuzzRegression, OffPrefixWithoutTheKeywordCannotReserveGigabytes) {
  const std::string input("N219647295 327 s\0\x1a" "142949\n", 25);
  EXPECT_EQ(loadError("prefix.off", input),
            ":1: OFF header: expected the OFF keyword or the vertex, face and edge counts, got 'N219647295'");
  EXPECT_EQ(loadError("next.off", "N\n3 1000000 0\n"),
            ":1: OFF header: expected the OFF keyword or the vertex, face and edge counts, got 'N'");
  EXPECT_EQ(loadError("noff.off", "nOFF\n3\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"), "accepted");
  EXPECT_EQ(loadError("noff4.off", "nOFF\n4\n3 1 0\n0 0 0 0\n"), ":2: OFF header: dimension 4: only 3 is read");
}

// fuzz_mesh: a PLY header with a garbled format word (two headers run together) kept the importer
// busy for over a minute (a timeout); so might a property of an unknown type. Both are refused
// before the importer sees them, naming the line (corpus input regression-ply-garbled-format).
TEST(FuzzRegression, APlyWithAGarbledFormatOrPropertyIsRefused) {
  const std::string head = "ply\nformat binary_Litbinary_big_endiantle_endian 1.0e\nelement vertex 4\n";
  EXPECT_EQ(loadError("garbled.ply", head + "property float x\nend_header\n"),
            ":2: PLY format: expected ascii, binary_little_endian or binary_big_endian, got "
            "'binary_Litbinary_big_endiantle_endian'");
  EXPECT_EQ(loadError("unknown.ply", "ply\nformat ascii 1.0\nelement face 1\nproperty l]st uchar int vertex_indices\n"
                                     "end_header\n3 0 1 2\n"),
            ":4: PLY property: unknown type in 'property l]st uchar int vertex_indices'");
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

// fuzz_patch: the closest point on a sliver came from barycentric coordinates whose
// cancellation grows with the square of the aspect ratio: on a tilted 10 cm x 1 um triangle the
// closest point to a point of it lay 2.3e-8 m away (an SGO checked against the surface seemed
// to have left it). The face point is now the projection on the face's plane.
TEST(FuzzRegression, ClosestPointOnASliverIsThePointItself) {
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  const Mesh m = buildMesh({turn * Vec3(0, 0, 0), turn * Vec3(0.1, 0, 0), turn * Vec3(0.07, 1e-6, 0)}, {{0, 1, 2}});
  ASSERT_EQ(m.faceCount(), 1);
  std::mt19937 rng(14);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  double worst = 0.0;
  for (int i = 0; i < 1000; ++i) {
    double a = u(rng), b = u(rng);
    if (a + b > 1.0) a = 1.0 - a, b = 1.0 - b;
    const Vec3 p = m.corner(0, 0) + a * (m.corner(0, 1) - m.corner(0, 0)) + b * (m.corner(0, 2) - m.corner(0, 0));
    worst = std::max(worst, m.closestPoint(p, 0.0).query_distance);
  }
  EXPECT_LT(worst, 1e-12) << "rounding of the point itself is about 1e-17 m";
}

// fuzz_patch: on a 7e36 m sliver (its long edges 1.1e28 m apart there) the closest-point
// regions' tests cancel, and a point on one long edge was taken for the other's region: the
// "closest" point lay 1.1e28 m away, 1.6e-9 of the mesh's size. Each edge's nearest point now
// checks the region's (corpus input regression-sliver-edge-region).
TEST(FuzzRegression, APointOnAHugeSliversEdgeIsItsOwnClosestPoint) {
  const Mesh m = buildMesh({{6.8538318532659725e+36, 0.014223783613220187, -6.0322268731608177e+32},
                            {-169795279.99733189, 0.014223783612589802, 0.0010074474073731713},
                            {-2.0385139284099243e+32, 0.014223783612589802, 0.0010074474073736783}},
                           {{0, 1, 2}});
  ASSERT_EQ(m.faceCount(), 1);
  const Vec3 on_edge(2.6475656904411401e+36, 0.014223783612833324, -2.3302981298056594e+32);
  EXPECT_LE(m.closestPoint(on_edge, 0.0).query_distance, 1e-9 * 6.85e36);
}

// The fuzz_patch input that found it: a 1.9e41 m sliver, pressed; every SGO lies on the surface
// within 1e-9 of the mesh's scale.
TEST(FuzzRegression, PatchOnAHugeSliverStaysOnTheSurface) {
  const Mesh m = buildMesh({{484241657823232, 0.039812088012695312, -1.8544598878572408e-34},
                            {-8.3476574658685477e+35, -2.4708001272466709e+36, 1.320746876354231e-19},
                            {1.8846565061092344e+41, 1.3746478262245645e-18, -1802616296177664}},
                           {{2, 1, 0}});
  ASSERT_EQ(m.faceCount(), 1);
  PatchContact c;
  c.point_local = Vec3(1.6498496734660572e+41, -4.8257820746493402e+33, 1.4098609602285082e+38);
  c.outward_normal_local = Vec3(-9.5646940985498847e-27, 3.2314548319677619e-27, -1);
  c.separation = -1.16821e-08;
  PatchSettings s;
  s.n_sgo = 61;
  s.r_max = 0.0400391;
  s.d0 = 1e-6;
  Patch p;
  computePatch(m, c, Vec3(0, 0, 1.1099888093108006e-12), s, p);
  ASSERT_TRUE(p.valid);
  ASSERT_EQ(p.sgos.size(), 61u);
  for (const Sgo& sgo : p.sgos) {
    EXPECT_LE(m.closestPoint(sgo.position, 0.0).query_distance, 1e-9 * m.diagonal());
  }
}

}  // namespace
}  // namespace gf::sim
