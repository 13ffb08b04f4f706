// The 6-DOF pad model (sim/patch/patch_ring.hpp, docs/pad-model.md): a flat pad is the paper's
// 3-DOF patch exactly; a tilted pad's distances are its ellipse's radii, its filled weights its
// ellipse's sectors, and its torsion limit (filled patch and soft finger) falls with the angle.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <span>
#include <vector>

#include "sim/patch/patch_ring.hpp"
#include "sim/patch/god_finger.hpp"
#include "sim/mesh/primitives.hpp"
#include "sim/world/world.hpp"
#include "tests/sim/pressed_box.hpp"
#include "tests/sim/angles.hpp"

namespace gf::sim {
namespace {

using gf::test::kDeg;

PatchSettings oriented(PatchFill fill, int n = 8) {
  PatchSettings s;
  s.n_sgo = n;
  s.fill = fill;
  s.pad_model = PadModel::kOriented;
  return s;
}

// The pad's outward normal tilted by beta from the press direction -n, towards unit tangent t.
Vec3 tiltedPad(const Vec3& n, const Vec3& t, double beta) { return -std::cos(beta) * n + std::sin(beta) * t; }

// Every point of two patches (SGOs and filled points) within `tol` (m), and the same weights.
void expectSamePatch(const Patch& a, const Patch& b, double tol, const char* what) {
  ASSERT_EQ(a.sgos.size(), b.sgos.size()) << what;
  ASSERT_EQ(a.inner.size(), b.inner.size()) << what;
  for (std::size_t k = 0; k < a.sgos.size(); ++k) {
    EXPECT_LE((a.sgos[k].position - b.sgos[k].position).norm(), tol) << what << " SGO " << k;
    EXPECT_NEAR(a.sgos[k].load_share, b.sgos[k].load_share, 1e-12) << what << " SGO " << k;
  }
  for (std::size_t k = 0; k < a.inner.size(); ++k) {
    EXPECT_LE((a.inner[k].position - b.inner[k].position).norm(), tol) << what << " point " << k;
  }
  EXPECT_EQ(a.ring_tangent, b.ring_tangent) << what << ": the ring's reference is unchanged";
}

struct Surface {
  const char* name;
  Mesh mesh;
  Vec3 point, normal;
};

std::vector<Surface> surfaces() {
  const Vec3 slanted = Vec3(0.3, 1.0, -0.2).normalized();
  std::vector<Surface> out;
  out.push_back({"plane", tessellatePlane(1.0, 4), Vec3(0.01, 0, 0.02), Vec3::UnitY()});
  out.push_back({"box top", tessellateBox(Vec3(0.02, 0.01, 0.02), 4), Vec3(0.005, 0.01, -0.003), Vec3::UnitY()});
  out.push_back({"box side", tessellateBox(Vec3(0.02, 0.01, 0.02), 4), Vec3(0.02, 0.002, 0.004), Vec3::UnitX()});
  out.push_back({"sphere", tessellateSphere(0.03, 4), 0.03 * slanted, slanted});
  return out;
}

// A flat pad (its normal along the press, in any orientation about it) reproduces the 3-DOF
// patch: the same SGOs and filled points within 1e-12 m, ring and filled, with a tangential push.
TEST(PadModel, AFlatPadIsTheDiscPatchExactly) {
  for (const Surface& surf : surfaces()) {
    for (const PatchFill fill : {PatchFill::kRing, PatchFill::kFilled}) {
      PatchSettings disc = oriented(fill);
      disc.pad_model = PadModel::kDisc;
      const PatchContact c{surf.point, surf.normal, -0.001};
      const Vec3 v = -0.004 * surf.normal + Vec3(0.001, 0.0005, -0.0007);
      Patch a, b;
      computePatch(surf.mesh, c, v, disc, a);
      ASSERT_FALSE(a.sgos.empty()) << surf.name;
      // The pad along -n, turned about n by 40 degrees by a device's orientation (rounding).
      const Quat turn(Eigen::AngleAxisd(40.0 * kDeg, surf.normal));
      for (const Vec3& pad : {Vec3(-surf.normal), Vec3(turn * Vec3(-surf.normal))}) {
        PatchContact tilted = c;
        tilted.pad_normal_local = pad;
        computePatch(surf.mesh, tilted, v, oriented(fill), b);
        expectSamePatch(a, b, 1e-12, surf.name);
      }
      // No pad (zero normal) is the disc too.
      computePatch(surf.mesh, c, v, oriented(fill), b);
      expectSamePatch(a, b, 0.0, surf.name);
    }
  }
}

// On a flat face without a push, d_i is the ellipse's radius in r_i's direction: semi-axes
// r (1 - (1 - tip)(1 - cos beta)) along the tilt and r (1 - (1 - tip)(1 - cos beta) / 2) across.
TEST(PadModel, DistancesAreTheEllipsesRadiiOnAFlatFace) {
  const Mesh plane = tessellatePlane(1.0, 2);
  for (const double beta : {15.0, 45.0, 75.0, 90.0, 120.0}) {
    for (const double tip : {0.4, 0.1, 1.0}) {
      PatchSettings s = oriented(PatchFill::kRing, 12);
      s.tip_ratio = tip;
      const Vec3 along = Vec3(1, 0, 1).normalized();
      PatchContact c{Vec3(0.01, 0, 0.02), Vec3::UnitY(), -0.001};
      c.pad_normal_local = tiltedPad(Vec3::UnitY(), along, beta * kDeg);
      Patch p;
      computePatch(plane, c, Vec3(0, -0.004, 0), s, p);
      const double cos_beta = std::max(0.0, std::cos(beta * kDeg));
      const double a = 1.0 - (1.0 - tip) * (1.0 - cos_beta), b = 1.0 - 0.5 * (1.0 - tip) * (1.0 - cos_beta);
      ASSERT_EQ(p.sgos.size(), 12u);
      for (std::size_t i = 0; i < 12; ++i) {
        const double cx = p.radial[i].dot(along), cy = p.radial[i].dot(Vec3::UnitY().cross(along));
        const double expected = p.radius * a * b / std::sqrt(b * b * cx * cx + a * a * cy * cy);
        EXPECT_NEAR(p.d_i[i], expected, 1e-12) << "beta " << beta << " tip " << tip << " radial " << i;
        EXPECT_NEAR((p.sgos[i].position - p.hit.point).norm(), expected, 1e-12) << "beta " << beta;
      }
    }
  }
}

// A filled patch's weights are the ellipse's sectors: without a push the areas sum to
// pi a b exactly, whatever n_SGO.
TEST(PadModel, FilledAreasSumToTheEllipsesArea) {
  const Mesh plane = tessellatePlane(1.0, 2);
  for (const int n : {3, 8, 17}) {
    for (const double beta : {0.0, 30.0, 75.0}) {
      PatchSettings s = oriented(PatchFill::kFilled, n);
      PatchContact c{Vec3(0.0, 0, 0.0), Vec3::UnitY(), -0.001};
      c.pad_normal_local = tiltedPad(Vec3::UnitY(), Vec3::UnitX(), beta * kDeg);
      Patch p;
      computePatch(plane, c, Vec3(0, -0.004, 0), s, p);
      const double shrink = (1.0 - s.tip_ratio) * (1.0 - std::cos(beta * kDeg));
      const double area = std::numbers::pi * p.radius * p.radius * (1.0 - shrink) * (1.0 - 0.5 * shrink);
      double total = p.centre_area;
      for (const Sgo& q : p.sgos) total += q.area;
      for (const Sgo& q : p.inner) total += q.area;
      EXPECT_NEAR(total / area, 1.0, 1e-12) << "n " << n << " beta " << beta;
    }
  }
}

// A patch's torsion limit per mu N (m) from its points: sum_k share_k |rho_k|.
double pointsTorsionLever(const Patch& p) {
  double lever = 0.0;
  const Vec3 n = -p.press_dir;
  const auto add = [&](const Sgo& q) {
    const Vec3 d = q.position - p.hit.point;
    lever += q.load_share * (d - d.dot(n) * n).norm();
  };
  for (const Sgo& q : p.sgos) add(q);
  for (const Sgo& q : p.inner) add(q);
  return lever;
}

TEST(PadModel, FilledTorsionLeverFallsWithThePadAngle) {
  const Mesh plane = tessellatePlane(1.0, 2);
  PatchSettings disc = oriented(PatchFill::kFilled, 16);
  disc.pad_model = PadModel::kDisc;
  const PatchContact c0{Vec3(0.0, 0, 0.0), Vec3::UnitY(), -0.001};
  Patch p;
  computePatch(plane, c0, Vec3(0, -0.004, 0), disc, p);
  const double disc_lever = pointsTorsionLever(p);
  double last = 2.0 * disc_lever;
  for (int beta = 0; beta <= 75; beta += 5) {
    PatchContact c = c0;
    c.pad_normal_local = tiltedPad(Vec3::UnitY(), Vec3::UnitZ(), beta * kDeg);
    computePatch(plane, c, Vec3(0, -0.004, 0), oriented(PatchFill::kFilled, 16), p);
    const double lever = pointsTorsionLever(p);
    if (beta == 0) {
      EXPECT_EQ(lever, disc_lever);
    }
    EXPECT_LT(lever, last) << "beta " << beta;
    last = lever;
  }
}

// The soft finger's torsion factor is the uniform ellipse's mean distance from its centre over
// the disc's (2 r / 3): checked against a direct quadrature of that mean.
TEST(PadModel, TorsionFactorIsTheEllipsesMeanLeverOverTheDiscs) {
  for (const double beta : {0.0, 20.0, 50.0, 75.0, 90.0}) {
    for (const double tip : {0.05, 0.4, 1.0}) {
      PatchSettings s;
      s.pad_model = PadModel::kOriented;
      s.tip_ratio = tip;
      const PadEllipse pad = padEllipse(s, tiltedPad(Vec3::UnitY(), Vec3::UnitX(), beta * kDeg), Vec3::UnitY());
      // Mean of |x| over the ellipse, by polar quadrature: (1 / area) int rho(phi)^3 / 3 dphi.
      const int steps = 20000;
      double integral = 0.0;
      for (int k = 0; k < steps; ++k) {
        const double phi = 2.0 * std::numbers::pi * (k + 0.5) / steps;
        const double rho = padRadiusScale(pad, Vec3(std::cos(phi), 0.0, std::sin(phi)));
        integral += rho * rho * rho / 3.0 * (2.0 * std::numbers::pi / steps);
      }
      const double mean = integral / (std::numbers::pi * pad.k_along * pad.k_across);
      EXPECT_NEAR(padTorsionFactor(pad), mean / (2.0 / 3.0), 1e-4) << "beta " << beta << " tip " << tip;
      if (beta == 0.0 || tip == 1.0) {
      EXPECT_EQ(padTorsionFactor(pad), 1.0);
    }
    }
  }
}

// The pressed box of the contact-accuracy tests, its finger's device turned by `beta` about z
// (the pad tilts towards +x): the friction torque while a torque above the limit spins the box.
struct Measured {
  double limit = 0.0, normal = 0.0;  // N m, N
};

Measured slipTorque(PatchSettings patch, double beta, double applied) {
  LoadDesc load;
  load.torque = Vec3(0, applied, 0);
  SceneDesc scene = pressed_box::scene(patch, 0.0, load);
  for (DeviceTrack::Keyframe& k : scene.fingers[0].device.keyframes) {
    k.orientation = Quat(Eigen::AngleAxisd(beta, Vec3::UnitZ()));
  }
  World w(scene);
  const DeviceTrack track = scene.fingers[0].device;
  std::vector<double> t, omega;
  Measured m;
  int samples = 0;
  while (w.time() < pressed_box::kLoadStart + 0.4 - 5e-4) {
    const DeviceSample d = track.sample(w.time());
    w.step(1e-3, std::span(&d, 1));
    if (w.time() < pressed_box::kLoadStart + 0.1) continue;
    t.push_back(w.time());
    omega.push_back(w.bodyAngularVelocity(1).y());
    m.normal -= w.couplingForce(0).y();
    ++samples;
  }
  const double n = static_cast<double>(t.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < t.size(); ++i) sx += t[i], sy += omega[i], sxx += t[i] * t[i], sxy += t[i] * omega[i];
  const double inertia = pressed_box::kMass * 8.0 * pressed_box::kHalfWidth * pressed_box::kHalfWidth / 12.0;
  m.limit = applied - inertia * (n * sxy - sx * sy) / (n * sxx - sx * sx);
  m.normal /= samples;
  return m;
}

// In the World: the filled patch's slip torque falls monotonically with the pad angle over
// 0..75 degrees and at 0 is within 2 % of the 3-DOF filled patch's; points and aggregate solver.
TEST(PadModel, WorldTorsionLimitOfAFilledPatchFallsWithThePadAngle) {
  for (const SolverChoice solver : {SolverChoice::kPoints, SolverChoice::kAggregate}) {
    PatchSettings disc = oriented(PatchFill::kFilled, 16);
    disc.contact_solver = solver;
    disc.pad_model = PadModel::kDisc;
    const double applied = 0.04;
    const double disc_limit = slipTorque(disc, 0.0, applied).limit;
    PatchSettings pad = disc;
    pad.pad_model = PadModel::kOriented;
    double last = 2.0 * disc_limit;
    for (const double beta : {0.0, 15.0, 30.0, 45.0, 60.0, 75.0}) {
      const double limit = slipTorque(pad, beta * kDeg, applied).limit;
      std::printf("%s beta %4.0f: slip torque %.5f N m (3-DOF %.5f)\n",
                  solver == SolverChoice::kPoints ? "points" : "aggregate", beta, limit, disc_limit);
      if (beta == 0.0) {
      EXPECT_NEAR(limit / disc_limit, 1.0, 0.02);
    }
      EXPECT_LT(limit, last) << "beta " << beta;
      last = limit;
    }
  }
}

// The soft finger's torsion radius follows the same pad: its slip torque is torsional_friction
// times the pad's torsion factor times mu N, within 2 %.
TEST(PadModel, WorldSoftFingerTorsionFollowsThePad) {
  PatchSettings soft;
  soft.model = ContactModel::kSoftFinger;
  soft.pad_model = PadModel::kOriented;
  for (const double beta : {0.0, 45.0, 75.0}) {
    const Measured m = slipTorque(soft, beta * kDeg, 0.04);
    const PadEllipse pad = padEllipse(soft, tiltedPad(Vec3::UnitY(), Vec3::UnitX(), beta * kDeg), Vec3::UnitY());
    const double expected = soft.friction * m.normal * soft.torsional_friction * padTorsionFactor(pad);
    std::printf("soft finger beta %4.0f: slip torque %.5f N m, expected %.5f N m\n", beta, m.limit, expected);
    EXPECT_NEAR(m.limit / expected, 1.0, 0.02) << "beta " << beta;
  }
}

}  // namespace
}  // namespace gf::sim
