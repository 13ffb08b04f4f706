#include "sim/soft/fem_solid.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace gf::sim {
namespace {

// A box of nx × ny × nz cells of `cell` m (y up, its base at y = 0), each cell split into six
// tetrahedra along its diagonal (the pad's split), every one positively oriented.
TetMesh boxMesh(int nx, int ny, int nz, double cell) {
  TetMesh m;
  const auto index = [&](int i, int j, int k) { return (k * (nz + 1) + j) * (nx + 1) + i; };
  for (int k = 0; k <= ny; ++k) {
    for (int j = 0; j <= nz; ++j) {
      for (int i = 0; i <= nx; ++i) m.nodes.emplace_back(i * cell, k * cell, j * cell);
    }
  }
  static constexpr int kOrders[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int k = 0; k < ny; ++k) {
    for (int j = 0; j < nz; ++j) {
      for (int i = 0; i < nx; ++i) {
        const auto corner = [&](int bits) { return index(i + (bits & 1), j + ((bits >> 1) & 1), k + ((bits >> 2) & 1)); };
        for (const auto& order : kOrders) {
          std::array<int, 4> t{corner(0), corner(1 << order[0]), corner((1 << order[0]) | (1 << order[1])), corner(7)};
          const auto& p = m.nodes;
          if (tetVolume(p[t[0]], p[t[1]], p[t[2]], p[t[3]]) < 0.0) std::swap(t[1], t[2]);
          m.tets.push_back(t);
        }
      }
    }
  }
  return m;
}

// Node (i, j) of the top face of boxMesh(n, layers, n, ...).
int topNode(int n, int layers, int i, int j) { return (layers * (n + 1) + j) * (n + 1) + i; }

// A load `force` (N, down) spread evenly over the top face of boxMesh(n, layers, n, cell): each
// of its triangles (the split's diagonal on every face runs from its lowest corner to its
// highest) takes a third of its share at each corner.
void addTopLoad(int n, int layers, double cell, double force, std::vector<Vec3>& load) {
  const double share = force * (cell * cell / 2.0) / ((n * cell) * (n * cell)) / 3.0;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      for (const auto& tri : {std::array<int, 3>{topNode(n, layers, i, j), topNode(n, layers, i + 1, j),
                                                 topNode(n, layers, i + 1, j + 1)},
                              std::array<int, 3>{topNode(n, layers, i, j), topNode(n, layers, i + 1, j + 1),
                                                 topNode(n, layers, i, j + 1)}}) {
        for (int node : tri) load[static_cast<std::size_t>(node)].y() -= share;
      }
    }
  }
}

// With ν = 0 a column under a uniform load on its top is in uniaxial stress even with its base
// held: the top moves F H / (E A), which linear tetrahedra reproduce exactly (the patch test).
// Steps of 10 s are quasi-static: the mass term is 1e-8 of the stiffness.
TEST(FemSolid, AColumnUnderLoadShortensByFHOverEA) {
  const int n = 3, layers = 5;
  const double cell = 0.002, young = 2e5, force = 0.05;
  const TetMesh mesh = boxMesh(n, layers, n, cell);
  FemSolid solid(mesh, {young, 0.0, 1100.0, 0.0});
  std::vector<int> base;
  std::vector<Vec3> load(mesh.nodes.size(), Vec3::Zero());
  const double area = (n * cell) * (n * cell), height = layers * cell;
  for (int node = 0; node < static_cast<int>(mesh.nodes.size()); ++node) {
    if (mesh.nodes[node].y() == 0.0) base.push_back(node);
  }
  solid.fixNodes(base);
  const auto top = [&](int i, int j) { return topNode(n, layers, i, j); };
  addTopLoad(n, layers, cell, force, load);
  for (int s = 0; s < 5; ++s) solid.step(10.0, load, Vec3::Zero());
  const double expected = -force * height / (young * area);
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      const std::size_t node = static_cast<std::size_t>(top(i, j));
      EXPECT_NEAR(solid.positions()[node].y() - mesh.nodes[node].y(), expected, 1e-4 * std::abs(expected));
      EXPECT_NEAR(solid.positions()[node].x(), mesh.nodes[node].x(), 1e-4 * std::abs(expected)) << "ν = 0: no bulge";
    }
  }
}

