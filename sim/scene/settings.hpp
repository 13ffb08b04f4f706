// Every setting a scene file, the command line, `live` and the overlay may give, with its unit
// and legal range: one table per description type and one validator per setting. The scene
// reader, the command line, `live`, the overlay and the World all check values here.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <string_view>

#include "sim/scene/scene_desc.hpp"

namespace gf::sim {

/// Young's modulus of a soft body (Pa): a sponge's 10 kPa to a stiff rubber's 10 MPa.
inline constexpr double kMinSoftYoung = 1e4, kMaxSoftYoung = 1e7;
/// A soft body's density (its mass over its tetrahedra's volume, kg/m³): what its material takes.
inline constexpr double kMinSoftDensity = 100.0, kMaxSoftDensity = 1e4;
/// A finger's walk_fill, when on (m).
inline constexpr double kMinWalkFill = 1e-4;

/// m: the largest scene coordinate a position (body, keyframe, device) may have.
inline constexpr double kMaxSceneCoordinate = 1e3;

/// A dynamic body must weigh at least this fraction of every proxy: the solver holds a pinched
/// body down to 1/100 of the proxy's mass and lets a 1/1000 one tumble.
inline constexpr double kMinBodyToProxyMass = 0.01;

/// A field of a description that is not legal: its name as scene files write it, and why.
struct FieldError {
  std::string field;   ///< "n_sgo", "device.keyframes.t", "world.solver_iterations", ...
  std::string reason;  ///< "must be 0 (god-object) or 3..64"
  int index = -1;      ///< element of an array field (keyframe k); -1 for a plain field
};

/// A description that cannot be built: which body, finger or load, which field, and why. what()
/// reads "body 'cylinder': mass: must be in [1e-06, 1e+06], got -1".
class DescriptionError : public std::invalid_argument {
 public:
  DescriptionError(std::string subject, FieldError error);
  /// "body 'NAME'", "finger 'NAME'", "load INDEX" or "scene".
  const std::string& subject() const { return subject_; }
  const FieldError& error() const { return error_; }

