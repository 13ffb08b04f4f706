// The god-finger settings of one finger: plain data shared by the patch function, the scene
// description and the overlay. Their legal ranges and validators are in sim/scene/settings.hpp.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <string_view>

#include "sim/math.hpp"

namespace gf::sim {

/// How a finger touches a body (`contact_model` in scene files).
enum class ContactModel : std::uint8_t {
  kGodObject,   ///< "god_object": one point, friction against sliding only
  kSoftFinger,  ///< "soft_finger": one point with a torsional friction limit (condim 4)
  kGodFinger,   ///< "god_finger": the paper's patch of SGOs (n_sgo 0: a god-object)
  kFemPad,      ///< "fem_pad": a deformable finger pad (finite elements) on a rigid bone (sim/soft/)
};

/// The scene-file names of the ContactModel values, in enum order ("god_object"), and how people
/// read them in overlays, labels and charts ("god-object").
inline constexpr std::string_view kContactModelNames[] = {"god_object", "soft_finger", "god_finger", "fem_pad"};
inline constexpr std::string_view kContactModelLabels[] = {"god-object", "soft finger", "god-finger", "FEM pad"};

/// Where a god-finger patch puts its points (`patch` in scene files).
enum class PatchFill : std::uint8_t {
  kRing,    ///< "ring": the paper's SGOs where the walks end, and the contact
  kFilled,  ///< "filled": also `rings` points along each walked path; weights by area
};

/// How the solver takes a god-finger contact (`world.contact_solver` in scene files).
enum class ContactSolver : std::uint8_t {
  kPoints,     ///< "points": every patch point is a contact row of Bullet's solver
  kAggregate,  ///< "aggregate": one block per contact (normal, 2 tilt, 2 tangential, torsion
               ///< rows) whose limits come from the patch's points (sim/contact/patch_friction.hpp)
};

/// How a god-finger's contact area follows the device's orientation (`pad_model` in scene files).
enum class PadModel : std::uint8_t {
  kDisc,      ///< "disc": the paper's 3-DOF patch, a disc of Eq. 1's radius; orientation ignored
  kOriented,  ///< "oriented": the 6-DOF pad, an ellipse shrinking towards the tip as the pad
              ///< tilts from the surface (docs/pad-model.md, sim/patch/patch_ring.hpp)
};

/// A finger's choice of solver (`contact_solver` of a finger): the world's, or one of them.
enum class SolverChoice : std::uint8_t {
  kWorld,      ///< "world": `world.contact_solver`
  kPoints,     ///< "points"
  kAggregate,  ///< "aggregate"
};

/// Write the scene-file name of a value ("god_finger", "filled", "aggregate", "world"), as the
/// settings tables spell it (sim/scene/settings.hpp): for messages and test names. Any thread.
std::ostream& operator<<(std::ostream& os, ContactModel model);
std::ostream& operator<<(std::ostream& os, PatchFill fill);
std::ostream& operator<<(std::ostream& os, ContactSolver solver);
std::ostream& operator<<(std::ostream& os, SolverChoice choice);
std::ostream& operator<<(std::ostream& os, PadModel pad);

/// The solver a finger's choice gives under the world's.
inline ContactSolver resolveSolver(SolverChoice finger, ContactSolver world) {
  return finger == SolverChoice::kWorld       ? world
         : finger == SolverChoice::kAggregate ? ContactSolver::kAggregate
                                              : ContactSolver::kPoints;
}

/// Most points a filled patch puts along one walked path.
inline constexpr int kMaxRings = 8;

/// Fewest and most SGOs a god-finger patch has (the paper asks for at least 3).
inline constexpr int kMinSgo = 3;
inline constexpr int kMaxSgo = 64;

/// God-finger settings. Defaults suit a fingertip on objects of a few centimetres. Their legal
/// ranges are in sim/scene/settings.hpp (fingerSettings()).
///
/// tau_a and the friction cone: the walk stops at a face turned more than min(tau_a,
/// atan(friction)) from the contact normal. At the defaults (tau_a 30 degrees, friction 1, a
/// 45-degree cone) tau_a is the bound; the cone takes over below friction tan(30) = 0.577.
struct PatchSettings {
  ContactModel model = ContactModel::kGodFinger;
  PatchFill fill = PatchFill::kRing;
  SolverChoice contact_solver = SolverChoice::kWorld;  ///< points or one aggregate block
  int rings = 3;                    ///< filled patch: points per walked path (1..kMaxRings)
  double torsional_friction = 0.005;  ///< soft finger: torsion limit per newton of normal force (m)
  int n_sgo = 8;                    ///< number of radial vectors / SGOs (kMinSgo..kMaxSgo)
  double r_max = 0.010;             ///< r_max of Eq. 1: largest contact radius (m)
  double d0 = 0.004;                ///< D'_0 of Eq. 1: press depth scale (m)
  double alpha = 2.0;               ///< alpha of Eq. 2: stretch base (>= 1; 1 = no stretch)
  double stretch_length = 0.004;    ///< length making Eq. 2's exponent dimensionless (m)
  double max_stretch = 2.0;         ///< Eq. 2's d_i is kept within [r / max_stretch, r max_stretch]
  double tau_a = 0.5235987755982988;  ///< tau_a: angular threshold (rad; default 30 deg)
  double friction = 1.0;            ///< theta: friction coefficient of the finger pad
  bool tangential_stretch = true;   ///< effect switch: Eq. 2 stretch (off: d_i = r)
  bool angular_threshold = true;    ///< effect switch: stop at faces beyond tau_a
  bool friction_cone = true;        ///< effect switch: stop at faces beyond atan(theta)
  /// Edges one walk may cross: this many plus 8 per mean edge length of the start face in d_i,
  /// so a fine mesh keeps the full radius; a walk that runs out stops (WalkStop::kCrossingLimit).
  int max_face_crossings = 64;
  double feature_tolerance = 1e-7;  ///< distance (m) within which a hit is an edge/vertex hit
  PadModel pad_model = PadModel::kDisc;  ///< disc (3-DOF) or oriented (6-DOF pad)
  /// oriented: the pad's outward normal, device frame; fem_pad: the way its soft cap faces (world)
  Vec3 pad_axis = Vec3(0.0, -1.0, 0.0);
  double tip_ratio = 0.4;  ///< oriented: the tip's contact size over the flat pad's, in (0, 1]

  bool operator==(const PatchSettings&) const = default;
};

/// The model a finger's settings give: n_sgo 0 makes the god-finger a god-object.
inline ContactModel effectiveModel(const PatchSettings& s) {
  return s.model == ContactModel::kGodFinger && s.n_sgo == 0 ? ContactModel::kGodObject : s.model;
}

/// The model a finger runs as (effectiveModel), as people read it, a filled god-finger patch
/// said: "god-object", "soft finger", "god-finger" or "god-finger, filled".
inline std::string_view modelLabel(const PatchSettings& s) {
  const ContactModel m = effectiveModel(s);
  if (m == ContactModel::kGodFinger && s.fill == PatchFill::kFilled) return "god-finger, filled";
  return kContactModelLabels[static_cast<int>(m)];
}

/// The same in scene-file names (the live state's "model"): "god_object", "soft_finger",
/// "god_finger" or "god_finger (filled)".
inline std::string_view modelName(const PatchSettings& s) {
  const ContactModel m = effectiveModel(s);
  if (m == ContactModel::kGodFinger && s.fill == PatchFill::kFilled) return "god_finger (filled)";
  return kContactModelNames[static_cast<int>(m)];
}

}  // namespace gf::sim
