// The load on a contact as the pictures show it, plain data without GL: each point's normal
// load on a perceptually uniform colour scale (viridis) centred on the contact's mean point load
// and stretched to its points' spread, and the contact's force split into its normal and
// tangential parts, and the twist it resists.
#pragma once

#include <Eigen/Core>

#include "sim/scene/snapshot.hpp"

namespace gf::render {

/// The least half-span of a contact's load scale, as a share of its mean point load: a press
/// whose points differ by less than 5 % either way is drawn within mid-scale's neighbourhood,
/// not stretched over the whole map.
inline constexpr double kLoadScaleMinHalfSpan = 0.05;

/// Viridis (matplotlib's perceptually uniform map, dark purple to yellow) at `u` in 0..1
/// (clamped), as linear RGB: the display gamma 2 of the shaders and of imguiColour() undone, so
/// what is shown is viridis itself.
Eigen::Vector3f viridis(double u);

/// How one contact's points are coloured: on a scale centred on the contact's mean point load,
/// reaching from mean x (1 - h) to mean x (1 + h), h the larger of the points' own spread either
/// way and kLoadScaleMinHalfSpan. The least and most loaded points take the scale's ends when
/// they lie the same way off the mean; a uniform press sits mid-scale.
struct ContactLoads {
  /// Per-point loads known and the contact pressing: the dots are coloured. Otherwise they are
  /// drawn uniformly (finger colour, the contact point white), as before the solver filled loads.
  bool shown = false;
  double mean_normal = 0.0;  ///< N: the normal load over the contact's points (SGOs, filled points, c_p)
  double min_normal = 0.0;   ///< N: the least point's
  double max_normal = 0.0;   ///< N: the most loaded point's
  double half_span = kLoadScaleMinHalfSpan;  ///< h: the scale's half-width, of the mean
  /// A point's normal load (N) over the mean: 1 for a uniform press, 0 for a point that carries nothing.
  double share(double normal) const { return mean_normal > 0.0 ? normal / mean_normal : 0.0; }
  /// Where a point with normal load `normal` (N) sits on the scale, 0..1 (0.5: the mean).
  double scale(double normal) const { return 0.5 + (share(normal) - 1.0) / (2.0 * half_span); }
  /// N: the load at scale position `u` (0..1).
  double loadAt(double u) const { return mean_normal * (1.0 + (2.0 * u - 1.0) * half_span); }
  /// The colour of a point with normal load `normal` (N), linear RGB.
  Eigen::Vector3f colour(double normal) const { return viridis(scale(normal)); }
};

/// The colouring of contact `c`'s points: shown when `c.loads` has one load per SGO and the
/// loads press (their normal sum is above 1 µN).
ContactLoads contactLoads(const sim::ContactSnapshot& c);

/// A contact's force on the body it touches, split along its outward normal.
struct ContactForce {
  double normal = 0.0;                          ///< F_n: pressing into the body (N, >= 0)
  sim::Vec3 tangential = sim::Vec3::Zero();     ///< friction on the body, in the tangent plane (N, world)
  bool from_solver = false;                     ///< the contact's own force; false: the finger's feedback
};

/// The force of contact `c` of finger `f` on the body: the solver's `c.force` when it has one,
/// else the reaction of the force rendered to the device (-f.feedback_force), which is the
/// finger's whole contact force when it touches one thing.
ContactForce contactForce(const sim::FingerSnapshot& f, const sim::ContactSnapshot& c);

/// The twist a contact resists: its moment on the body about the outward normal through the
/// points' centre of pressure (N m; positive counter-clockwise seen from outside the body): the
/// points' friction forces' moment there, with the moment they do not carry (a soft finger's
/// torsion_moment, all there is of a soft finger's). Zero for a god-object (its point turns freely).
double contactTorsion(const sim::ContactSnapshot& c);

/// The centre of pressure of contact `c`: its points weighted by their normal loads (the
/// contact point when they press nothing).
sim::Vec3 pressureCentre(const sim::ContactSnapshot& c);

}  // namespace gf::render
