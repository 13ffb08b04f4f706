#include "render/state/contact_load.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace gf::render {
namespace {

// Viridis at u = 0, 0.1, ..., 1 (matplotlib's _viridis_data, sRGB display values), interpolated
// linearly between these eleven keys: the map is smooth enough for dots of a few pixels.
constexpr std::array<std::array<float, 3>, 11> kViridis = {{
    {0.267004f, 0.004874f, 0.329415f}, {0.282623f, 0.140926f, 0.457517f}, {0.253935f, 0.265254f, 0.529983f},
    {0.206756f, 0.371758f, 0.553117f}, {0.163625f, 0.471133f, 0.558148f}, {0.127568f, 0.566949f, 0.550556f},
    {0.134692f, 0.658636f, 0.517649f}, {0.266941f, 0.748751f, 0.440573f}, {0.477504f, 0.821444f, 0.318195f},
    {0.741388f, 0.873449f, 0.149561f}, {0.993248f, 0.906157f, 0.143936f},
}};
constexpr double kMinPressN = 1e-6;   // N: below this a contact's loads press nothing
constexpr double kMinForceN = 1e-12;  // N: a contact force this small was not filled in

}  // namespace

Eigen::Vector3f viridis(double u) {
  const double x = std::clamp(std::isfinite(u) ? u : 0.0, 0.0, 1.0) * (kViridis.size() - 1);
  const std::size_t k = std::min(static_cast<std::size_t>(x), kViridis.size() - 2);
  const float t = static_cast<float>(x - static_cast<double>(k));
  const Eigen::Vector3f a(kViridis[k][0], kViridis[k][1], kViridis[k][2]);
  const Eigen::Vector3f b(kViridis[k + 1][0], kViridis[k + 1][1], kViridis[k + 1][2]);
  const Eigen::Vector3f display = (1.0f - t) * a + t * b;
  return display.cwiseProduct(display);  // the display gamma 2 undone
}

ContactLoads contactLoads(const sim::ContactSnapshot& c) {
  ContactLoads out;
  if (c.loads.empty() || c.loads.size() != c.sgos_world.size()) return out;
  // c_p, when it is one of the solver's points, then the SGOs.
  const double first = c.point_loaded ? std::max(0.0, c.point_load.normal) : std::max(0.0, c.loads.front().normal);
  double total = c.point_loaded ? first : 0.0, least = first, most = first;
  for (const sim::PointLoad& l : c.loads) {
    const double n = std::max(0.0, l.normal);
    total += n, least = std::min(least, n), most = std::max(most, n);
  }
  if (!(total > kMinPressN)) return out;
  out.shown = true;
  out.mean_normal = total / static_cast<double>(c.loads.size() + (c.point_loaded ? 1 : 0));
  out.min_normal = least;
  out.max_normal = most;
  out.half_span = std::max({kLoadScaleMinHalfSpan, most / out.mean_normal - 1.0, 1.0 - least / out.mean_normal});
  return out;
}

ContactForce contactForce(const sim::FingerSnapshot& f, const sim::ContactSnapshot& c) {
  ContactForce out;
  out.from_solver = c.force.squaredNorm() > kMinForceN * kMinForceN;
  const sim::Vec3 on_body = out.from_solver ? c.force : sim::Vec3(-f.feedback_force);
  const sim::Vec3& n = c.outward_normal_world;
  const double along = on_body.dot(n);
  out.normal = std::max(0.0, -along);
  out.tangential = on_body - along * n;
  return out;
}

sim::Vec3 pressureCentre(const sim::ContactSnapshot& c) {
  if (c.loads.size() != c.sgos_world.size()) return c.point_world;
  double total = c.point_loaded ? std::max(0.0, c.point_load.normal) : 0.0;
  sim::Vec3 sum = total * c.point_world;
  for (std::size_t k = 0; k < c.loads.size(); ++k) {
    const double n = std::max(0.0, c.loads[k].normal);
    total += n;
    sum += n * c.sgos_world[k];
  }
  return total > kMinPressN ? sim::Vec3(sum / total) : c.point_world;
}

double contactTorsion(const sim::ContactSnapshot& c) {
  const sim::Vec3& n = c.outward_normal_world;
  double moment = c.torsion_moment.dot(n);
  if (c.loads.size() != c.sgos_world.size()) return moment;
  const sim::Vec3 centre = pressureCentre(c);
  moment += (c.point_world - centre).cross(c.point_load.tangential).dot(n);
  for (std::size_t k = 0; k < c.loads.size(); ++k) moment += (c.sgos_world[k] - centre).cross(c.loads[k].tangential).dot(n);
  return moment;
}

}  // namespace gf::render
