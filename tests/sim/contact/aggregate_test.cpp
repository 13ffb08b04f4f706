// The aggregate block's limits on hand-made patches against closed forms: a uniform ring, a
// filled disc and a half disc (a pad cut by an edge), in a tilted tangent plane. The limits are
// the points' load distribution: mean lever (torsion per unit mu N), the second moment about the
// tilt axes (tilt stiffness per unit contact stiffness) and the support of the points' hull (the
// tilt moment per unit normal force), and the tilt the points' depths make.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "sim/contact/aggregate_patch.hpp"

namespace gf::sim {
namespace {

using std::numbers::pi;
constexpr double kRadius = 0.008;  // m

// A patch: points (world), their shares (summing to 1) and depths, around `origin` in the
// plane of normal `n` with in-plane axes x, y.
struct HandPatch {
  btVector3 origin{0.1, 0.2, -0.05};
  btVector3 n = btVector3(0.3, 0.9, -0.2).normalized();
  btVector3 x, y;
  std::vector<btVector3> points;
  std::vector<double> shares, depths;

  HandPatch() {
    x = n.cross(btVector3(0, 0, 1)).normalized();
    y = n.cross(x);
  }
  void add(double px, double py, double weight, double depth = -1e-4) {
    points.push_back(origin + px * x + py * y);
    shares.push_back(weight);
    depths.push_back(depth);
  }
  void normalise() {
    double total = 0.0;
    for (double w : shares) total += w;
    for (double& w : shares) w /= total;
  }
  PressRows rows(btVector3& centre) const {
    PressRows out;
    std::vector<double> levers(points.size());
    aggregatePatch(points.data(), shares.data(), depths.data(), static_cast<int>(points.size()), n, origin, 800.0, 4.0,
                   centre, out, levers.data());
    return out;
  }
};

// The support of the points' hull in in-plane direction d, from the block's support samples:
// the tilt limit's direction j bounds u . D_j with u = rho x n, that is rho . (n x D_j).
// Returns the sampled direction closest to d and its support.
double supportToward(const HandPatch& p, const PressRows& r, const btVector3& d) {
  double best = -2.0, support = 0.0;
  for (int j = 0; j < kTiltDirections; ++j) {
    const double a = 2.0 * pi * j / kTiltDirections;
    const btVector3 D = std::cos(a) * r.tilt_axis[0] + std::sin(a) * r.tilt_axis[1];
    const btVector3 rho_dir = p.n.cross(D);
    if (rho_dir.dot(d) > best) best = rho_dir.dot(d), support = r.support[static_cast<std::size_t>(j)];
  }
  return support;
}

// A filled disc (or its half y >= 0): rings of points at radii (k / rings) r with the area of
// the annulus each stands for, `spokes` points per ring, angles 0 and pi included.
HandPatch filledDisc(int rings, int spokes, bool half) {
  HandPatch p;
  const double step = kRadius / rings;
  p.add(0.0, 0.0, pi * (0.5 * step) * (0.5 * step) * (half ? 0.5 : 1.0));
  for (int k = 1; k <= rings; ++k) {
    const double inner = (k - 0.5) * step, outer = std::min(kRadius, (k + 0.5) * step);
    const double annulus = pi * (outer * outer - inner * inner);
    const int count = half ? spokes / 2 + 1 : spokes;
    for (int i = 0; i < count; ++i) {
      const double a = 2.0 * pi * i / spokes;
      // A half disc's two diameter ends stand for half a spoke's sector each.
      const double w = half && (i == 0 || i == count - 1) ? 0.5 : 1.0;
      p.add(k * step * std::cos(a), k * step * std::sin(a), w * annulus / spokes);
    }
  }
  p.normalise();
  return p;
}

TEST(AggregatePatch, UniformRingHasLeverRMomentHalfRSquaredAndSupportR) {
  HandPatch p;
  constexpr int kCount = 64;
  for (int i = 0; i < kCount; ++i) {
    const double a = 0.37 + 2.0 * pi * i / kCount;  // any phase
    p.add(kRadius * std::cos(a), kRadius * std::sin(a), 1.0 / kCount);
  }
  btVector3 centre;
  const PressRows r = p.rows(centre);
  EXPECT_LT((centre - p.origin).length(), 1e-12);
  EXPECT_NEAR(r.mean_lever, kRadius, 1e-12);
  // sum_i w (rho_i . a)^2 = r^2 / 2 for every in-plane axis a.
  EXPECT_NEAR(r.tilt_moment[0], 0.5 * kRadius * kRadius, 1e-12 * kRadius);
  EXPECT_NEAR(r.tilt_moment[1], 0.5 * kRadius * kRadius, 1e-12 * kRadius);
  // Centre of pressure anywhere on the ring: the support is r in every direction, within the
  // sampling of 64 points (cos(pi / 64)).
  for (double h : r.support) {
    EXPECT_LE(h, kRadius * (1 + 1e-12));
    EXPECT_GE(h, kRadius * std::cos(pi / kCount));
  }
  EXPECT_NEAR(r.separation, -1e-4, 1e-15);
  EXPECT_NEAR(r.stiffness, 800.0, 0.0);
  EXPECT_NEAR(r.damping, 4.0, 0.0);
}

TEST(AggregatePatch, FilledDiscHasLeverTwoThirdsRMomentQuarterRSquared) {
  const HandPatch p = filledDisc(40, 64, false);
  btVector3 centre;
  const PressRows r = p.rows(centre);
  EXPECT_LT((centre - p.origin).length(), 1e-12);
  // Uniform pressure on a disc: mean lever (1 / A) int |rho| dA = 2r/3, second moment r^2 / 4
  // about any diameter; the rings' midpoint rule is within 0.1 % at 40 rings.
  EXPECT_NEAR(r.mean_lever / (2.0 / 3.0 * kRadius), 1.0, 1e-3);
  EXPECT_NEAR(r.tilt_moment[0] / (0.25 * kRadius * kRadius), 1.0, 1e-3);
  EXPECT_NEAR(r.tilt_moment[1] / (0.25 * kRadius * kRadius), 1.0, 1e-3);
  for (double h : r.support) EXPECT_NEAR(h / kRadius, 1.0, 1 - std::cos(pi / 64));
}

TEST(AggregatePatch, HalfDiscAtAnEdgeHasItsCentroidMomentsAndOneSidedSupport) {
  const HandPatch p = filledDisc(40, 64, true);
  btVector3 centre;
  const PressRows r = p.rows(centre);
  // The half disc y >= 0: centroid 4r / (3 pi) from the cut, second moments about the centroid
  // r^2/4 (across the cut's normal) and r^2/4 - (4r / 3pi)^2 (along it).
  const double c = 4.0 * kRadius / (3.0 * pi);
  EXPECT_NEAR((centre - p.origin).dot(p.y) / c, 1.0, 2e-3);
  EXPECT_NEAR((centre - p.origin).dot(p.x), 0.0, 1e-12);
  const double low = std::min(r.tilt_moment[0], r.tilt_moment[1]), high = std::max(r.tilt_moment[0], r.tilt_moment[1]);
  EXPECT_NEAR(high / (0.25 * kRadius * kRadius), 1.0, 2e-3);
  EXPECT_NEAR(low / (0.25 * kRadius * kRadius - c * c), 1.0, 5e-3);
  // Support from the centroid: r - c towards the arc, c towards the cut, r along the cut.
  EXPECT_NEAR(supportToward(p, r, p.y), kRadius - c, 2e-3 * kRadius);
  EXPECT_NEAR(supportToward(p, r, -p.y), c, 2e-3 * kRadius);
  EXPECT_NEAR(supportToward(p, r, p.x), kRadius, 2e-3 * kRadius);
  EXPECT_NEAR(supportToward(p, r, -p.x), kRadius, 2e-3 * kRadius);
}

// A pad tilted by angle theta about in-plane axis e: depths s_i = s0 - rho_i . (theta e x n)
// (the points on one side pressed deeper). The block's tilt error is that rotation.
TEST(AggregatePatch, DepthsOfATiltedPadGiveItsTiltAboutEachAxis) {
  HandPatch p = filledDisc(12, 32, false);
  const double theta = 0.01;  // rad
  const btVector3 e = (0.6 * p.x + 0.8 * p.y).normalized();
  const btVector3 slope = theta * e.cross(p.n);
  for (std::size_t i = 0; i < p.points.size(); ++i) p.depths[i] = -1e-4 - (p.points[i] - p.origin).dot(slope);
  btVector3 centre;
  const PressRows r = p.rows(centre);
  const btVector3 tilt = r.tilt_error[0] * r.tilt_axis[0] + r.tilt_error[1] * r.tilt_axis[1];
  // sum_i w u_i s_i = -sum_i w (rho_i x n)(rho_i . slope) = sigma theta e for an isotropic
  // second moment sigma: the error is theta about e.
  EXPECT_NEAR(tilt.dot(e), theta, 1e-9);
  EXPECT_NEAR(tilt.dot(p.n.cross(e)), 0.0, 1e-9);
  EXPECT_NEAR(r.separation, -1e-4, 1e-12);
}

// Points on one line hold no moment about that line: the axis across it has no tilt row.
TEST(AggregatePatch, CollinearPointsHaveNoTiltRowAcrossTheirLine) {
  HandPatch p;
  for (int i = -3; i <= 3; ++i) p.add(1e-3 * i, 0.0, 1.0);
  p.normalise();
  btVector3 centre;
  const PressRows r = p.rows(centre);
  const int zero = r.tilt_moment[0] == 0.0 ? 0 : 1;
  EXPECT_EQ(r.tilt_moment[static_cast<std::size_t>(zero)], 0.0);
  EXPECT_GT(r.tilt_moment[static_cast<std::size_t>(1 - zero)], 0.0);
  EXPECT_TRUE(std::isfinite(r.tilt_error[0]) && std::isfinite(r.tilt_error[1]));
}

}  // namespace
}  // namespace gf::sim