 private:
  std::string subject_;
  FieldError error_;
};

/// What a setting holds.
enum class SettingKind : std::uint8_t {
  kNumber,
  kInteger,
  kVector,
  kChoice,  ///< one of `choices`, given by name, stored as its index (an enum)
};

/// One setting of a description type (SceneDesc, BodyDesc, FingerDesc or LoadDesc).
template <class Desc>
struct Setting {
  std::string_view name;   ///< key in scene files, --set, `live`, the overlay and JSON
  std::string_view unit;   ///< unit it is given in: "m", "deg", "kg", ...; "" when dimensionless
  SettingKind kind = SettingKind::kNumber;
  double min = 0.0;        ///< legal range in `unit` (every component of a vector)
  double max = 0.0;
  bool min_excluded = false;  ///< (min, max] instead of [min, max]
  bool live = false;          ///< may change while a session runs (`live` set, the overlay)
  double si_per_unit = 1.0;   ///< stored value = given value * si_per_unit (degrees to radians)
  std::span<const std::string_view> choices;  ///< kChoice: the names, in enum order
  /// A further condition on the given value, or null; returns why the value breaks it.
  const char* (*rule)(double given) = nullptr;
  double (*get)(const Desc&) = nullptr;  ///< kNumber, kInteger: the stored value
  void (*set)(Desc&, double stored) = nullptr;
  Vec3 (*get_vector)(const Desc&) = nullptr;  ///< kVector
  void (*set_vector)(Desc&, const Vec3& stored) = nullptr;
};

/// Settings of the scene as a whole: `duration`, `haptic_rate` and `world.*`.
std::span<const Setting<SceneDesc>> sceneSettings();
/// Settings of a body (`bodies.NAME.*`) other than its shape, mesh and orientation.
std::span<const Setting<BodyDesc>> bodySettings();
/// Settings of a finger (`fingers.NAME.*`) other than its device; the god-finger ones are live.
std::span<const Setting<FingerDesc>> fingerSettings();

/// Settings of a load (`loads.INDEX.*`) other than its body: force, torque, start, ramp, stop.
std::span<const Setting<LoadDesc>> loadSettings();

/// The setting called `name` in `table`, or null.
template <class Desc>
const Setting<Desc>* findSetting(std::span<const Setting<Desc>> table, std::string_view name) {
  for (const Setting<Desc>& s : table) {
    if (s.name == name) return &s;
  }
  return nullptr;
}

/// `x` as text for messages: `digits` significant digits, and as many more (up to 17) as it
/// takes to read back as `x`, so that "got X" never reads as a bound X violates
/// (1.000001 is "1.000001", not "1"). Any thread; allocates.
std::string numberText(double x, int digits = 6);

/// A computed bound and the value that violates it as texts: the value as numberText gives it,
/// the bound with `digits` significant digits and more while, as printed, it would equal the
/// value or lie on the value's other side (up to 17). Any thread; allocates.
std::pair<std::string, std::string> distinctTexts(double bound, double got, int digits = 4);

/// Why `given` (in the setting's unit) is not legal for `setting`, or nullopt when it is.
/// Allocates only to return a reason. Any thread.
template <class Desc>
std::optional<std::string> checkGiven(const Setting<Desc>& setting, double given);
/// The same for each component of a vector setting.
template <class Desc>
std::optional<std::string> checkGiven(const Setting<Desc>& setting, const Vec3& given);

/// `setting` of `desc` as a user gives it (in its unit): n_sgo 8, tau_a 60 (degrees).
template <class Desc>
double givenValue(const Setting<Desc>& setting, const Desc& desc) {
  return setting.get(desc) / setting.si_per_unit;
}
/// Stores `given` (in the setting's unit, already checked) into `desc`.
template <class Desc>
void setGiven(const Setting<Desc>& setting, Desc& desc, double given) {
  setting.set(desc, given * setting.si_per_unit);
}

/// The index of `name` among a kChoice setting's choices, or -1.
template <class Desc>
int choiceIndex(const Setting<Desc>& setting, std::string_view name) {
  for (std::size_t i = 0; i < setting.choices.size(); ++i) {
    if (setting.choices[i] == name) return static_cast<int>(i);
  }
  return -1;
}
/// The name of a kChoice setting's value in `desc`.
template <class Desc>
std::string_view choiceName(const Setting<Desc>& setting, const Desc& desc) {
  return setting.choices[static_cast<std::size_t>(setting.get(desc))];
}
/// The names of a kChoice setting, quoted and separated by commas: "\"a\", \"b\"".
template <class Desc>
std::string choiceList(const Setting<Desc>& setting) {
  std::string out;
  for (std::string_view c : setting.choices) out.append(out.empty() ? "\"" : ", \"").append(c).append("\"");
  return out;
}

/// The name of a setting in JSON: its name with its unit ("r_max_m", "tau_a_deg", "n_sgo").
template <class Desc>
std::string jsonKey(const Setting<Desc>& setting);

/// How each body shape is written in scene files, what it requires and how finely its walk
/// mesh may be tessellated.
struct ShapeInfo {
  ShapeKind kind;
  std::string_view shape;      ///< `shape` in scene files
  std::string_view collision;  ///< `collision` of a mesh shape; "" for primitives
  std::array<std::string_view, 2> dimensions;  ///< settings the shape requires ("" unused)
  int default_resolution;      ///< walk mesh tessellation when walk_resolution is 0
  int min_resolution;          ///< walk_resolution, when given, is in [min, max]
  int max_resolution;          ///< (0: a mesh, walked as loaded)
};
/// Every shape kind, in ShapeKind order.
std::span<const ShapeInfo> shapeInfos();
const ShapeInfo& shapeInfo(ShapeKind kind);
/// True for the kinds whose surface comes from a mesh file.
bool isMeshShape(ShapeKind kind);

/// A physics effect a scene lists: its name in scene files and its switch in EffectSet.
struct EffectSwitch {
  std::string_view name;
  bool EffectSet::*on;
};
/// The physics effects, in scene-file documentation order.
std::span<const EffectSwitch> effectSwitches();

/// A soft body's own rules (scene_desc.cpp): dynamic, a file when soft_mesh, its density (its
/// mass over its tetrahedra's volume, once `soft.tets` is loaded) in kMinSoftDensity..
/// kMaxSoftDensity. Part of validateBody.
std::optional<FieldError> validateSoftBody(const BodyDesc& body);

/// The first field of the scene-wide settings (not bodies nor fingers) that is not legal.
std::optional<FieldError> validateScene(const SceneDesc& scene);
/// The first field of `body` that is not legal: every body setting, then the rules between
/// fields (a static body has mass 0, a plane is static, a shape's walk resolution range).
std::optional<FieldError> validateBody(const BodyDesc& body);
/// The first field of `finger` that is not legal: every finger setting, then the proxy's
/// radius against its deepest press (max_force / contact_stiffness), then its device track.
std::optional<FieldError> validateFinger(const FingerDesc& finger);
/// The first coupling setting of `finger` that the explicit integration of its spring-damper
/// cannot hold at `haptic_rate_hz`: stiffness above proxy_mass * rate^2 or damping above
/// proxy_mass * rate (k dt^2 / m and c dt / m at most 1; hard cases pinch-coupling-stiff and
/// pinch-coupling-damped hold at those limits, and 4 times the stiffness rings).
std::optional<FieldError> validateCouplingStability(const FingerDesc& finger, double haptic_rate_hz);
/// push_apart's stiffness against the stable bound of every finger's proxy and coupling:
/// overlap_stiffness <= (proxy_mass x haptic_rate^2 - coupling_stiffness) / 2. Nullopt for the
/// other overlap modes. Any thread.
std::optional<FieldError> validateOverlapStability(const SceneDesc& scene);
/// The names of the finger settings that may change during a run (`live`'s `set`, a scene's
/// `[[changes]]`), comma-separated in table order.
std::string liveFingerSettingNames();
/// A finger whose scene gives it `scene_model` changing to `to`: refused to or from fem_pad (the
/// pad is built with the world).
std::optional<FieldError> validateModelChange(ContactModel scene_model, ContactModel to);
/// The first god-finger setting (a live one) of `patch` that is not legal.
std::optional<FieldError> validatePatch(const PatchSettings& patch);
/// The first keyframe of `track` that is not legal ("keyframes.t" or "keyframes.p", with its
/// index): times finite, in [0, 1e6] s and strictly increasing; positions finite.
std::optional<FieldError> validateTrack(const DeviceTrack& track);
/// The first field of `load` that is not legal: its body (one of `bodies`, dynamic), every load
/// setting (finite; start, ramp and stop in [0, 1e6] s, stop +inf when there is none), then
/// stop after start.
std::optional<FieldError> validateLoad(const LoadDesc& load, std::span<const BodyDesc> bodies);
/// The first field of `change` that is not legal: its finger (an index into `fingers`), its time
/// (finite, in [0, 1e6] s, not before `previous_time`), then its god-finger settings.
std::optional<FieldError> validateChange(const PatchChange& change, std::span<const FingerDesc> fingers,
                                         double previous_time);
/// Throws DescriptionError naming the scene, body, finger, load or change of the first field of
/// `scene` that is not legal.
void requireValid(const SceneDesc& scene);

/// A change of one finger's god-finger settings, made away from the haptic thread (the
/// overlay) and applied by it from its next step.
struct SettingsCommand {
  int finger = 0;      ///< index into SceneDesc::fingers
  PatchSettings patch; ///< the finger's whole new settings (n_sgo 0: god-object)
};

}  // namespace gf::sim