// Corotational: a rigid rotation of the whole solid, however large, costs no elastic force.
TEST(FemSolid, ARigidRotationCostsNoForce) {
  const TetMesh mesh = generatePad({});
  FemSolid solid(mesh, {});
  const Eigen::Matrix3d r = Eigen::AngleAxisd(2.0, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  for (Vec3& p : solid.positions()) p = r * p + Vec3(0.1, -0.2, 0.3);
  double largest = 0.0;
  for (const Vec3& f : solid.elasticForces()) largest = std::max(largest, f.norm());
  // A displacement of 1 % of the element size would give forces near E h² / 100 ≈ 2e-3 N.
  EXPECT_LT(largest, 1e-12);
}

// The elastic forces are internal: a free solid keeps its momentum through every step.
TEST(FemSolid, AFreeSolidKeepsItsMomentum) {
  const TetMesh mesh = generatePad({});
  FemSolid solid(mesh, {});
  std::mt19937 random(7);
  std::uniform_real_distribution<double> speed(-0.1, 0.1);
  for (Vec3& v : solid.velocities()) v = Vec3(speed(random), speed(random), speed(random));
  const auto momentum = [&] {
    Vec3 p = Vec3::Zero();
    for (int i = 0; i < solid.nodeCount(); ++i) p += solid.masses()[static_cast<std::size_t>(i)] * solid.velocities()[static_cast<std::size_t>(i)];
    return p;
  };
  const Vec3 before = momentum();
  for (int s = 0; s < 50; ++s) solid.step(0.001, {}, Vec3::Zero());
  EXPECT_LT((momentum() - before).norm(), 1e-9 * solid.masses().size() * 0.1 * 1e-4);
}

// The nodes of `solid` below the plane y = 0, as contacts.
std::vector<FemContact> groundContacts(const FemSolid& solid) {
  std::vector<FemContact> out;
  for (int i = 0; i < solid.nodeCount(); ++i) {
    const double y = solid.positions()[static_cast<std::size_t>(i)].y();
    if (y < 0.0) out.push_back({i, Vec3::UnitY(), -y});
  }
  return out;
}

Vec3 total(const std::vector<Vec3>& forces) {
  Vec3 sum = Vec3::Zero();
  for (const Vec3& f : forces) sum += f;
  return sum;
}

// The column standing on stiff contact springs instead of held at its base: at rest the springs
// carry the load whole and the column shortens as held (ν = 0), their own give negligible.
TEST(FemSolid, AColumnOnContactsCarriesItsLoadAndShortensByFHOverEA) {
  const int n = 3, layers = 5;
  const double cell = 0.002, young = 2e5, force = 0.05;
  TetMesh mesh = boxMesh(n, layers, n, cell);
  for (Vec3& p : mesh.nodes) p.y() -= 1e-9;  // the base just pressed: its springs are on
  FemSolid solid(mesh, {young, 0.0, 1100.0, 0.0});
  solid.setContactStiffness(1e8);
  std::vector<Vec3> load(mesh.nodes.size(), Vec3::Zero());
  const double area = (n * cell) * (n * cell), height = layers * cell;
  const auto top = [&](int i, int j) { return topNode(n, layers, i, j); };
  addTopLoad(n, layers, cell, force, load);
  for (int s = 0; s < 20; ++s) solid.step(10.0, load, Vec3::Zero(), groundContacts(solid));
  EXPECT_NEAR(total(solid.contactForces()).y(), force, 1e-9 * force);
  double base = 0.0, top_y = 0.0;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      base += solid.positions()[static_cast<std::size_t>((j * (n + 1)) + i)].y();
      top_y += solid.positions()[static_cast<std::size_t>(top(i, j))].y();
    }
  }
  const double shortening = height - (top_y - base) / ((n + 1) * (n + 1));
  EXPECT_NEAR(shortening, force * height / (young * area), 1e-3 * force * height / (young * area));
}

