// What a contact's loads do, drawn at the patch as plain data (DrawList items): the twist the
// patch resists as an arc around its normal with a head showing the moment's sense, and on
// request each point's load split into its normal part and its friction as small arrows. Built
// without GL, like the rest of the draw list.
#pragma once

#include <optional>

#include "render/scene/draw_list.hpp"

namespace gf::render {

/// A contact's moment about its normal is drawn when it is at least this share of mu F_n r (the
/// moment of a friction limit mu F_n at the patch's rim): smaller twists are the solver's noise
/// on a still press.
inline constexpr double kTorsionShownShare = 0.05;

/// The arc of a contact that resists a twist: around the normal through its centre of pressure,
/// beyond the patch, sweeping 90 degrees plus 180 times the moment's share of mu F_n r (at most
/// 270), its head showing the sense of the moment on the body.
struct TorsionArc {
  sim::Vec3 centre = sim::Vec3::Zero();         ///< the centre of pressure (m)
  sim::Vec3 normal = sim::Vec3::UnitY();        ///< the outward normal (unit)
  double radius = 0.0;                          ///< m: 1.3 times the patch's radius
  double sweep = 0.0;                           ///< rad
  double moment = 0.0;                          ///< N m, on the body about `normal` (contactTorsion)
};

/// The torsion arc of contact `c` with pad friction `friction`, or none when it resists no twist
/// worth showing. `r_fallback` (m): the radius used when the contact has none (a soft finger's
/// point), e.g. the finger's r_max.
std::optional<TorsionArc> torsionArc(const sim::ContactSnapshot& c, double friction, double r_fallback);

/// Appends `arc` as a tube of `tube_radius` (m) with a cone head, in `colour`, drawn through
/// everything (DrawPass::kArrows); `eye` orders the head against the tube as addArrowItems does.
void addTorsionArc(DrawList& out, const TorsionArc& arc, double tube_radius, const Eigen::Vector3f& colour,
                   const std::optional<sim::Vec3>& eye);

/// The length per newton (m/N) of contact `c`'s point-load arrows: the mean point load draws as
/// half the patch's radius (`r_fallback` without one); 0 without per-point loads.
double loadArrowScale(const sim::ContactSnapshot& c, double r_fallback);

/// Appends each point's load of contact `c` as arrows at `m_per_n`: its friction on the body
/// from the point along the tangent plane, and with `normals` its normal part ending at the
/// point, pushing into the body. Arrows of `radius` (m).
void addLoadArrows(DrawList& out, const sim::ContactSnapshot& c, double m_per_n, bool normals, double radius,
                   const std::optional<sim::Vec3>& eye);

}  // namespace gf::render
