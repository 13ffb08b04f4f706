#include "render/scene/load_marks.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "render/state/contact_load.hpp"

namespace gf::render {
namespace {

using sim::Vec3;

constexpr double kArcRadiusShare = 1.3;      // of the patch's radius: the arc runs beyond it
constexpr double kArcLiftM = 0.0004;         // m above the surface
constexpr double kLeastSweep = 0.5 * std::numbers::pi;
constexpr double kSweepPerShare = std::numbers::pi;
constexpr int kArcSegmentsPerTurn = 48;
constexpr double kHeadTubes = 3.0;           // the head's arc, in tube diameters
const Eigen::Vector3f kNormalLoadColour(0.85f, 0.85f, 0.9f);
const Eigen::Vector3f kFrictionLoadColour(1.0f, 0.45f, 0.1f);

}  // namespace

std::optional<TorsionArc> torsionArc(const sim::ContactSnapshot& c, double friction, double r_fallback) {
  const Vec3& n = c.outward_normal_world;
  const double pressing = std::max(0.0, -c.force.dot(n));
  const double r = c.radius > 0.0 ? c.radius : r_fallback;
  const double limit = friction * pressing * r;  // N m: mu F_n at the rim
  const double moment = contactTorsion(c);
  if (!(limit > 0.0) || !(std::abs(moment) >= kTorsionShownShare * limit)) return std::nullopt;
  TorsionArc arc;
  arc.centre = pressureCentre(c) + kArcLiftM * n;
  arc.normal = n;
  arc.radius = kArcRadiusShare * r;
  arc.sweep = kLeastSweep + kSweepPerShare * std::min(1.0, std::abs(moment) / limit);
  arc.moment = moment;
  return arc;
}

void addTorsionArc(DrawList& out, const TorsionArc& arc, double tube_radius, const Eigen::Vector3f& colour,
                   const std::optional<Vec3>& eye) {
  // u, v span the tangent plane with u x v = n: increasing angle turns counter-clockwise about n.
  const Vec3 u = arc.normal.unitOrthogonal(), v = arc.normal.cross(u);
  const double sense = arc.moment >= 0.0 ? 1.0 : -1.0;
  const double head = kHeadTubes * 2.0 * tube_radius;
  const double head_angle = std::min(0.5 * arc.sweep, head / arc.radius);
  const double body = arc.sweep - head_angle;
  const int segments = std::max(4, static_cast<int>(std::ceil(kArcSegmentsPerTurn * body / (2.0 * std::numbers::pi))));
  const auto at = [&](double angle) {
    return Vec3(arc.centre + arc.radius * (std::cos(sense * angle) * u + std::sin(sense * angle) * v));
  };
  for (int s = 0; s < segments; ++s) {
    const Vec3 a = at(body * s / segments), b = at(body * (s + 1) / segments);
    const Vec3 d = b - a;
    out.items.push_back(shapeItem(DrawPass::kArrows, DrawShape::kCylinder,
                             modelMatrix(a, sim::Quat::FromTwoVectors(Vec3::UnitY(), d.normalized()),
                                         Vec3(tube_radius, d.norm(), tube_radius)),
                             colour));
  }
  addArrowItems(out, at(body), at(arc.sweep) - at(body), tube_radius, colour, eye);
}

double loadArrowScale(const sim::ContactSnapshot& c, double r_fallback) {
  const ContactLoads loads = contactLoads(c);
  if (!loads.shown) return 0.0;
  return 0.5 * (c.radius > 0.0 ? c.radius : r_fallback) / loads.mean_normal;
}

void addLoadArrows(DrawList& out, const sim::ContactSnapshot& c, double m_per_n, bool normals, double radius,
                   const std::optional<Vec3>& eye) {
  if (!(m_per_n > 0.0) || c.loads.size() != c.sgos_world.size()) return;
  const Vec3& n = c.outward_normal_world;
  const auto arrows = [&](const Vec3& at, const sim::PointLoad& l) {
    if (normals && l.normal > 0.0) {
      const Vec3 push = -m_per_n * l.normal * n;
      addArrowItems(out, at - push, push, radius, kNormalLoadColour, eye);
    }
    addArrowItems(out, at + kArcLiftM * n, m_per_n * l.tangential, radius, kFrictionLoadColour, eye);
  };
  arrows(c.point_world, c.point_load);
  for (std::size_t k = 0; k < c.loads.size(); ++k) arrows(c.sgos_world[k], c.loads[k]);
}

}  // namespace gf::render
