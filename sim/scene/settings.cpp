#include "sim/scene/settings.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iomanip>
#include <numbers>
#include <sstream>
#include <type_traits>

#include "sim/assert.hpp"
#include "sim/mesh/primitives.hpp"

namespace gf::sim {

std::string numberText(double x, int digits) {
  for (;; ++digits) {
    std::ostringstream s;
    s << std::setprecision(digits) << x;
    if (digits >= 17 || std::strtod(s.str().c_str(), nullptr) == x) return s.str();
  }
}

std::pair<std::string, std::string> distinctTexts(double bound, double got, int digits) {
  const std::string g = numberText(got);
  for (;; ++digits) {
    std::ostringstream b;
    b << std::setprecision(digits) << bound;
    // The bound as printed must lie on the same side of the value as the bound itself.
    const double shown_bound = std::strtod(b.str().c_str(), nullptr);
    if (digits >= 17 || ((shown_bound < got) == (bound < got) && (shown_bound > got) == (bound > got))) return {b.str(), g};
  }
}

namespace {

// Vector components are bounded to what a haptic scene can hold and the solver stays finite on
// (a body at 1e155 m or a gravity of 1e6 m/s^2 made every step roll back): positions within a
// kilometre, gravity within 10 g, loads within 10 kN and 1 kN m.
constexpr double kMaxCoordinate = kMaxSceneCoordinate;  // m
constexpr double kMaxGravity = 100.0;   // m/s^2
constexpr double kMaxLoadForce = 1e4;   // N
constexpr double kMaxLoadTorque = 1e3;  // N m
constexpr double kRadPerDeg = std::numbers::pi / 180.0;
constexpr double kBig = 1e3;  // m: nothing in a haptic scene is larger
constexpr double kMinPadAxisLength = 0.1;  // the pad axis is normalized: a typo of 0 is refused
// Pa: fem_pad's tissue, from a gel to a stiff rubber; hard cases fem-pad-young-min/max hold at both.
constexpr double kMinPadYoung = 1e4, kMaxPadYoung = 1e7;
constexpr int kMaxPadCellsAcross = 16;  // fem_pad: cells across its cap, each way
// N/m: push_apart's stiffness; each scene's bound is narrower (validateOverlapStability).
constexpr double kMaxOverlapStiffness = 1e5;

// The member reached from `object` through the member pointers First, Rest...
template <auto First, auto... Rest, class T>
constexpr auto& reach(T& object) {
  if constexpr (sizeof...(Rest) == 0) {
    return object.*First;
  } else {
    return reach<Rest...>(object.*First);
  }
}

// The setting stored at the member path M... of Desc: its kind follows the member's type
// (Vec3: a vector, an integer type: an integer, else a number).
template <class Desc, auto... M>
Setting<Desc> row(std::string_view name, std::string_view unit, double min, double max) {
  using Stored = std::remove_cvref_t<decltype(reach<M...>(std::declval<Desc&>()))>;
  Setting<Desc> s;
  s.name = name;
  s.unit = unit;
  s.min = min;
  s.max = max;
  if constexpr (std::is_same_v<Stored, Vec3>) {
    s.kind = SettingKind::kVector;
    s.get_vector = [](const Desc& d) { return Vec3(reach<M...>(d)); };
    s.set_vector = [](Desc& d, const Vec3& v) { reach<M...>(d) = v; };
  } else {
    s.kind = std::is_enum_v<Stored>       ? SettingKind::kChoice
             : std::is_integral_v<Stored> ? SettingKind::kInteger
                                          : SettingKind::kNumber;
    s.get = [](const Desc& d) { return static_cast<double>(reach<M...>(d)); };
    s.set = [](Desc& d, double v) { reach<M...>(d) = static_cast<Stored>(v); };
  }
  return s;
}

// A kChoice setting: its names, in enum order.
template <class S>
S named(S s, std::span<const std::string_view> choices) {
  s.choices = choices;
  s.min = 0;
  s.max = static_cast<double>(choices.size()) - 1;
  return s;
}

constexpr std::string_view kPatchFillNames[] = {"ring", "filled"};
constexpr std::string_view kContactSolverNames[] = {"points", "aggregate"};
constexpr std::string_view kSolverChoiceNames[] = {"world", "points", "aggregate"};
constexpr std::string_view kPadModelNames[] = {"disc", "oriented"};
constexpr std::string_view kImprintNames[] = {"flat", "round"};
constexpr std::string_view kOverlapNames[] = {"ignore", "push_apart", "merge"};

template <class S>
S live(S s) {
  s.live = true;
  return s;
}

template <class S>
S aboveMin(S s) {
  s.min_excluded = true;
  return s;
}

template <class S>
S degrees(S s) {
  s.si_per_unit = kRadPerDeg;
  return s;
}

template <class S>
S withRule(S s, const char* (*rule)(double)) {
  s.rule = rule;
  return s;
}

const char* nSgoRule(double n) {
  static const std::string reason = "must be 0 (god-object) or " + std::to_string(kMinSgo) + ".." +
                                    std::to_string(kMaxSgo);
  return n == 0.0 || n >= kMinSgo ? nullptr : reason.c_str();
}

// Formats a number as a reason shows it (6 significant digits).
std::string shown(double x) { return numberText(x); }

std::string rangeReason(const SettingKind kind, double min, double max, bool min_excluded, double got) {
  if (kind == SettingKind::kInteger || kind == SettingKind::kChoice) {
    return "must be in " + shown(min) + ".." + shown(max) + ", got " + shown(got);
  }
  return std::string("must be in ") + (min_excluded ? "(" : "[") + shown(min) + ", " + shown(max) + "], got " +
         shown(got);
}

// The first setting of `table` whose value in `desc` is not legal, skipping those `skip` names.
template <class Desc, class Skip>
std::optional<FieldError> firstBadSetting(std::span<const Setting<Desc>> table, const Desc& desc, Skip&& skip) {
  for (const Setting<Desc>& s : table) {
    if (skip(s)) continue;
    const std::optional<std::string> why = s.kind == SettingKind::kVector
                                               ? checkGiven(s, Vec3(s.get_vector(desc) / s.si_per_unit))
                                               : checkGiven(s, givenValue(s, desc));
    if (why) return FieldError{std::string(s.name), *why};
  }
  return std::nullopt;
}

// "body 'ball': mass: must be ..." (appended piece by piece: GCC 12 misreads the one-line
// concatenation under -Wrestrict, PR 105329).
std::string descriptionMessage(const std::string& subject, const FieldError& e) {
  std::string m = subject;
  m.append(": ").append(e.field);
  if (e.index >= 0) m.append(" ").append(std::to_string(e.index));
  return m.append(": ").append(e.reason);
}

// A finger's fem_pad against its proxy: a bone at least as thick as the tissue, cells between a
// quarter of the thickness and the thickness, at most kMaxPadCellsAcross of them across the cap
// (as generatePad lays them): the finest pad a scene may ask for steps in about 40 ms (hard case
// fem-pad-finest), a haptic session's pads far coarser.
std::optional<FieldError> validatePadShape(const FingerDesc& finger) {
  const PadSettings& p = finger.pad;
  const double skin = finger.proxy.radius;
  if (!(p.thickness <= 0.5 * skin)) {
    const auto [bound, got] = distinctTexts(0.5 * skin, p.thickness);
    return FieldError{"pad_thickness", "must be at most half proxy_radius = " + bound +
                                           " m (the bone, a sphere inside the skin, at least as thick as the tissue), got " + got};
  }
  if (!(p.element_size >= p.thickness / 4.0 && p.element_size <= p.thickness)) {
    return FieldError{"pad_element_size", "must be in [pad_thickness / 4, pad_thickness] = [" + shown(p.thickness / 4.0) +
                                              ", " + shown(p.thickness) + "] m, got " + shown(p.element_size)};
  }
  // fem_pad's proxy is its bone: the clamp's press must stay within the bone, as any proxy's.
  const double bone = skin - p.thickness;
  if (const double depth = finger.coupling.max_force / finger.proxy.contact_stiffness; !(depth < bone)) {
    const auto [bound, got] = distinctTexts(depth, bone);
    return FieldError{"pad_thickness", "leaves a bone of proxy_radius - pad_thickness = " + got +
                                           " m, not more than max_force / contact_stiffness = " + bound +
                                           " m, how deep the bone's own contact lets it in at the coupling's clamp"};
  }
  const double arc = 2.0 * p.cap_angle * (skin - 0.5 * p.thickness);
  if (const double across = std::ceil(arc / p.element_size - 1e-9); across > kMaxPadCellsAcross) {
    return FieldError{"pad_element_size", "makes " + shown(across) + " cells across the pad (at most " +
                                              std::to_string(kMaxPadCellsAcross) + "); take at least " +
                                              shown(arc / kMaxPadCellsAcross) + " m, got " + shown(p.element_size)};
  }
  return std::nullopt;
}

}  // namespace

std::optional<FieldError> validateModelChange(ContactModel scene_model, ContactModel to) {
  if ((scene_model == ContactModel::kFemPad) == (to == ContactModel::kFemPad)) return std::nullopt;
  return FieldError{"contact_model", "fem_pad is a finger's model for a whole session: its pad is built with the world, "
                                     "so a finger can neither change to nor from it"};
}

DescriptionError::DescriptionError(std::string subject, FieldError error)
    : std::invalid_argument(descriptionMessage(subject, error)), subject_(std::move(subject)), error_(std::move(error)) {}

std::span<const Setting<SceneDesc>> sceneSettings() {
  using S = SceneDesc;
  static const Setting<S> kTable[] = {
      row<S, &S::duration>("duration", "s", 1e-3, 1e6),
      row<S, &S::world, &WorldSettings::haptic_rate_hz>("haptic_rate", "Hz", 100.0, 1e5),
      row<S, &S::world, &WorldSettings::gravity>("world.gravity", "m/s^2", -kMaxGravity, kMaxGravity),
      row<S, &S::world, &WorldSettings::solver_iterations>("world.solver_iterations", "", 1, 10000),
      named(row<S, &S::world, &WorldSettings::contact_solver>("world.contact_solver", "", 0, 0), kContactSolverNames),
      row<S, &S::world, &WorldSettings::linear_damping>("world.linear_damping", "1/s", 0.0, 1e3),
      row<S, &S::world, &WorldSettings::angular_damping>("world.angular_damping", "1/s", 0.0, 1e3),
      named(row<S, &S::world, &WorldSettings::overlap>("world.overlap", "", 0, 0), kOverlapNames),
      // The stable bound for the scene's proxies is checked with them (validateOverlapStability).
      row<S, &S::world, &WorldSettings::overlap_stiffness>("world.overlap_stiffness", "N/m", 10.0, kMaxOverlapStiffness),
  };
  return kTable;
}

std::span<const Setting<BodyDesc>> bodySettings() {
  using B = BodyDesc;
  static const Setting<B> kTable[] = {
      row<B, &B::radius>("radius", "m", 1e-4, kBig),
      row<B, &B::half_height>("half_height", "m", 1e-4, kBig),
      row<B, &B::half_extents>("half_extents", "m", 1e-4, kBig),
      row<B, &B::mesh_scale>("scale", "", 1e-9, 1e9),
      row<B, &B::walk_resolution>("walk_resolution", "", 0, 4096),
      // Lighter bodies tumble in a pinch whatever the solver iterations (1e-5 kg did with a 0.1 g
      // proxy; 0.1 g holds: hard case pinch-mass-0.1g); see also kMinBodyToProxyMass.
      row<B, &B::mass>("mass", "kg", 1e-4, 1e6),
      row<B, &B::friction>("friction", "", 0.0, 100.0),
      row<B, &B::restitution>("restitution", "", 0.0, 1.0),
      row<B, &B::position>("position", "m", -kMaxCoordinate, kMaxCoordinate),
      row<B, &B::colour>("colour", "", 0.0, 1.0),
      // Soft bodies only (SoftDesc); the hard cases soft-* hold these ranges.
      row<B, &B::soft, &SoftDesc::young>("young", "Pa", kMinSoftYoung, kMaxSoftYoung),
      row<B, &B::soft, &SoftDesc::poisson>("poisson", "", 0.0, 0.49),
      row<B, &B::soft, &SoftDesc::damping>("damping", "s", 0.0, 0.1),
      row<B, &B::soft, &SoftDesc::element_size>("element_size", "m", 1e-3, 0.1),
      row<B, &B::soft, &SoftDesc::contact_stiffness>("contact_stiffness", "N/m", 1e3, 1e7),
  };
  return kTable;
}

std::span<const Setting<LoadDesc>> loadSettings() {
  using L = LoadDesc;
  static const Setting<L> kTable[] = {
      row<L, &L::force>("force", "N", -kMaxLoadForce, kMaxLoadForce),
      row<L, &L::torque>("torque", "N m", -kMaxLoadTorque, kMaxLoadTorque),
      row<L, &L::start>("start", "s", 0.0, 1e6),
      row<L, &L::ramp>("ramp", "s", 0.0, 1e6),
      row<L, &L::stop>("stop", "s", 0.0, 1e6),
  };
  return kTable;
}

std::span<const Setting<FingerDesc>> fingerSettings() {
  using F = FingerDesc;
  using P = PatchSettings;
  static const Setting<F> kTable[] = {
      named(row<F, &F::patch, &P::model>("contact_model", "", 0, 0), kContactModelNames),
      named(row<F, &F::patch, &P::fill>("patch", "", 0, 0), kPatchFillNames),
      named(row<F, &F::patch, &P::contact_solver>("contact_solver", "", 0, 0), kSolverChoiceNames),
      row<F, &F::patch, &P::rings>("rings", "", 1, kMaxRings),
      row<F, &F::patch, &P::torsional_friction>("torsional_friction", "m", 0.0, 0.1),
      named(row<F, &F::patch, &P::pad_model>("pad_model", "", 0, 0), kPadModelNames),
      row<F, &F::patch, &P::pad_axis>("pad_axis", "", -1.0, 1.0),
      aboveMin(row<F, &F::patch, &P::tip_ratio>("tip_ratio", "", 0.0, 1.0)),
      live(withRule(row<F, &F::patch, &P::n_sgo>("n_sgo", "", 0, kMaxSgo), nSgoRule)),
      live(row<F, &F::patch, &P::r_max>("r_max", "m", 0.0, 1.0)),
      live(row<F, &F::patch, &P::d0>("d0", "m", 1e-6, 1.0)),
      live(row<F, &F::patch, &P::alpha>("alpha", "", 1.0, 100.0)),
      live(row<F, &F::patch, &P::stretch_length>("stretch_length", "m", 1e-6, 1.0)),
      live(row<F, &F::patch, &P::max_stretch>("max_stretch", "", 1.0, 2.0)),
      live(degrees(row<F, &F::patch, &P::tau_a>("tau_a", "deg", 0.0, 90.0))),
      live(row<F, &F::patch, &P::friction>("friction", "", 0.0, 100.0)),
      row<F, &F::proxy, &ProxySettings::radius>("proxy_radius", "m", 1e-4, 0.1),
      row<F, &F::proxy, &ProxySettings::mass>("proxy_mass", "kg", 1e-4, 10.0),
      row<F, &F::proxy, &ProxySettings::contact_stiffness>("contact_stiffness", "N/m", 1.0, 1e8),
      row<F, &F::proxy, &ProxySettings::contact_damping>("contact_damping", "N s/m", 0.0, 1e6),
      aboveMin(row<F, &F::coupling, &CouplingSettings::stiffness>("coupling_stiffness", "N/m", 0.0, 1e6)),
      row<F, &F::coupling, &CouplingSettings::damping>("coupling_damping", "N s/m", 0.0, 1e5),
      aboveMin(row<F, &F::coupling, &CouplingSettings::max_force>("max_force", "N", 0.0, 1e4)),
      row<F, &F::coupling, &CouplingSettings::max_force_rate>("max_force_rate", "N/s", 0.0, 1e7),
      row<F, &F::coupling, &CouplingSettings::max_device_speed>("max_device_speed", "m/s", 0.01, 1e4),
      // fem_pad's pad (sim/soft/fem_pad.hpp); the rules between them and the proxy in validateFinger.
      row<F, &F::pad, &PadSettings::thickness>("pad_thickness", "m", kMinPadLength, 0.05),
      degrees(row<F, &F::pad, &PadSettings::cap_angle>("pad_cap_angle", "deg", 6.0, 45.0)),
      row<F, &F::pad, &PadSettings::element_size>("pad_element_size", "m", kMinPadLength / 16.0, 0.05),
      row<F, &F::pad, &PadSettings::young>("pad_young", "Pa", kMinPadYoung, kMaxPadYoung),
      row<F, &F::pad, &PadSettings::poisson>("pad_poisson", "", 0.0, 0.49),
      row<F, &F::pad, &PadSettings::density>("pad_density", "kg/m^3", 100.0, 1e4),
      row<F, &F::pad, &PadSettings::damping>("pad_damping", "s", 0.0, 0.1),
      row<F, &F::pad, &PadSettings::contact_stiffness>("pad_contact_stiffness", "N/m", 1e3, 1e7),
      named(row<F, &F::soft_imprint>("imprint", "", 0, 0), kImprintNames),
      row<F, &F::soft_walk_fill>("walk_fill", "m", 0.0, 0.05),
  };
  return kTable;
}

template <class Desc>
std::optional<std::string> checkGiven(const Setting<Desc>& s, double given) {
  if (!std::isfinite(given)) return "must be finite";
  if ((s.kind == SettingKind::kInteger || s.kind == SettingKind::kChoice) && given != std::trunc(given)) return "expected an integer, got " + shown(given);
  const bool below = s.min_excluded ? !(given > s.min) : !(given >= s.min);
  if (below || !(given <= s.max)) return rangeReason(s.kind, s.min, s.max, s.min_excluded, given);
  if (s.rule) {
    if (const char* why = s.rule(given)) return std::string(why);
  }
  return std::nullopt;
}

template <class Desc>
std::optional<std::string> checkGiven(const Setting<Desc>& s, const Vec3& given) {
  if (!given.allFinite()) return "must be finite";
  for (int i = 0; i < 3; ++i) {
    const bool below = s.min_excluded ? !(given[i] > s.min) : !(given[i] >= s.min);
    if (below || !(given[i] <= s.max)) {
      return "every component " + rangeReason(s.kind, s.min, s.max, s.min_excluded, given[i]);
    }
  }
  return std::nullopt;
}

template <class Desc>
std::string jsonKey(const Setting<Desc>& s) {
  // The suffix JSON names give each unit.
  static constexpr std::pair<std::string_view, std::string_view> kSuffixes[] = {
      {"", ""},         {"m", "_m"},        {"deg", "_deg"},         {"kg", "_kg"},        {"s", "_s"},
      {"N", "_n"},      {"Hz", "_hz"},      {"N/m", "_n_per_m"},     {"N s/m", "_ns_per_m"},
      {"1/s", "_per_s"}, {"m/s^2", "_m_per_s2"}, {"N m", "_nm"},  {"N/s", "_n_per_s"}, {"m/s", "_m_per_s"},
      {"Pa", "_pa"},    {"kg/m^3", "_kg_per_m3"},
  };
  std::string key(s.name);
  for (char& c : key) c = c == '.' ? '_' : c;
  for (const auto& [unit, suffix] : kSuffixes) {
    if (unit == s.unit) return key.append(suffix);
  }
  GF_ASSERT(false && "every unit of a setting has a JSON suffix in jsonKey()");
  return key;
}

#define GF_INSTANTIATE(Desc)                                                                  \
  template std::optional<std::string> checkGiven(const Setting<Desc>&, double);               \
  template std::optional<std::string> checkGiven(const Setting<Desc>&, const Vec3&);          \
  template std::string jsonKey(const Setting<Desc>&);
GF_INSTANTIATE(SceneDesc)
GF_INSTANTIATE(BodyDesc)
GF_INSTANTIATE(FingerDesc)
GF_INSTANTIATE(LoadDesc)
#undef GF_INSTANTIATE

std::span<const ShapeInfo> shapeInfos() {
  using K = ShapeKind;
  static const ShapeInfo kShapes[] = {
      {K::kSphere, "sphere", "", {"radius", ""}, 4, 1, kMaxSphereSubdivisions},
      {K::kBox, "box", "", {"half_extents", ""}, 4, kMinBoxSegments, kMaxBoxSegments},
      {K::kCylinder, "cylinder", "", {"radius", "half_height"}, 64, kMinCylinderSegments, kMaxRoundSegments},
      {K::kCapsule, "capsule", "", {"radius", "half_height"}, 64, kMinCapsuleSegments, kMaxRoundSegments},
      {K::kPlane, "plane", "", {"", ""}, 1, kMinPlaneSegments, kMaxPlaneSegments},
      {K::kConvexHull, "mesh", "convex_hull", {"", ""}, 0, 0, 0},
      {K::kConvexDecomposition, "mesh", "decomposition", {"", ""}, 0, 0, 0},
      {K::kConcaveMesh, "mesh", "concave", {"", ""}, 0, 0, 0},
      {K::kSoftBox, "soft_box", "", {"half_extents", ""}, 0, 0, 0},
      {K::kSoftSphere, "soft_sphere", "", {"radius", ""}, 0, 0, 0},
      {K::kSoftCylinder, "soft_cylinder", "", {"radius", "half_height"}, 0, 0, 0},
      {K::kSoftMesh, "soft_mesh", "", {"", ""}, 0, 0, 0},
  };
  return kShapes;
}

const ShapeInfo& shapeInfo(ShapeKind kind) { return shapeInfos()[static_cast<std::size_t>(kind)]; }

bool isMeshShape(ShapeKind kind) { return !shapeInfo(kind).collision.empty(); }

std::span<const EffectSwitch> effectSwitches() {
  static const EffectSwitch kEffects[] = {
      {"gravity", &EffectSet::gravity},
      {"friction", &EffectSet::friction},
      {"god_finger", &EffectSet::god_finger},
      {"tangential_stretch", &EffectSet::tangential_stretch},
      {"angular_threshold", &EffectSet::angular_threshold},
      {"friction_cone", &EffectSet::friction_cone},
      {"force_feedback", &EffectSet::force_feedback},
  };
  return kEffects;
}

constexpr auto kNone = [](const auto&) { return false; };

std::optional<FieldError> validateScene(const SceneDesc& scene) { return firstBadSetting(sceneSettings(), scene, kNone); }

std::optional<FieldError> validateBody(const BodyDesc& body) {
  // A static body (mass 0) has no mass setting to check.
  const auto static_mass = [&](const Setting<BodyDesc>& s) { return s.name == "mass" && body.mass == 0.0; };
  if (std::optional<FieldError> e = firstBadSetting(bodySettings(), body, static_mass)) return e;
  const ShapeInfo& shape = shapeInfo(body.shape);
  if (body.shape == ShapeKind::kPlane && body.mass != 0.0) return FieldError{"mass", "a plane must be static (mass 0)"};
  if (std::optional<FieldError> e = validateSoftBody(body)) return e;
  if (body.walk_resolution != 0 &&
      (body.walk_resolution < shape.min_resolution || body.walk_resolution > shape.max_resolution)) {
    return FieldError{"walk_resolution", shape.max_resolution == 0
                                             ? "a mesh is walked as loaded; remove the field"
                                             : "must be 0 (the default, " + std::to_string(shape.default_resolution) +
                                                   ") or in " + std::to_string(shape.min_resolution) + ".." +
                                                   std::to_string(shape.max_resolution) + " for a " +
                                                   std::string(shape.shape)};
  }
  if (isMeshShape(body.shape) && body.mesh_path.empty() && !body.mesh) return FieldError{"mesh", "is empty"};
  if (!body.orientation.coeffs().allFinite() || body.orientation.norm() < 1e-9) {
    return FieldError{"orientation", "must be finite and not zero"};
  }
  return std::nullopt;
}

std::optional<FieldError> validateTrack(const DeviceTrack& track) {
  for (std::size_t k = 0; k < track.keyframes.size(); ++k) {
    const DeviceTrack::Keyframe& f = track.keyframes[k];
    const int index = static_cast<int>(k);
    if (!std::isfinite(f.time) || f.time < 0.0 || f.time > 1e6) {
      return FieldError{"keyframes.t", "must be in [0, 1e+06] s, got " + shown(f.time), index};
    }
    if (k > 0 && !(f.time > track.keyframes[k - 1].time)) {
      return FieldError{"keyframes.t", "keyframe times must increase strictly", index};
    }
    if (!f.position.allFinite() || f.position.cwiseAbs().maxCoeff() > kMaxCoordinate) {
      return FieldError{"keyframes.p", "must be finite, each coordinate in [-1000, 1000] m", index};
    }
  }
  return std::nullopt;
}

std::optional<FieldError> validateFinger(const FingerDesc& finger) {
  if (std::optional<FieldError> e = firstBadSetting(fingerSettings(), finger, kNone)) return e;
  if (finger.patch.model == ContactModel::kFemPad) {
    if (std::optional<FieldError> e = validatePadShape(finger)) return e;
  }
  // The contact is a spring too: at the coupling's clamp it lets the proxy in by max_force /
  // contact_stiffness. Past its radius the proxy's centre is inside the body, whose nearest face
  // may then be the far one: a 1 mm proxy at 40 N went 2 mm into a 1 mm wall.
  if (const double depth = finger.coupling.max_force / finger.proxy.contact_stiffness; !(depth < finger.proxy.radius)) {
    const auto [bound, got] = distinctTexts(depth, finger.proxy.radius);
    return FieldError{"proxy_radius", "must exceed max_force / contact_stiffness = " + bound +
                                          " m, how deep the contact lets the proxy in at the coupling's clamp (lower "
                                          "max_force or raise contact_stiffness), got " + got};
  }
  // A walk filled every walk_fill: below 0.1 mm the points (each a closest-point query a step)
  // outnumber any mesh's faces.
  if (finger.soft_walk_fill > 0.0 && finger.soft_walk_fill < kMinWalkFill) {
    return FieldError{"walk_fill", "must be 0 (off) or at least " + shown(kMinWalkFill) + " m, got " + shown(finger.soft_walk_fill)};
  }
  // The pad's axis is a direction: normalized where it is used, so it needs a length.
  if (!(finger.patch.pad_axis.norm() >= kMinPadAxisLength)) {
    return FieldError{"pad_axis", "must be a direction, of length at least " + shown(kMinPadAxisLength) + ", got " +
                                      shown(finger.patch.pad_axis.norm())};
  }
  if (std::optional<FieldError> e = validateTrack(finger.device)) {
    e->field = "device." + e->field;
    return e;
  }
  return std::nullopt;
}

std::optional<FieldError> validateCouplingStability(const FingerDesc& finger, double haptic_rate_hz) {
  const double m = finger.proxy.mass, rate = haptic_rate_hz;
  if (finger.coupling.stiffness > m * rate * rate) {
    const auto [bound, got] = distinctTexts(m * rate * rate, finger.coupling.stiffness);
    return FieldError{"coupling_stiffness", "must be at most proxy_mass x haptic_rate^2 = " + bound +
                                                " N/m here (the coupling spring is integrated explicitly), got " + got};
  }
  if (finger.coupling.damping > m * rate) {
    const auto [bound, got] = distinctTexts(m * rate, finger.coupling.damping);
    return FieldError{"coupling_damping", "must be at most proxy_mass x haptic_rate = " + bound +
                                              " N s/m here (the coupling damper is integrated explicitly), got " + got};
  }
  return std::nullopt;
}

std::optional<FieldError> validateOverlapStability(const SceneDesc& scene) {
  if (scene.world.overlap != OverlapMode::kPushApart) return std::nullopt;
  const double rate = scene.world.haptic_rate_hz;
  for (const FingerDesc& f : scene.fingers) {
    // Each proxy feels its coupling and the push against the other proxy: the relative motion
    // of two proxies of mass m is a spring of coupling + 2 x overlap stiffness on m, integrated
    // explicitly like the coupling (validateCouplingStability).
    const double bound = 0.5 * (f.proxy.mass * rate * rate - f.coupling.stiffness);
    if (scene.world.overlap_stiffness > bound) {
      const auto [shown_bound, got] = distinctTexts(bound, scene.world.overlap_stiffness);
      return FieldError{"world.overlap_stiffness", "must be at most (proxy_mass x haptic_rate^2 - coupling_stiffness) / 2 = " +
                                                       shown_bound + " N/m for finger '" + f.name +
                                                       "' (push_apart's spring is integrated explicitly), got " + got};
    }
  }
  return std::nullopt;
}

std::string liveFingerSettingNames() {
  std::string names;
  for (const Setting<FingerDesc>& s : fingerSettings()) {
    if (s.live) names.append(names.empty() ? "" : ", ").append(s.name);
  }
  return names;
}

std::optional<FieldError> validatePatch(const PatchSettings& patch) {
  FingerDesc finger;
  finger.patch = patch;
  return firstBadSetting(fingerSettings(), finger, [](const Setting<FingerDesc>& s) { return !s.live; });
}

std::optional<FieldError> validateLoad(const LoadDesc& load, std::span<const BodyDesc> bodies) {
  if (load.body < 0 || load.body >= static_cast<int>(bodies.size())) {
    return FieldError{"body", "no body of index " + std::to_string(load.body) + " (the scene has " +
                                  std::to_string(bodies.size()) + ")"};
  }
  if (bodies[static_cast<std::size_t>(load.body)].mass == 0.0) {
    return FieldError{"body", "'" + bodies[static_cast<std::size_t>(load.body)].name +
                                  "' is static (mass 0): a load needs a dynamic body"};
  }
  // A load without a stop (+inf) has no stop time to check.
  const auto never_stops = [&](const Setting<LoadDesc>& s) {
    return s.name == "stop" && load.stop == HUGE_VAL;
  };
  if (std::optional<FieldError> e = firstBadSetting(loadSettings(), load, never_stops)) return e;
  if (!(load.stop > load.start)) {
    return FieldError{"stop",
                      "must be after start (" + shown(load.start) + " s), got " + shown(load.stop)};
  }
  return std::nullopt;
}

std::optional<FieldError> validateChange(const PatchChange& change, std::span<const FingerDesc> fingers,
                                         double previous_time) {
  if (change.finger < 0 || change.finger >= static_cast<int>(fingers.size())) {
    return FieldError{"finger", "no finger of index " + std::to_string(change.finger) + " (the scene has " +
                                    std::to_string(fingers.size()) + ")"};
  }
  if (!(change.time >= 0.0 && change.time <= 1e6)) {
    return FieldError{"t", "must be in [0, 1e6] s, got " + shown(change.time)};
  }
  if (change.time < previous_time) {
    return FieldError{"t", "changes must be in time order: " + shown(change.time) + " s comes after " +
                               shown(previous_time) + " s"};
  }
  const ContactModel model = fingers[static_cast<std::size_t>(change.finger)].patch.model;
  if (std::optional<FieldError> e = validateModelChange(model, change.patch.model)) return e;
  return validatePatch(change.patch);
}

void requireValid(const SceneDesc& scene) {
  if (std::optional<FieldError> e = validateScene(scene)) throw DescriptionError("scene", *e);
  for (const BodyDesc& b : scene.bodies) {
    if (std::optional<FieldError> e = validateBody(b)) throw DescriptionError("body '" + b.name + "'", *e);
  }
  for (const FingerDesc& f : scene.fingers) {
    if (std::optional<FieldError> e = validateFinger(f)) throw DescriptionError("finger '" + f.name + "'", *e);
  }
  if (std::optional<FieldError> e = validateOverlapStability(scene)) throw DescriptionError("scene", *e);
  for (std::size_t i = 0; i < scene.loads.size(); ++i) {
    if (std::optional<FieldError> e = validateLoad(scene.loads[i], scene.bodies)) {
      throw DescriptionError("load " + std::to_string(i), *e);
    }
  }
  double previous_time = 0.0;
  for (std::size_t i = 0; i < scene.changes.size(); ++i) {
    if (std::optional<FieldError> e = validateChange(scene.changes[i], scene.fingers, previous_time)) {
      throw DescriptionError("change " + std::to_string(i), *e);
    }
    previous_time = scene.changes[i].time;
  }
}

namespace {

// The name of `value` in its choice table; "?" for a value outside it.
template <class Enum, std::size_t N>
std::ostream& writeName(std::ostream& os, Enum value, const std::string_view (&names)[N]) {
  const auto i = static_cast<std::size_t>(value);
  return os << (i < N ? names[i] : std::string_view("?"));
}

}  // namespace

std::ostream& operator<<(std::ostream& os, ContactModel model) { return writeName(os, model, kContactModelNames); }
std::ostream& operator<<(std::ostream& os, PatchFill fill) { return writeName(os, fill, kPatchFillNames); }
std::ostream& operator<<(std::ostream& os, ContactSolver solver) { return writeName(os, solver, kContactSolverNames); }
std::ostream& operator<<(std::ostream& os, SolverChoice choice) { return writeName(os, choice, kSolverChoiceNames); }
std::ostream& operator<<(std::ostream& os, PadModel pad) { return writeName(os, pad, kPadModelNames); }

}  // namespace gf::sim
