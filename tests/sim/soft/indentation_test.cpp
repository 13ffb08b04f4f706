// A soft solid indented by a rigid sphere against Hertz's law, F = 4/3 E* √R d^(3/2) with
// E* = E / (1 − ν²), at two mesh resolutions: the finer within 10 %, closer than the coarser.
// The half-space is a quarter of a cylinder 50 contact radii wide and deep (its base fixed, its
// two cut faces planes of symmetry held by bilateral frictionless contacts), its grid graded:
// `rings` rings of equal width inside the contact radius, each further one 1.25 times wider
// than the last. The sphere is frictionless (Hertz's assumption) and its contact set is found by
// repeating static steps: a node inside the sphere presses it, one that pressed stays pressed
// until its spring would pull. Also: a bilateral contact holds a node both ways.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <vector>

#include "sim/mesh/tet_shapes.hpp"
#include "sim/soft/fem_solid.hpp"

namespace gf::sim {
namespace {

constexpr double kYoung = 1e5, kPoisson = 0.3;
constexpr double kContactRadius = 0.002;  // Hertz's a = √(R d) (m)
constexpr double kDepth = 2e-4;           // d (m): a / R = 0.1, small strain
constexpr double kBlockRadius = 0.1;      // the quarter cylinder's radius and depth: 50 a
constexpr double kGrowth = 1.25;

// The rings' radii: `rings` equal ones up to the contact radius, then each 1.25 times wider,
// until past the block's radius.
std::vector<double> ringRadii(int rings) {
  const double first = kContactRadius / rings;
  std::vector<double> r{0.0};
  while (r.back() < kBlockRadius) {
    const int beyond = std::max(0, static_cast<int>(r.size()) - rings);
    r.push_back(r.back() + first * std::pow(kGrowth, beyond));
  }
  return r;
}

// The quarter cylinder x, z ≥ 0, y ≤ 0 (its top at y = 0): grid node (i, k) on the square ring
// q = max(i, k), blended from the square at the centre to the circle at the contact radius and
// beyond (so the contact's rim is a ring of nodes); depth j graded like the radii.
TetMesh gradedQuarter(int rings) {
  const std::vector<double> r = ringRadii(rings);
  const int n = static_cast<int>(r.size()) - 1;
  const auto node = [&](int i, int j, int k) -> Vec3 {
    Vec3 p(0.0, -r[static_cast<std::size_t>(n - j)], 0.0);
    const int q = std::max(i, k);
    if (q == 0) return p;
    const Vec3 square(static_cast<double>(i) / q, 0.0, static_cast<double>(k) / q);
    const auto angle = [](double u) { return std::tan(0.25 * std::numbers::pi * u); };
    const Vec3 circle = Vec3(angle(square.x()), 0.0, angle(square.z())).normalized();
    const double t = std::min(1.0, static_cast<double>(q) / rings);
    const Vec3 d = (1.0 - t) * 0.7 * square + t * circle;
    p.x() = r[static_cast<std::size_t>(q)] * d.x();
    p.z() = r[static_cast<std::size_t>(q)] * d.z();
    return p;
  };
  return kuhnGrid({n, n, n}, node, false);
}

struct Indentation {
  double force = 0.0;  // N, the whole sphere's (four quarters)
  int pressing = 0;    // the quarter's nodes pressing the sphere
  std::size_t tets = 0;
  bool settled = false;  // the contact set and the force (to 1e-5) as in the step before
};

Indentation indent(int rings) {
  const TetMesh mesh = gradedQuarter(rings);
  FemSolid solid(mesh, {kYoung, kPoisson, 1000.0, 0.0});
  std::vector<int> base;
  const double bottom = std::min_element(mesh.nodes.begin(), mesh.nodes.end(), [](const Vec3& a, const Vec3& b) {
                          return a.y() < b.y();
                        })->y();
  for (std::size_t i = 0; i < mesh.nodes.size(); ++i) {
    if (mesh.nodes[i].y() == bottom) base.push_back(static_cast<int>(i));
  }
  solid.fixNodes(base);
  solid.setContactStiffness(1e9);  // a node's spring: 5e6 times the block's stiffness E a (200 N/m)
  const double radius = kContactRadius * kContactRadius / kDepth;
  const Vec3 centre(0.0, radius - kDepth, 0.0);
  std::vector<char> pressed(mesh.nodes.size(), 0);
  Indentation out;
  out.tets = mesh.tets.size();
  for (int step = 0; step < 6; ++step) {
    std::vector<FemContact> contacts;
    for (std::size_t i = 0; i < mesh.nodes.size(); ++i) {
      const Vec3& x = solid.positions()[i];
      const double distance = (x - centre).norm();
      if (distance < radius || pressed[i]) {
        FemContact c;
        c.node = static_cast<int>(i);
        c.normal = (x - centre) / distance;
        c.depth = std::max(radius - distance, 1e-12);
        contacts.push_back(c);
      }
    }
    const std::size_t sphere_contacts = contacts.size();
    for (std::size_t i = 0; i < mesh.nodes.size(); ++i) {
      FemContact plane;
      plane.node = static_cast<int>(i);
      plane.bilateral = true;
      if (mesh.nodes[i].x() == 0.0) {
        plane.normal = Vec3::UnitX();
        plane.depth = -solid.positions()[i].x();
        contacts.push_back(plane);
      }
      if (mesh.nodes[i].z() == 0.0) {
        plane.normal = Vec3::UnitZ();
        plane.depth = -solid.positions()[i].z();
        contacts.push_back(plane);
      }
    }
    solid.step(100.0, {}, Vec3::Zero(), contacts);  // a step far longer than any vibration: static
    double force = 0.0;
    int pressing = 0;
    std::fill(pressed.begin(), pressed.end(), 0);
    for (std::size_t k = 0; k < sphere_contacts; ++k) {
      if (solid.contactResults()[k].released) continue;
      force -= 4.0 * solid.contactForces()[k].y();
      pressed[static_cast<std::size_t>(contacts[k].node)] = 1;
      ++pressing;
    }
    const bool settled = step > 0 && std::abs(force - out.force) < 1e-5 * force && pressing == out.pressing;
    out.force = force;
    out.pressing = pressing;
    out.settled = settled;
    if (settled) break;
  }
  return out;
}

double hertz() {
  const double radius = kContactRadius * kContactRadius / kDepth;
  return 4.0 / 3.0 * kYoung / (1.0 - kPoisson * kPoisson) * std::sqrt(radius) * std::pow(kDepth, 1.5);
}

TEST(Indentation, ASphereOnAHalfSpaceFollowsHertzWithin10PercentAtTheFinerMesh) {
#if defined(GF_UNDER_SANITIZER) || !defined(NDEBUG)
  GTEST_SKIP() << "static solves of 25 000 and 41 000 tetrahedra (3 to 6 factorisations each, 45 s "
                  "optimised): many minutes under a sanitizer or unoptimised";
#endif
  const double closed_form = hertz();
  const Indentation coarse = indent(2), fine = indent(3);
  const double coarse_error = coarse.force / closed_form - 1.0, fine_error = fine.force / closed_form - 1.0;
  RecordProperty("hertz_n", std::to_string(closed_form));
  RecordProperty("coarse_ratio", std::to_string(coarse.force / closed_form));
  RecordProperty("fine_ratio", std::to_string(fine.force / closed_form));
  std::printf("Hertz %.5f N; %zu tets %.5f N (%+.1f %%), %zu tets %.5f N (%+.1f %%)\n", closed_form, coarse.tets,
              coarse.force, 100.0 * coarse_error, fine.tets, fine.force, 100.0 * fine_error);
  // The rim: every top node within the contact radius presses, none beyond.
  EXPECT_TRUE(coarse.settled);
  EXPECT_TRUE(fine.settled);
  EXPECT_EQ(coarse.pressing, 3 * 3);
  EXPECT_EQ(fine.pressing, 4 * 4);
  EXPECT_LT(std::abs(fine_error), 0.10) << fine.force << " N against " << closed_form << " N, " << fine.tets << " tets";
  EXPECT_LT(std::abs(fine_error), std::abs(coarse_error)) << "refining brings the force towards Hertz's";
}

TEST(Indentation, ABilateralContactHoldsANodeBothWays) {
  // One tetrahedron, its base fixed, its apex touching a plane above it and loaded by 1 N up
  // (into the plane) and down (away): a bilateral contact holds it both ways (its force
  // balancing the load), a one-sided one lets go of the pull. With friction, a bilateral
  // contact pulled sticks (glued) and stays finite.
  TetMesh mesh;
  mesh.nodes = {Vec3(0, 0, 0), Vec3(0.01, 0, 0), Vec3(0, 0, 0.01), Vec3(0, 0.01, 0)};
  mesh.tets = {{0, 2, 1, 3}};
  const auto pull = [&](bool bilateral, double load, double depth, double friction) {
    auto solid = std::make_unique<FemSolid>(mesh, FemMaterial{kYoung, kPoisson, 1000.0, 0.0});
    solid->fixNodes({0, 1, 2});
    solid->setContactStiffness(1e9);
    FemContact c;
    c.node = 3;
    c.normal = -Vec3::UnitY();  // the plane above the apex, pressing it down
    c.depth = depth;
    c.bilateral = bilateral;
    c.friction = friction;
    std::vector<Vec3> forces(4, Vec3::Zero());
    forces[3] = Vec3(0.2 * load, load, 0.0);  // and sideways, for the friction
    solid->step(100.0, forces, Vec3::Zero(), {c});
    return solid;
  };
  for (const bool bilateral : {true, false}) {
    for (const double load : {1.0, -1.0}) {
      const auto solid = pull(bilateral, load, 1e-12, 0.0);  // touching
      const double apex_moved = solid->positions()[3].y() - 0.01;
      if (bilateral || load > 0.0) {  // an upward load presses the apex into the plane
        EXPECT_NEAR(solid->contactForces()[0].y(), -load, 1e-6) << "bilateral " << bilateral << ", load " << load;
        EXPECT_LT(std::abs(apex_moved), 1e-8);
      } else {
        EXPECT_TRUE(solid->contactResults()[0].released);
        EXPECT_LT(apex_moved, -1e-5);  // the load pulls the apex down (E a = 1000 N/m)
      }
    }
  }
  // The plane 0.1 mm above the apex (depth < 0): a bilateral contact pulls the apex up to it.
  const auto lifted = pull(true, 0.0, -1e-4, 0.0);
  EXPECT_NEAR(lifted->positions()[3].y(), 0.0101, 1e-8);
  EXPECT_GT(lifted->contactForces()[0].y(), 0.0) << "it pulls";
  // Glued: pulled down and sideways with friction 0.5, it holds both ways, finite.
  const auto glued = pull(true, -1.0, 1e-12, 0.5);
  EXPECT_TRUE(glued->positions()[3].allFinite());
  EXPECT_NEAR(glued->contactForces()[0].y(), 1.0, 1e-6);
  EXPECT_NEAR(glued->contactForces()[0].x(), 0.2, 1e-6);
  EXPECT_FALSE(glued->contactResults()[0].slipping);
}

}  // namespace
}  // namespace gf::sim