// The pad on its bone pressed onto the ground at 1 ms steps comes to rest with the contacts
// carrying the bone's force, no element inverted, and its indentation converged: 3 mm and
// 1.5 mm elements within 5 % of each other.
TEST(FemSolid, APadPressedOntoTheGroundComesToRestAndItsIndentationConverges) {
  std::vector<double> indentation;
  for (double size : {0.003, 0.0015}) {
    const PadShape shape{0.006, 0.003, 0.7, size};
    TetMesh mesh = generatePad(shape);
    const double lift = shape.bone_radius + shape.thickness;  // the skin's lowest point on the ground
    for (Vec3& p : mesh.nodes) p.y() += lift;
    FemSolid pad(mesh, {});
    pad.setBone(mesh.bone_nodes, 0.01);
    const double force = 1.0, dt = 0.001;
    for (int s = 0; s < 600; ++s) {
      const double ramp = std::min(1.0, s * dt / 0.2);
      pad.step(dt, {}, Vec3(0.0, -force * ramp, 0.0), groundContacts(pad));
    }
    EXPECT_NEAR(total(pad.contactForces()).y(), force, 1e-3 * force) << "element size " << size;
    EXPECT_LT(pad.boneVelocity().norm(), 1e-4) << "element size " << size;
    TetMesh now = mesh;
    now.nodes = pad.positions();
    EXPECT_GT(tetQuality(now).min_volume, 0.0) << "element size " << size;
    indentation.push_back(-pad.boneOffset().y());
  }
  EXPECT_GT(indentation[1], 0.0);
  EXPECT_NEAR(indentation[0], indentation[1], 0.05 * indentation[1]);
}

// A soft pad pressed past its thickness (30 kPa under 5 N: the bone would sink 3 mm into a 3 mm
// pad) turns elements inside out; that is seen, and a reset puts the pad back at rest on the bone,
// nothing inverted, every position finite.
TEST(FemSolid, APadPressedPastItsThicknessIsSeenInvertedAndResetsToRest) {
  const PadShape shape{0.006, 0.003, 0.7, 0.0015};
  TetMesh mesh = generatePad(shape);
  for (Vec3& p : mesh.nodes) p.y() += shape.bone_radius + shape.thickness;
  FemSolid pad(mesh, {3e4, 0.45, 1100.0, 0.002});
  pad.setBone(mesh.bone_nodes, 0.01);
  int inverted = 0;
  for (int s = 0; s < 600 && inverted == 0; ++s) {
    pad.step(0.001, {}, Vec3(0.0, -5.0 * std::min(1.0, s / 200.0), 0.0), groundContacts(pad));
    inverted = pad.invertedElements();
  }
  ASSERT_GT(inverted, 0) << "the pad held 5 N at 30 kPa";
  pad.resetToRest();
  EXPECT_EQ(pad.invertedElements(), 0);
  for (int i = 0; i < pad.nodeCount(); ++i) {
    const std::size_t n = static_cast<std::size_t>(i);
    EXPECT_TRUE(pad.positions()[n].allFinite());
    EXPECT_NEAR((pad.positions()[n] - mesh.nodes[n] - pad.boneOffset()).norm(), 0.0, 1e-15);
    EXPECT_EQ(pad.velocities()[n], Vec3::Zero());
  }
  EXPECT_EQ(pad.boneVelocity(), Vec3::Zero());
}

TEST(FemSolid, MaterialsOutsideTheirRangesAreRefusedNamingTheField) {
  const auto message = [](FemMaterial m) {
    try {
      validateMaterial(m);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(message({}), "");
  EXPECT_NE(message({0.0, 0.45, 1100.0, 0.002}).find("pad.young_pa"), std::string::npos);
  EXPECT_NE(message({1e5, 0.5, 1100.0, 0.002}).find("pad.poisson"), std::string::npos);
  EXPECT_NE(message({1e5, 0.45, std::nan(""), 0.002}).find("pad.density_kg_m3"), std::string::npos);
  EXPECT_NE(message({1e5, 0.45, 1100.0, -1.0}).find("pad.damping_s"), std::string::npos);
}

}  // namespace
}  // namespace gf::sim
