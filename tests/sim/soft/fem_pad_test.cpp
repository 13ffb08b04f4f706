// The soft pad against rigid surfaces: friction that holds below its cap and slides at it, the
// friction torque of a pressed pad on a spinning plate against the slip limit of its own
// pressure and the Hertzian closed form, its resolutions converging, and a pad sheared past
// what it can take undone instead of exploding.
#include "sim/soft/fem_pad.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace gf::sim {
namespace {

// The sanitizer builds slow the pad's steps about 20 times (GCC says AddressSanitizer is on by a
// macro, clang by a feature test).
#if defined(__SANITIZE_ADDRESS__)
constexpr bool kUnderAddressSanitizer = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kUnderAddressSanitizer = true;
#else
constexpr bool kUnderAddressSanitizer = false;
#endif
#else
constexpr bool kUnderAddressSanitizer = false;
#endif

// The plane y = 0, turning about the y axis at `omega` (its frame's angle `angle`) or sliding
// along x at `speed` (its frame at `shift`).
struct Plate final : PadSurfaces {
  double angle = 0.0, omega = 0.0, speed = 0.0, shift = 0.0;
  void near(const Vec3&, const Vec3&, std::vector<int>& out) const override { out.assign(1, 0); }
  bool inside(int, const Vec3& p, double& depth, Vec3& normal) const override {
    depth = -p.y();
    normal = Vec3::UnitY();
    return depth > 0.0;
  }
  Pose frame(int) const override { return {Vec3(shift, 0.0, 0.0), Quat(Eigen::AngleAxisd(angle, Vec3::UnitY()))}; }
  Vec3 velocityAt(int, const Vec3& p) const override { return Vec3(speed, 0.0, 0.0) + Vec3(0.0, omega, 0.0).cross(p); }
  double mass(int) const override { return 0.0; }  // driven: its motion is given
  Vec3 velocity(int) const override { return Vec3(speed, 0.0, 0.0); }
};

struct Load {
  double normal = 0.0, torque = 0.0, slip_limit = 0.0, area = 0.0;
  Vec3 tangential = Vec3::Zero();
};

// The plate's load from the pad's last step: normal force, torque about y, the torque were every
// node slipping (mu sum of F_n r), the pressed area.
Load plateLoad(const FemPad& pad, double mu) {
  Load l;
  for (const PadNodeContact& c : pad.contacts()) {
    const double fn = -c.force.dot(c.normal);
    l.normal += fn;
    l.torque += c.point.cross(c.force).y();
    l.slip_limit += mu * fn * std::hypot(c.point.x(), c.point.z());
    l.area += c.area;
    l.tangential += c.force + fn * c.normal;
  }
  return l;
}

constexpr double kSkin = 0.008, kBoneMass = 0.1, kDt = 0.001;

FemPad padOnPlate(const PadSettings& s) { return FemPad(s, kSkin, kBoneMass, Vec3(0.0, -1.0, 0.0), Vec3(0.0, kSkin, 0.0)); }

// Pressed by 1 N with mu 1 on a still plate and pushed sideways by 0.5 N, the pad comes to rest,
// its friction carrying the push whole. Held sideways by a spring over a plate sliding at 5 cm/s,
// its friction over 0.6..0.8 s is mu N within 1 % on the mean (1.003 mu N measured).
TEST(FemPad, FrictionHoldsBelowItsCapAndIsMuTimesTheLoadWhenSliding) {
  for (const bool sliding : {false, true}) {
    FemPad pad = padOnPlate({});
    Plate plate;
    double normal = 0.0, friction = 0.0;
    int samples = 0;
    for (int k = 0; k < 800; ++k) {
      const double t = k * kDt, ramp = std::min(1.0, t / 0.2), late = t > 0.3 ? std::min(1.0, (t - 0.3) / 0.2) : 0.0;
      plate.speed = sliding ? 0.05 * late : 0.0;
      const double side = sliding ? -2000.0 * pad.boneCentre().x() - 20.0 * pad.boneVelocity().x() : 0.5 * late;
      pad.step(kDt, Vec3(side, -1.0 * ramp, 0.0), 1.0, plate);
      plate.shift += plate.speed * kDt;
      if (t < 0.6) continue;
      const Load l = plateLoad(pad, 1.0);
      normal += l.normal;
      friction += -l.tangential.x();
      ++samples;
    }
    const Load l = plateLoad(pad, 1.0);
    if (!sliding) {
      EXPECT_NEAR(l.normal, 1.0, 1e-3);
      EXPECT_NEAR(l.tangential.x(), 0.5, 1e-3) << "held";
      EXPECT_LT(pad.boneVelocity().norm(), 1e-4);
    } else {
      std::printf("sliding: mean normal %.4f N, mean friction %.4f N\n", normal / samples, friction / samples);
      EXPECT_NEAR(normal / samples, 1.0, 0.05);
      EXPECT_NEAR(friction / samples, 1.0 * normal / samples, 0.01 * normal / samples) << "sliding at mu N";
    }
    EXPECT_EQ(pad.resets(), 0);
  }
}

// The steady friction torque (1..1.3 s) of a pad pressed by 3 N onto a plate spinning at 5 rad/s,
// with its contact radius (a disc of its pressed area).
Load spinTorque(double element_size) {
  PadSettings s;
  s.element_size = element_size;
  FemPad pad = padOnPlate(s);
  Plate plate;
  Load mean;
  int samples = 0;
  for (int k = 0; k < 1300; ++k) {
    const double t = k * kDt;
    plate.omega = t > 0.5 ? std::min(1.0, (t - 0.5) / 0.2) * 5.0 : 0.0;
    pad.step(kDt, Vec3(0.0, -3.0 * std::min(1.0, t / 0.2), 0.0), 1.0, plate);
    plate.angle += plate.omega * kDt;
    if (t < 1.0) continue;
    const Load l = plateLoad(pad, 1.0);
    mean.normal += l.normal;
    mean.torque += l.torque;
    mean.slip_limit += l.slip_limit;
    mean.area += l.area;
    ++samples;
  }
  EXPECT_EQ(pad.resets(), 0) << "element size " << element_size;
  mean.normal /= samples;
  mean.torque /= samples;
  mean.slip_limit /= samples;
  mean.area /= samples;
  return mean;
}

// Spinning, every node of the pad slips: its friction torque is the limit of its own pressure
// (mu sum F_n r) within 1 % (99.6 and 99.96 % measured). Against the closed forms at its contact
// radius r (a disc of its pressed area): a layer on a bone presses between a thin layer's
// parabolic pressure, torsion (8/15) mu F r, and a half-space's Hertzian one, (3 pi / 16) mu F r;
// the pad's is within 3 % of that span (0.555 and 0.536 mu F r measured, the span 0.533..0.589),
// within 10 % of Hertz's, nearer it than the uniform (2 / 3) mu F r, and the torque converges:
// 1.5 and 1 mm elements within 5 % (1.9 % measured).
TEST(FemPad, ASpinningPlateFeelsTheFrictionTorqueOfThePadsPressure) {
  if (kUnderAddressSanitizer) {
    GTEST_SKIP() << "20 s in release, about 20 times that under the sanitizers (the sliding test: 2.4 s and 50 s); "
                    "the other FemPad tests run the same code there";
  }
  std::vector<double> torques;
  for (const double size : {0.0015, 0.001}) {
    const Load l = spinTorque(size);
    const double torque = -l.torque, r = std::sqrt(l.area / std::numbers::pi);
    const double hertz = 3.0 * std::numbers::pi / 16.0 * l.normal * r, uniform = 2.0 / 3.0 * l.normal * r;
    std::printf("element %.2f mm: torque %.5f N m, slip limit %.5f, Hertz %.5f, uniform %.5f, r %.2f mm\n",
                1000 * size, torque, l.slip_limit, hertz, uniform, 1000 * r);
    EXPECT_NEAR(l.normal, 3.0, 0.01);
    EXPECT_NEAR(torque, l.slip_limit, 0.01 * l.slip_limit);
    EXPECT_LE(torque, l.slip_limit * (1.0 + 1e-3)) << "past Coulomb's limit";
    EXPECT_NEAR(torque, hertz, 0.10 * hertz);
    EXPECT_GT(torque, 0.97 * 8.0 / 15.0 * l.normal * r);
    EXPECT_LT(torque, 1.03 * hertz);
    EXPECT_LT(std::abs(torque - hertz), std::abs(torque - uniform));
    torques.push_back(torque);
  }
  EXPECT_NEAR(torques[0], torques[1], 0.05 * torques[1]);
}

// A 100 kPa pad pressed by 3 N and twisted at mu 1 is sheared past what linear elements take: each
// such step is undone (counted) and its forces dropped, nothing is ever non-finite and the force
// on the plate stays within three times the press (3.01 N at most, measured), never a kick of its
// skin's springs. (Once twisted inside out it mostly stays undone: 911 of the 1000 twisted steps,
// the plate then pressed by 0.26 N on the mean; docs/soft-hand.md, failure modes.)
TEST(FemPad, APadShearedInsideOutIsUndoneWithoutASpike) {
  PadSettings s;
  s.young = 1e5;
  FemPad pad = padOnPlate(s);
  Plate plate;
  double largest = 0.0, pressed = 0.0;
  int twisted = 0;
  for (int k = 0; k < 1500; ++k) {
    const double t = k * kDt;
    plate.omega = t > 0.5 ? 5.0 : 0.0;
    pad.step(kDt, Vec3(0.0, -3.0 * std::min(1.0, t / 0.2), 0.0), 1.0, plate);
    plate.angle += plate.omega * kDt;
    for (const Vec3& p : pad.nodes()) ASSERT_TRUE(p.allFinite());
    if (t < 0.3) continue;
    largest = std::max(largest, plateLoad(pad, 1.0).normal);
    if (t > 0.5) {
      pressed += plateLoad(pad, 1.0).normal;
      ++twisted;
    }
  }
  std::printf("100 kPa pad twisted: %ld steps undone, largest force on the plate %.2f N, mean %.2f N\n", pad.resets(),
              largest, pressed / twisted);
  EXPECT_GT(pad.resets(), 0) << "a 100 kPa pad held the twist";
  EXPECT_LT(largest, 3.0 * 3.0) << "the force on the plate jumped";
}

}  // namespace
}  // namespace gf::sim
