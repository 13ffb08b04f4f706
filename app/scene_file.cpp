#include "app/scene_file.hpp"

#include <toml++/toml.h>
#include <nlohmann/json.hpp>

#include <arpa/inet.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <set>
#include <sstream>

#include "app/toml_reader.hpp"
#include "sim/mesh_import.hpp"
#include "sim/settings.hpp"

namespace gf::app {
namespace {

namespace fs = std::filesystem;
using sim::Vec3;

constexpr double kDegToRad = std::numbers::pi / 180.0;

std::string resolvePath(const std::string& base_dir, const std::string& p) {
  const fs::path path(p);
  return path.is_absolute() || base_dir.empty() ? p : (fs::path(base_dir) / path).lexically_normal().string();
}

constexpr const char* kInterpolations[] = {"linear", "smooth"};
constexpr const char* kUpAxes[] = {"y", "z", "-z", "x", "-x", "-y"};  // a mesh body's up_axis
constexpr const char* kUdpFields[] = {"channel", "workspace_scale", "workspace_offset", "start", "force_scale",
                                      "stale_after", "force_ramp", "velocity_smoothing"};

// Effects that change the pictures, not the physics (sim::effectSwitches() lists those).
struct ViewEffect {
  std::string_view name;
  bool ViewSettings::*on;
};
constexpr ViewEffect kViewEffects[] = {
    {"patch_highlight", &ViewSettings::patch_highlight},
    {"patch_insets", &ViewSettings::patch_insets},
    {"shadows", &ViewSettings::shadows},
    {"overlay", &ViewSettings::overlay},
};

std::vector<std::string_view> effectNames() {
  std::vector<std::string_view> names;
  for (const sim::EffectSwitch& e : sim::effectSwitches()) names.push_back(e.name);
  for (const ViewEffect& e : kViewEffects) names.push_back(e.name);
  return names;
}

// `effects`: every effect listed is on, every other one off.
void readEffects(Reader& r, sim::EffectSet& e, ViewSettings& view) {
  if (!r.has("effects")) {
    r.fail(nullptr, "effects", "missing: list the effects the scene calls for (any of " + join(effectNames()) + ")");
  }
  for (const sim::EffectSwitch& s : sim::effectSwitches()) e.*s.on = false;
  for (const ViewEffect& s : kViewEffects) view.*s.on = false;
  for (const auto& [name, node] : r.strings("effects")) {
    const auto sim_effect = std::find_if(sim::effectSwitches().begin(), sim::effectSwitches().end(),
                                         [&wanted = name](const sim::EffectSwitch& s) { return s.name == wanted; });
    const auto view_effect = std::find_if(std::begin(kViewEffects), std::end(kViewEffects),
                                          [&wanted = name](const ViewEffect& s) { return s.name == wanted; });
    if (sim_effect != sim::effectSwitches().end()) {
      e.*sim_effect->on = true;
    } else if (view_effect != std::end(kViewEffects)) {
      view.*view_effect->on = true;
    } else {
      r.fail(node, "effects", "unknown effect '" + name + "' (one of " + join(effectNames()) + ")");
    }
  }
}

// widget = "FINGER/FIELD" names a finger of the scene and a widget of its panel; the value is
// one the widget's setting accepts (in the unit the widget shows).
void checkWidget(Reader& r, const sim::SceneDesc& scene, const render::WidgetAction& a) {
  const std::size_t slash = a.widget.find('/');
  const std::string finger = a.widget.substr(0, slash);
  const std::string field = slash == std::string::npos ? "" : a.widget.substr(slash + 1);
  const bool known_finger = std::any_of(scene.fingers.begin(), scene.fingers.end(),
                                        [&](const sim::FingerDesc& f) { return f.name == finger; });
  const render::OverlayWidget* widget = render::findOverlayWidget(field);
  if (!known_finger || !widget) {
    std::vector<std::string_view> names;
    for (const render::OverlayWidget& w : render::kOverlayWidgets) names.push_back(w.field);
    r.fail(r.find("widget"), "widget", "expected FINGER/FIELD with a finger of the scene and FIELD one of " + join(names));
  }
  if (field == "god_finger") {
    if (a.value != "on" && a.value != "off") r.fail(r.find("value"), "value", "expected \"on\" or \"off\"");
    return;
  }
  char* end = nullptr;
  const double shown = std::strtod(a.value.c_str(), &end);
  if (a.value.empty() || *end != '\0' || !std::isfinite(shown)) r.fail(r.find("value"), "value", "expected a number");
  const sim::Setting<sim::FingerDesc>& s = *sim::findSetting(sim::fingerSettings(), field);
  if (const std::optional<std::string> why = sim::checkGiven(s, shown / widget->shown_per_unit)) {
    r.fail(r.find("value"), "value", field + " " + *why);
  }
}

// [render]: frame size, anti-aliasing and scripted overlay input.
void readView(Reader& parent, SessionDesc& s) {
  ViewSettings& v = s.view;
  if (const toml::node* n = parent.find("render")) {
    if (!n->is_table()) parent.fail(n, "render", "expected a table");
    Reader r(*n->as_table(), "render", parent.file());
    v.width = r.integer("width", v.width, 16, 1920);
    v.height = r.integer("height", v.height, 16, 1080);
    const std::string aa = r.string("antialiasing", render::antialiasingName(v.antialiasing));
    if (const std::optional<render::Antialiasing> parsed = render::parseAntialiasing(aa)) {
      v.antialiasing = *parsed;
    } else {
      r.fail(r.find("antialiasing"), "antialiasing", "expected \"fxaa\", \"msaa\" or \"none\"");
    }
    v.msaa_samples = r.integer("msaa_samples", v.msaa_samples, 2, 8);
    if (const toml::node* k = r.find("actions")) {
      const toml::array* a = k->as_array();
      if (!a) r.fail(k, "actions", "expected an array of {t = s, widget = \"FINGER/FIELD\", value = \"...\"}");
      for (const toml::node& e : *a) {
        if (!e.is_table()) r.fail(&e, "actions", "expected {t = s, widget = \"FINGER/FIELD\", value = \"...\"}");
        Reader ar(*e.as_table(), r.field("actions"), r.file());
        render::WidgetAction act;
        act.time = ar.requiredNumber("t", 0.0, s.scene.duration);
        act.widget = ar.string("widget", "");
        act.value = ar.string("value", "");
        checkWidget(ar, s.scene, act);
        if (!v.actions.empty() && act.time < v.actions.back().time) ar.fail(ar.find("t"), "t", "actions must be in time order");
        v.actions.push_back(act);
        ar.finish();
      }
    }
    r.finish();
  }
  if (!v.actions.empty() && !v.overlay) {
    parent.fail(parent.find("render"), "render.actions", "scripted input needs the overlay effect");
  }
}

Eigen::Quaterniond readOrientation(Reader& r) {
  if (r.has("orientation") && r.has("rotation")) {
    r.fail(r.find("rotation"), "rotation", "give either orientation or rotation, not both");
  }
  if (r.has("rotation")) {
    const Vec3 deg = r.vec3("rotation", Vec3::Zero());
    return Eigen::AngleAxisd(deg.x() * kDegToRad, Vec3::UnitX()) *
           Eigen::AngleAxisd(deg.y() * kDegToRad, Vec3::UnitY()) *
           Eigen::AngleAxisd(deg.z() * kDegToRad, Vec3::UnitZ());
  }
  const toml::node* n = r.find("orientation");
  if (!n) return Eigen::Quaterniond::Identity();
  const toml::array* a = n->as_array();
  if (!a || a->size() != 4 || !std::all_of(a->begin(), a->end(), [](const toml::node& e) {
        return e.is_number() && std::isfinite(e.value<double>().value_or(NAN));
      })) {
    r.fail(n, "orientation", "expected a quaternion [x, y, z, w] of finite numbers");
  }
  Eigen::Quaterniond q(a->get(3)->value<double>().value(), a->get(0)->value<double>().value(),
                       a->get(1)->value<double>().value(), a->get(2)->value<double>().value());
  if (q.norm() < 1e-9) r.fail(n, "orientation", "quaternion has zero length");
  return q.normalized();
}

// `shape` (and `collision` for meshes): the row of sim::shapeInfos() it names.
const sim::ShapeInfo& readShape(Reader& r) {
  std::vector<std::string_view> shapes, collisions;
  for (const sim::ShapeInfo& s : sim::shapeInfos()) {
    if (std::find(shapes.begin(), shapes.end(), s.shape) == shapes.end()) shapes.push_back(s.shape);
    if (!s.collision.empty()) collisions.push_back(s.collision);
  }
  const std::string_view shape = shapes[static_cast<std::size_t>(r.choice("shape", shapes, -1))];
  const std::string_view collision =
      shape == "mesh" ? collisions[static_cast<std::size_t>(r.choice("collision", collisions, 0))] : "";
  for (const sim::ShapeInfo& s : sim::shapeInfos()) {
    if (s.shape == shape && s.collision == collision) return s;
  }
  r.fail(r.find("shape"), "shape", "no such shape");
}

// `mesh` and `scale`: the mesh file, loaded once per (path, scale) into `meshes`.
void readMesh(Reader& r, const std::string& base_dir, sim::MeshCache& meshes, sim::BodyDesc& b) {
  const toml::node* n = r.find("mesh");
  if (!n || !n->is_string()) r.fail(n, "mesh", "expected the mesh file's path (a string)");
  b.mesh_path = resolvePath(base_dir, n->as_string()->get());
  r.setting(*sim::findSetting(sim::bodySettings(), "scale"), b, "scale");
  try {
    b.mesh = meshes.load(b.mesh_path, b.mesh_scale);
  } catch (const sim::MeshLoadError& e) {
    r.fail(n, "mesh", e.what());
  }
  // The file's up axis when it is not the scene's +y (CAD and 3D-printing files are mostly +z
  // up): the mesh turned so that axis points up. Files that declare theirs (Collada) are turned
  // on reading already; "y" keeps the mesh as read.
  const int up = r.choice("up_axis", kUpAxes, 0);
  if (up != 0) {
    // Rotations taking the named axis onto +y (right-handed, proper).
    static const Eigen::Matrix3d kTurns[] = {
        Eigen::Matrix3d::Identity(),
        (Eigen::Matrix3d() << 1, 0, 0, 0, 0, 1, 0, -1, 0).finished(),   // +z up: (x, y, z) -> (x, z, -y)
        (Eigen::Matrix3d() << 1, 0, 0, 0, 0, -1, 0, 1, 0).finished(),   // -z up: (x, y, z) -> (x, -z, y)
        (Eigen::Matrix3d() << 0, -1, 0, 1, 0, 0, 0, 0, 1).finished(),   // +x up: (x, y, z) -> (-y, x, z)
        (Eigen::Matrix3d() << 0, 1, 0, -1, 0, 0, 0, 0, 1).finished(),   // -x up: (x, y, z) -> (y, -x, z)
        (Eigen::Matrix3d() << 1, 0, 0, 0, -1, 0, 0, 0, -1).finished()}; // -y up: (x, y, z) -> (x, -y, -z)
    std::vector<sim::Vec3> turned;
    turned.reserve(b.mesh->vertices().size());
    for (const sim::Vec3& p : b.mesh->vertices()) turned.push_back(kTurns[up] * p);
    b.mesh = std::make_shared<const sim::Mesh>(sim::buildMesh(turned, b.mesh->triangles()));
  }
}

// A body's `density` may lie in this range (kg/m^3: from aerogel to osmium, twice over).
constexpr double kMinDensity = 1.0, kMaxDensity = 50000.0;

// The volume of a body's shape (m^3): analytic for primitives, the enclosed volume for meshes
// (<= 0 for an open or inside-out mesh).
double bodyVolume(const sim::BodyDesc& b) {
  constexpr double pi = 3.14159265358979323846;
  switch (b.shape) {
    case sim::ShapeKind::kSphere: return 4.0 / 3.0 * pi * b.radius * b.radius * b.radius;
    case sim::ShapeKind::kBox: return 8.0 * b.half_extents.prod();
    case sim::ShapeKind::kCylinder: return pi * b.radius * b.radius * 2.0 * b.half_height;
    case sim::ShapeKind::kCapsule:
      return pi * b.radius * b.radius * 2.0 * b.half_height + 4.0 / 3.0 * pi * b.radius * b.radius * b.radius;
    case sim::ShapeKind::kPlane: return 0.0;
    case sim::ShapeKind::kConvexHull:
    case sim::ShapeKind::kConvexDecomposition:
    case sim::ShapeKind::kConcaveMesh: return b.mesh ? sim::massProperties(*b.mesh).volume : 0.0;
  }
  return 0.0;
}

// Body settings every shape has (dimensions, scale and mass are read where they apply).
bool commonBodySetting(const sim::Setting<sim::BodyDesc>& s) {
  for (const sim::ShapeInfo& shape : sim::shapeInfos()) {
    for (std::string_view d : shape.dimensions) {
      if (d == s.name) return false;
    }
  }
  return s.name != "scale" && s.name != "mass";
}

sim::BodyDesc readBody(const std::string& name, const toml::table& t, const Reader& parent,
                       const std::string& base_dir, sim::MeshCache& meshes) {
  Reader r(t, parent.field("bodies." + name), parent.file());
  sim::BodyDesc b;
  b.name = name;
  const sim::ShapeInfo& shape = readShape(r);
  b.shape = shape.kind;
  for (std::string_view d : shape.dimensions) {
    if (!d.empty()) r.setting(*sim::findSetting(sim::bodySettings(), d), b, std::string(d), true);
  }
  if (sim::isMeshShape(b.shape)) readMesh(r, base_dir, meshes, b);
  const bool is_plane = b.shape == sim::ShapeKind::kPlane;
  const bool is_static = r.boolean("static", is_plane);
  if (is_plane && !is_static) r.fail(r.find("static"), "static", "a plane is always static");
  if (is_static) {
    for (const char* field : {"mass", "density"}) {
      if (r.has(field)) r.fail(r.find(field), field, "a static body has no mass; remove the field");
    }
    b.mass = 0.0;
  } else if (r.has("density")) {  // the mass from the shape's volume
    if (r.has("mass")) r.fail(r.find("density"), "density", "give mass or density, not both");
    const double density = r.requiredNumber("density", kMinDensity, kMaxDensity);
    const double volume = bodyVolume(b);
    if (!(volume > 0.0)) {
      r.fail(r.find("density"), "density", "the mesh encloses no volume (open or inside-out): give a mass instead");
    }
    b.mass = density * volume;
    const sim::Setting<sim::BodyDesc>& mass = *sim::findSetting(sim::bodySettings(), "mass");
    if (const std::optional<std::string> why = sim::checkGiven(mass, b.mass)) {
      char text[160];
      std::snprintf(text, sizeof text, "gives a mass of %g kg (volume %g m^3): ", b.mass, volume);
      r.fail(r.find("density"), "density", text + *why);
    }
  } else {
    r.setting(*sim::findSetting(sim::bodySettings(), "mass"), b, "mass", true);
  }
  for (const sim::Setting<sim::BodyDesc>& s : sim::bodySettings()) {
    if (commonBodySetting(s)) r.setting(s, b, std::string(s.name));
  }
  b.orientation = readOrientation(r);
  r.failOn(sim::validateBody(b));
  r.finish();
  return b;
}

// The keyframes of a device table: each {t, p}, then the track's own rules (times increasing).
void readKeyframes(Reader& r, sim::DeviceTrack& d) {
  const toml::node* k = r.find("keyframes");
  const toml::array* a = k->as_array();
  if (!a || a->empty()) r.fail(k, "keyframes", "expected a non-empty array of {t = s, p = [x, y, z]}");
  std::vector<const toml::table*> tables;
  for (const toml::node& e : *a) {
    if (!e.is_table()) r.fail(&e, "keyframes", "expected {t = s, p = [x, y, z]}");
    Reader kr(*e.as_table(), r.field("keyframes"), r.file());
    sim::DeviceTrack::Keyframe kf{kr.requiredNumber("t"), Vec3::Zero()};
    const toml::node* p = kr.find("p");
    if (!p) kr.fail(&e, "p", "missing (device position [x, y, z] in m)");
    kf.position = kr.checkedVec3(*p, "p");
    kr.finish();
    d.keyframes.push_back(kf);
    tables.push_back(e.as_table());
  }
  if (const std::optional<sim::FieldError> e = sim::validateTrack(d)) {
    const std::string key = e->field.substr(e->field.find('.') + 1);  // "keyframes.t" -> "t"
    Reader kr(*tables[static_cast<std::size_t>(e->index)], r.field("keyframes"), r.file());
    kr.fail(kr.nodeOf(key), key, e->reason);
  }
}

// `udp = PORT` or `udp = "HOST:PORT"` (an IPv4 address, or "localhost"; a bare port listens on
// loopback), with the UDP device's own fields.
UdpDeviceDesc readUdpDevice(Reader& r) {
  UdpDeviceDesc u;
  const toml::node* n = r.find("udp");
  u.file = sourceOf(*n, r.file());
  u.line = static_cast<int>(n->source().begin.line);
  u.column = static_cast<int>(n->source().begin.column);
  constexpr const char* kForm = "expected a port (listening on 127.0.0.1) or \"HOST:PORT\" with HOST an IPv4 address";
  std::string port_text;
  if (n->is_integer()) {
    port_text = std::to_string(n->as_integer()->get());
  } else if (n->is_string()) {
    const std::string text = n->as_string()->get();
    const std::size_t colon = text.rfind(':');
    if (colon == std::string::npos || colon == 0) r.fail(n, "udp", std::string(kForm) + ", got '" + text + "'");
    u.host = text.substr(0, colon);
    if (u.host == "localhost") u.host = "127.0.0.1";
    in_addr address{};
    if (inet_pton(AF_INET, u.host.c_str(), &address) != 1) {
      r.fail(n, "udp", "'" + u.host + "' is not an IPv4 address (such as 127.0.0.1, or 0.0.0.0 for every interface)");
    }
    port_text = text.substr(colon + 1);
  } else {
    r.fail(n, "udp", kForm);
  }
  int port = -1;
  const auto [end, error] = std::from_chars(port_text.data(), port_text.data() + port_text.size(), port);
  if (error != std::errc() || end != port_text.data() + port_text.size() || port < 0 || port > 65535) {
    r.fail(n, "udp", "the port must be a whole number in 0..65535 (0: any free port), got '" + port_text + "'");
  }
  u.port = port;
  u.channel = r.integer("channel", 0, 0, 255);
  u.workspace_scale = r.number("workspace_scale", u.workspace_scale, 0.01, 100.0);
  u.workspace_offset = r.vec3("workspace_offset", u.workspace_offset);
  if (u.workspace_offset.cwiseAbs().maxCoeff() > sim::kMaxSceneCoordinate) {
    r.fail(r.nodeOf("workspace_offset"), "workspace_offset", "each coordinate must be in [-1000, 1000] m");
  }
  u.start = r.vec3("start", u.workspace_offset);
  if (u.start.cwiseAbs().maxCoeff() > sim::kMaxSceneCoordinate) {
    r.fail(r.nodeOf("start"), "start", "each coordinate must be in [-1000, 1000] m");
  }
  u.force_scale = r.number("force_scale", u.force_scale, 0.0, 100.0);
  u.stale_after = r.number("stale_after", u.stale_after, 0.005, 1.0);
  u.force_ramp = r.number("force_ramp", u.force_ramp, 0.005, 10.0);
  u.velocity_smoothing = r.number("velocity_smoothing", u.velocity_smoothing, 0.0, 0.1);
  return u;
}

// A finger's device: keyframes, a recorded CSV, or a live UDP device (then `udp` is set and
// the track holds the device at its start, where the proxy starts).
sim::DeviceTrack readDevice(Reader& parent, const std::string& base_dir, std::optional<UdpDeviceDesc>& udp) {
  const toml::node* n = parent.find("device");
  if (!n) parent.fail(nullptr, "device", "missing: the finger needs a device (keyframes, csv or udp)");
  if (!n->is_table()) parent.fail(n, "device", "expected a table");
  Reader r(*n->as_table(), parent.field("device"), parent.file());
  sim::DeviceTrack d;
  if (static_cast<int>(r.has("csv")) + static_cast<int>(r.has("keyframes")) + static_cast<int>(r.has("udp")) != 1) {
    r.fail(nullptr, "keyframes", "give exactly one of keyframes, csv and udp");
  }
  if (!r.has("udp")) {
    for (const char* key : kUdpFields) {
      if (r.has(key)) r.fail(r.nodeOf(key), key, "belongs to a UDP device (udp = ...)");
    }
  }
  d.interpolation = r.choice("interpolation", kInterpolations, 1) == 0 ? sim::Interpolation::kLinear
                                                                       : sim::Interpolation::kSmooth;
  if (r.has("csv")) {
    const toml::node* c = r.find("csv");
    if (!c->is_string()) r.fail(c, "csv", "expected the CSV file's path (a string)");
    if (r.has("interpolation")) r.fail(r.find("interpolation"), "interpolation", "a recorded CSV is always linear");
    d = readDeviceCsv(resolvePath(base_dir, c->as_string()->get()));
  } else if (r.has("udp")) {
    if (r.has("interpolation")) r.fail(r.find("interpolation"), "interpolation", "a live device is not interpolated");
    udp = readUdpDevice(r);
    d.keyframes.push_back({0.0, udp->start});
  } else {
    readKeyframes(r, d);
  }
  r.finish();
  return d;
}

sim::FingerDesc readFinger(const std::string& name, const toml::table& t, const Reader& parent,
                           const std::string& base_dir, double haptic_rate_hz, std::optional<UdpDeviceDesc>& udp) {
  Reader r(t, parent.field("fingers." + name), parent.file());
  sim::FingerDesc f;
  f.name = name;
  for (const sim::Setting<sim::FingerDesc>& s : sim::fingerSettings()) r.setting(s, f, std::string(s.name));
  f.device = readDevice(r, base_dir, udp);
  r.failOn(sim::validateFinger(f));
  r.failOn(sim::validateCouplingStability(f, haptic_rate_hz));
  r.finish();
  return f;
}

CameraDesc readCamera(const std::string& name, const toml::table& t, const Reader& parent) {
  Reader r(t, parent.field("cameras." + name), parent.file());
  CameraDesc c;
  c.name = name;
  c.position = r.vec3("position", c.position);
  c.target = r.vec3("target", c.target);
  c.fov_deg = r.number("fov", c.fov_deg, 1.0, 170.0);
  if ((c.position - c.target).norm() < 1e-6) r.fail(r.find("target"), "target", "equals the camera position");
  r.finish();
  return c;
}

void readRecord(Reader& parent, SessionDesc& s) {
  const toml::node* n = parent.find("record");
  if (!n) return;
  if (!n->is_table()) parent.fail(n, "record", "expected a table");
  Reader r(*n->as_table(), "record", parent.file());
  s.record.trace = r.boolean("trace", true);
  s.record.contact_times = r.numbers("contacts");
  for (const auto& [body, node] : r.strings("forces")) {
    const bool known = std::any_of(s.scene.bodies.begin(), s.scene.bodies.end(),
                                   [&wanted = body](const sim::BodyDesc& b) { return b.name == wanted && b.mass > 0.0; });
    if (!known) r.fail(node, "forces", "no dynamic body called '" + body + "'");
    s.record.force_bodies.push_back(body);
  }
  s.record.force_chart = r.boolean("force_chart", false);
  s.record.force_chart_title = r.string("force_chart_title", "");
  if (s.record.force_chart && s.record.force_bodies.empty()) {
    r.fail(r.find("force_chart"), "force_chart", "needs a body listed in record.forces");
  }
  r.finish();
}

// [expect]: invariants of the run (app/expectations.hpp).
void readExpect(Reader& parent, SessionDesc& s) {
  const toml::node* n = parent.find("expect");
  if (!n) return;
  if (!n->is_table()) parent.fail(n, "expect", "expected a table");
  Reader r(*n->as_table(), "expect", parent.file());
  ExpectDesc& e = s.expect;
  const auto optional = [](Reader& at, const std::string& key, double lo, double hi) -> std::optional<double> {
    if (!at.has(key)) return std::nullopt;
    return at.number(key, 0.0, lo, hi);
  };
  e.finite = r.boolean("finite", true);
  e.max_speed = optional(r, "max_speed", 0.0, 1e6);
  e.max_angular_speed = optional(r, "max_angular_speed", 0.0, 1e6);
  e.energy_growth = optional(r, "energy_growth", 0.0, 1e9);
  e.max_penetration = optional(r, "max_penetration", 0.0, 1e6);
  e.no_tunnelling = r.boolean("no_tunnelling", false);
  for (const auto& [name, t] : r.namedTables("bodies")) {
    const auto body = std::find_if(s.scene.bodies.begin(), s.scene.bodies.end(),
                                   [&wanted = name](const sim::BodyDesc& b) { return b.name == wanted; });
    if (body == s.scene.bodies.end() || body->mass <= 0.0) {
      r.fail(t, "bodies." + name, "no dynamic body called '" + name + "'");
    }
    Reader br(*t, "expect.bodies." + name, parent.file());
    BodyExpect& b = e.bodies[name];
    b.max_speed = optional(br, "max_speed", 0.0, 1e6);
    b.max_angular_speed = optional(br, "max_angular_speed", 0.0, 1e6);
    b.stays_above = optional(br, "stays_above", -1e6, 1e6);
    b.ends_above = optional(br, "ends_above", -1e6, 1e6);
    b.max_rotation_deg = optional(br, "max_rotation_deg", 0.0, 180.0);
    b.after = br.number("after", 0.0, 0.0, 1e6);
    br.finish();
  }
  for (const auto& [name, t] : r.namedTables("fingers")) {
    const bool known = std::any_of(s.scene.fingers.begin(), s.scene.fingers.end(),
                                   [&wanted = name](const sim::FingerDesc& f) { return f.name == wanted; });
    if (!known) r.fail(t, "fingers." + name, "no finger called '" + name + "'");
    Reader fr(*t, "expect.fingers." + name, parent.file());
    FingerExpect& f = e.fingers[name];
    if (fr.has("min_sgo")) f.min_sgo = fr.integer("min_sgo", 0, 0, sim::kMaxSgo * sim::kMaxRings);
    if (const toml::node* w = fr.find("window")) {
      const std::vector<double> v = fr.numbers("window");
      if (v.size() != 2 || !(v[1] > v[0])) fr.fail(w, "window", "expected [from, to] in seconds, from < to");
      f.from = v[0];
      f.to = v[1];
    }
    f.max_force = optional(fr, "max_force", 0.0, 1e9);
    f.max_penetration = optional(fr, "max_penetration", 0.0, 1e6);
    fr.finish();
  }
  r.finish();
}

// The index of the element of `items` (bodies or fingers) whose name field `key` gives, or fails
// naming the field: missing, not a string, or no such name (with the names there are).
template <class Desc>
int namedIndex(Reader& r, const std::string& key, const std::string& what, const std::vector<Desc>& items) {
  const toml::node* n = r.find(key);
  if (!n) r.fail(nullptr, key, "missing (the name of " + what + ")");
  if (!n->is_string()) r.fail(n, key, "expected the name of " + what + " (a string), got " + typeName(*n));
  const std::string name = n->as_string()->get();
  const auto named = std::find_if(items.begin(), items.end(), [&](const Desc& d) { return d.name == name; });
  if (named == items.end()) {
    std::vector<std::string> names;
    for (const Desc& d : items) names.push_back(d.name);
    r.fail(n, key, "no " + key + " called '" + name + "' (one of " + join(names) + ")");
  }
  return static_cast<int>(named - items.begin());
}

// One `[[loads]]` entry: the body it acts on (by name), then force, torque, start, ramp and stop.
sim::LoadDesc readLoad(Reader& r, const std::vector<sim::BodyDesc>& bodies) {
  sim::LoadDesc load;
  load.body = namedIndex(r, "body", "a dynamic body", bodies);
  load.body_name = bodies[static_cast<std::size_t>(load.body)].name;
  if (!r.has("force") && !r.has("torque")) {
    r.fail(nullptr, "force",
           "missing: give force = [x, y, z] (N), torque = [x, y, z] (N m) or both");
  }
  for (const sim::Setting<sim::LoadDesc>& s : sim::loadSettings()) {
    r.setting(s, load, std::string(s.name));
  }
  r.failOn(sim::validateLoad(load, bodies));
  r.finish();
  return load;
}

// `[[loads]]`: known external loads, named `loads.INDEX` in errors and --set.
void readLoads(Reader& parent, sim::SceneDesc& scene) {
  for (const auto& [key, t] : parent.arrayTables("loads", "")) {
    Reader r(*t, parent.field(key), parent.file());
    scene.loads.push_back(readLoad(r, scene.bodies));
  }
}

// `[[changes]]`: scripted changes of a finger's live god-finger settings at a time, in time
// order, named `changes.INDEX` in errors and --set. Each entry holds the finger's whole settings
// from then on: the fields it names over the finger's settings before it.
void readChanges(Reader& parent, sim::SceneDesc& scene) {
  std::vector<sim::PatchSettings> current;
  for (const sim::FingerDesc& f : scene.fingers) current.push_back(f.patch);
  double previous_time = 0.0;
  for (const auto& [key, t] : parent.arrayTables("changes", "")) {
    Reader r(*t, parent.field(key), parent.file());
    sim::PatchChange change;
    change.finger = namedIndex(r, "finger", "a finger", scene.fingers);
    change.time = r.requiredNumber("t", 0.0, 1e6);
    sim::FingerDesc next = scene.fingers[static_cast<std::size_t>(change.finger)];
    next.patch = current[static_cast<std::size_t>(change.finger)];
    bool any = false;
    const std::string live = sim::liveFingerSettingNames();
    for (const sim::Setting<sim::FingerDesc>& s : sim::fingerSettings()) {
      const std::string field(s.name);
      if (!s.live && r.has(field)) r.fail(r.find(field), field, "cannot change during a run; a change may give " + live);
      if (s.live) any = r.setting(s, next, field) || any;
    }
    r.finish();  // a misspelt setting is named as unknown, not as a change without settings
    if (!any) r.fail(r.find("finger"), "finger", "the change names no setting: give one or more of " + live);
    change.patch = next.patch;
    r.failOn(sim::validateChange(change, scene.fingers, previous_time));
    current[static_cast<std::size_t>(change.finger)] = change.patch;
    previous_time = change.time;
    scene.changes.push_back(change);
  }
}

// The element of array `a` that `part` (digits) names, or throws naming the field walked so far.
std::size_t arrayIndex(const toml::array& a, const std::string& part, const std::string& where,
                       const std::string& walked) {
  std::size_t i = 0;
  const auto [end, ec] = std::from_chars(part.data(), part.data() + part.size(), i);
  if (ec != std::errc() || end != part.data() + part.size()) {
    throw InputError(where, 0, 0, walked,
                     "is an array: expected an element index, got '" + part + "'");
  }
  if (i >= a.size()) {
    throw InputError(where, 0, 0, walked,
                     "no element " + part + " (the array has " + std::to_string(a.size()) + ")");
  }
  return i;
}

// "--set a.b.c=VALUE": VALUE is read as TOML, or as a string when it is not valid TOML. A part
// of the path may be an element index of an array (`loads.0.torque`).
// `--set fingers.NAME.FIELD=...` or `bodies.NAME.FIELD=...` for a NAME the scene lacks is a typo
// unless it starts a new finger with its device or a new body with its shape: then it says so,
// naming the fingers or bodies there are.
void requireKnownOrNew(const toml::table& group, const std::vector<std::string>& parts, const std::string& where) {
  struct Kind {
    const char* group;
    const char* what;
    const char* defining;
  };
  static constexpr Kind kKinds[] = {{"fingers", "finger", "device"}, {"bodies", "body", "shape"}};
  for (const Kind& k : kKinds) {
    if (parts[0] != k.group || (parts.size() > 2 && parts[2] == k.defining)) continue;
    std::string names;
    for (const auto& [name, node] : group) names.append(names.empty() ? "" : ", ").append(name.str());
    throw InputError(where, 0, 0, parts[0] + "." + parts[1],
                     std::string("no such ") + k.what + " (the scene has: " + (names.empty() ? "none" : names) +
                         "); a new " + k.what + " starts with its " + k.defining + ", e.g. --set " + parts[0] + "." +
                         parts[1] + "." + k.defining + (parts[0] == "fingers" ? ".csv=FILE" : "=\"box\""));
  }
}

void applyOverride(toml::table& root, const std::string& text) {
  const std::string where = "--set " + text;
  const std::size_t eq = text.find('=');
  if (eq == std::string::npos || eq == 0) throw InputError(where, 0, 0, text, "expected FIELD=VALUE");
  const std::string key = text.substr(0, eq), value = text.substr(eq + 1);
  std::vector<std::string> parts;
  for (std::size_t a = 0; a <= key.size();) {
    const std::size_t b = std::min(key.find('.', a), key.size());
    parts.push_back(key.substr(a, b - a));
    if (parts.back().empty()) throw InputError(where, 0, 0, key, "empty name in the field path");
    a = b + 1;
  }
  toml::node* at = &root;  // a table or an array
  std::string walked;
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
    walked += (walked.empty() ? "" : ".") + parts[i];
    toml::node* n = nullptr;
    if (toml::array* a = at->as_array()) {
      n = a->get(arrayIndex(*a, parts[i], where, walked));
    } else {
      n = at->as_table()->get(parts[i]);
      if (!n && i == 1) requireKnownOrNew(*at->as_table(), parts, where);
      if (!n) n = at->as_table()->insert(parts[i], toml::table{}).first->second.as_table();
    }
    if (!n->is_table() && !n->is_array()) throw InputError(where, 0, 0, walked, "is not a table");
    at = n;
  }
  toml::table parsed;
  try {
    parsed = toml::parse("v = " + value, where);
  } catch (const toml::parse_error&) {
    std::string quoted;
    for (char c : value) quoted += (c == '"' || c == '\\') ? std::string("\\") + c : std::string(1, c);
    try {
      parsed = toml::parse("v = \"" + quoted + "\"", where);
    } catch (const toml::parse_error& e) {
      throw InputError(where, 0, 0, key, std::string(e.description()));
    }
  }
  if (toml::array* a = at->as_array()) {
    const std::size_t i = arrayIndex(*a, parts.back(), where, key);
    a->replace(a->cbegin() + static_cast<std::ptrdiff_t>(i), std::move(*parsed.get("v")));
  } else {
    at->as_table()->insert_or_assign(parts.back(), std::move(*parsed.get("v")));
  }
}

// The scene-wide settings: `duration` and `haptic_rate` at the top, the rest in [world].
void readSceneSettings(Reader& r, sim::SceneDesc& scene) {
  const auto top = [](const sim::Setting<sim::SceneDesc>& s) { return s.name.find('.') == std::string_view::npos; };
  for (const sim::Setting<sim::SceneDesc>& s : sim::sceneSettings()) {
    if (top(s)) r.setting(s, scene, std::string(s.name), s.name == "duration");
  }
  if (const toml::node* w = r.find("world")) {
    if (!w->is_table()) r.fail(w, "world", "expected a table");
    Reader wr(*w->as_table(), "world", r.file());
    for (const sim::Setting<sim::SceneDesc>& s : sim::sceneSettings()) {
      if (!top(s)) wr.setting(s, scene, std::string(s.name.substr(s.name.find('.') + 1)));
    }
    wr.finish();
  }
  r.failOn(sim::validateScene(scene));
}

// The solver holds a pinched body down to 1/100 of a proxy's mass (hard case pinch-mass-1g, with
// the 100 iterations it needs to lift it; fewer leave it calm on the ground); at 1/1000 the body
// tumbles over whatever the iterations, so lighter bodies are rejected.
void checkMassRatios(Reader& r, const sim::SceneDesc& scene) {
  const sim::FingerDesc* heaviest = nullptr;
  for (const sim::FingerDesc& f : scene.fingers) {
    if (!heaviest || f.proxy.mass > heaviest->proxy.mass) heaviest = &f;
  }
  if (!heaviest) return;
  const double lightest = heaviest->proxy.mass * sim::kMinBodyToProxyMass;
  for (const auto& [name, t] : r.namedTables("bodies")) {
    const auto body = std::find_if(scene.bodies.begin(), scene.bodies.end(), [&name = name](const sim::BodyDesc& b) { return b.name == name; });
    if (body == scene.bodies.end() || body->mass <= 0.0 || body->mass >= lightest * (1 - 1e-9)) continue;
    Reader br(*t, r.field("bodies." + name), r.file());
    char why[240];
    std::snprintf(why, sizeof why,
                  "must be at least 1/100 of the heaviest proxy, %g kg here (fingers.%s.proxy_mass %g kg): the solver "
                  "cannot hold a lighter body in a pinch, got %g",
                  lightest, heaviest->name.c_str(), heaviest->proxy.mass, body->mass);
    const char* field = br.has("density") ? "density" : "mass";  // the field the user wrote
    br.fail(br.find(field), field, why);
  }
}

SessionDesc readSession(toml::table& root, const std::string& source, const std::string& base_dir,
                        std::span<const std::string> overrides) {
  for (const std::string& o : overrides) applyOverride(root, o);
  Reader r(root, "", source);
  SessionDesc s;
  s.source = source;
  s.scene.name = r.string("name", fs::path(source).stem().string());
  s.summary = r.string("summary", "");
  readSceneSettings(r, s.scene);
  readEffects(r, s.scene.effects, s.view);
  sim::MeshCache meshes;  // each mesh file is read once per scene
  // Names become file names, trace.csv columns and --set paths: keep them to what all three hold.
  const auto checkName = [&](const std::string& table, const std::string& name, const toml::table* t) {
    const bool ok = !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
      return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-';
    });
    if (!ok) r.fail(t, table + "." + name, "a name may hold only letters, digits, '_' and '-' (it names files, trace columns and --set fields)");
  };
  for (const auto& [name, t] : r.namedTables("bodies")) {
    checkName("bodies", name, t);
    s.scene.bodies.push_back(readBody(name, *t, r, base_dir, meshes));
  }
  if (s.scene.bodies.empty()) r.fail(nullptr, "bodies", "missing: a scene needs at least one body");
  for (const auto& [name, t] : r.namedTables("fingers")) {
    checkName("fingers", name, t);
    std::optional<UdpDeviceDesc> udp;
    s.scene.fingers.push_back(readFinger(name, *t, r, base_dir, s.scene.world.haptic_rate_hz, udp));
    if (udp) {
      udp->finger = static_cast<int>(s.scene.fingers.size()) - 1;
      s.udp_devices.push_back(*udp);
    }
  }
  checkMassRatios(r, s.scene);
  for (const auto& [name, t] : r.namedTables("cameras")) {
    checkName("cameras", name, t);
    s.cameras.push_back(readCamera(name, *t, r));
  }
  readLoads(r, s.scene);
  readChanges(r, s.scene);
  readRecord(r, s);
  readExpect(r, s);
  readView(r, s);
  r.finish();
  return s;
}

}  // namespace

std::string InputError::message(const std::string& file, int line, int column,
                                const std::string& field, const std::string& reason) {
  std::string m = file;
  if (line > 0) {
    m.append(":").append(std::to_string(line));
    if (column > 0) m.append(":").append(std::to_string(column));
  }
  m.append(": ");
  if (!field.empty()) m.append(field).append(": ");
  m.append(reason);
  return m;
}

InputError::InputError(const std::string& file, int line, int column, const std::string& field,
                       const std::string& reason)
    : std::runtime_error(message(file, line, column, field, reason)),
      file_(file),
      line_(line),
      column_(column),
      field_(field),
      reason_(reason) {}

SessionDesc parseSceneText(const std::string& text, const std::string& source_name,
                           const std::string& base_dir, std::span<const std::string> overrides) {
  toml::table root;
  try {
    root = toml::parse(text, source_name);
  } catch (const toml::parse_error& e) {
    throw InputError(source_name, static_cast<int>(e.source().begin.line),
                     static_cast<int>(e.source().begin.column), "", std::string(e.description()));
  }
  return readSession(root, source_name, base_dir, overrides);
}

SessionDesc loadSceneFile(const std::string& path, std::span<const std::string> overrides) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, 0, "", "cannot open the scene file");
  std::stringstream text;
  text << in.rdbuf();
  return parseSceneText(text.str(), path, fs::path(path).parent_path().string(), overrides);
}

sim::DeviceTrack readDeviceCsv(const std::string& path) {
  // A device, a pipe or /dev/zero would be read without end.
  std::error_code ec;
  if (fs::exists(path, ec) && !fs::is_regular_file(path, ec)) {
    throw InputError(path, 0, 0, "", "the device CSV is not a regular file");
  }
  std::ifstream in(path);
  if (!in) throw InputError(path, 0, 0, "", "cannot open the device CSV");
  sim::DeviceTrack d;
  d.interpolation = sim::Interpolation::kLinear;
  std::string line;
  int number = 0;
  std::vector<int> lines;  // file line of each keyframe
  constexpr const char* kColumns[] = {"t", "x", "y", "z"};
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (number == 1) {
      if (line != "t,x,y,z") throw InputError(path, 1, 0, "header", "expected the header row t,x,y,z");
      continue;
    }
    if (line.empty()) continue;
    double v[4];
    std::size_t pos = 0;
    for (int i = 0; i < 4; ++i) {
      const std::size_t end = std::min(line.find(',', pos), line.size());
      const std::string cell = line.substr(pos, end - pos);
      char* stop = nullptr;
      v[i] = std::strtod(cell.c_str(), &stop);
      if (cell.empty() || *stop != '\0' || !std::isfinite(v[i])) {
        throw InputError(path, number, 0, kColumns[i], "expected a finite number, got '" + cell + "'");
      }
      if ((i < 3) != (end < line.size())) throw InputError(path, number, 0, kColumns[i], "expected 4 columns");
      pos = end + 1;
    }
    d.keyframes.push_back({v[0], Vec3(v[1], v[2], v[3])});
    lines.push_back(number);
  }
  if (d.keyframes.empty()) throw InputError(path, number, 0, "", "no sample after the header");
  if (const std::optional<sim::FieldError> e = sim::validateTrack(d)) {
    throw InputError(path, lines[static_cast<std::size_t>(e->index)], 0, e->field == "keyframes.t" ? "t" : "x,y,z",
                     e->reason);
  }
  return d;
}

std::string dataDir() {
  if (const char* env = std::getenv("GODFINGER_DATA"); env && *env) return env;
  std::error_code ec;
  const fs::path exe = fs::canonical("/proc/self/exe", ec);
  if (!ec) {
    // Installed (<prefix>/bin and <prefix>/share/godfinger), then a build tree's copy (the
    // executable in <build>, or a test in a folder of it).
    for (const fs::path& candidate : {exe.parent_path() / GF_INSTALLED_DATA, exe.parent_path() / "share" / "godfinger",
                                      exe.parent_path().parent_path() / "share" / "godfinger"}) {
      if (fs::is_directory(candidate / "scenes", ec)) return candidate.lexically_normal().string();
    }
  }
  // An application embedding the installed library, anywhere: the prefix it was installed to.
  if (fs::is_directory(fs::path(GF_PREFIX_DATA) / "scenes", ec)) return GF_PREFIX_DATA;
  return GF_ASSET_DIR;
}

std::string bundledSceneDir() {
  if (const char* env = std::getenv("GODFINGER_SCENES"); env && *env) return env;
  return (fs::path(dataDir()) / "scenes").string();
}

std::string resolveScenePath(const std::string& scene) {
  if (fs::is_regular_file(scene)) return scene;
  const fs::path bundled = fs::path(bundledSceneDir()) / (scene + ".toml");
  if (scene.find('/') == std::string::npos && fs::is_regular_file(bundled)) return bundled.string();
  throw InputError(scene, 0, 0, "", "no such scene file, and no bundled scene of that name (see `godfinger list`)");
}

std::vector<std::string> bundledScenePaths() {
  std::vector<std::string> out;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(bundledSceneDir(), ec)) {
    if (e.path().extension() == ".toml") out.push_back(e.path().string());
  }
  std::sort(out.begin(), out.end());
  return out;
}

namespace {

using nlohmann::json;

json numberSchema(double lo, double hi, const std::string& description) {
  return {{"type", "number"}, {"minimum", lo}, {"maximum", hi}, {"description", description}};
}

json vec3Schema(const std::string& description, double limit = HUGE_VAL) {
  json item = {{"type", "number"}};
  if (std::isfinite(limit)) {
    item["minimum"] = -limit;
    item["maximum"] = limit;
  }
  return {{"type", "array"}, {"items", item}, {"minItems", 3}, {"maxItems", 3}, {"description", description}};
}

template <class Names>
json enumSchema(const Names& names, const std::string& description) {
  json values = json::array();
  for (const auto& n : names) values.push_back(std::string(n));
  return {{"enum", values}, {"description", description}};
}

// A setting's schema from its row of the validators' table: type, range, choices, unit.
template <class Desc>
json settingSchema(const sim::Setting<Desc>& s) {
  std::string description = std::string(s.name);
  if (!s.unit.empty()) description += " (" + std::string(s.unit) + ")";
  if (s.live) description += "; may change during a run";
  if (s.rule) description += "; further rules are checked when the scene loads";
  json out;
  switch (s.kind) {
    case sim::SettingKind::kChoice: return enumSchema(s.choices, description);
    case sim::SettingKind::kVector: {
      json v = vec3Schema(description);
      v["items"] = {{"type", "number"}, {"minimum", s.min}, {"maximum", s.max}};
      return v;
    }
    case sim::SettingKind::kInteger: out = {{"type", "integer"}}; break;
    case sim::SettingKind::kNumber: out = {{"type", "number"}}; break;
  }
  out[s.min_excluded ? "exclusiveMinimum" : "minimum"] = s.min;
  out["maximum"] = s.max;
  out["description"] = description;
  return out;
}

json object(json properties, const std::string& description, std::vector<std::string> required = {}) {
  json out = {{"type", "object"}, {"properties", std::move(properties)}, {"additionalProperties", false},
              {"description", description}};
  if (!required.empty()) out["required"] = required;
  return out;
}

json namedObjects(const json& each, const std::string& description) {
  return {{"type", "object"},
          {"propertyNames", {{"pattern", "^[A-Za-z0-9_-]+$"}}},
          {"additionalProperties", each},
          {"description", description}};
}

json deviceSchema() {
  json keyframe = object({{"t", numberSchema(0.0, 1e6, "s")}, {"p", vec3Schema("device position (m)", 1e3)}},
                         "a keyframe", {"t", "p"});
  json interpolation = enumSchema(kInterpolations, "between keyframes: smooth (zero velocity at each) or linear");
  json keyframes = object({{"keyframes", {{"type", "array"}, {"items", keyframe}, {"minItems", 1}}},
                           {"interpolation", interpolation}},
                          "scripted keyframes", {"keyframes"});
  json csv = object({{"csv", {{"type", "string"}, {"description", "recorded device: a CSV t,x,y,z (s, m)"}}}},
                    "a recorded device", {"csv"});
  json udp_fields = {
      {"udp",
       {{"type", {"string", "integer"}},
        {"description", "live device over UDP: \"HOST:PORT\" (IPv4) or a port on loopback (docs/device-protocol.md)"}}},
      {"channel", {{"type", "integer"}, {"minimum", 0}, {"maximum", 255}}},
      {"workspace_scale", numberSchema(0.01, 100.0, "scene m per device m")},
      {"workspace_offset", vec3Schema("scene position of the device's origin (m)", 1e3)},
      {"start", vec3Schema("scene position held until the first packet (m)", 1e3)},
      {"force_scale", numberSchema(0.0, 100.0, "device N per scene N")},
      {"stale_after", numberSchema(0.005, 1.0, "s without a packet before the device is stale")},
      {"force_ramp", numberSchema(0.005, 10.0, "s for the force to ramp from zero to full")},
      {"velocity_smoothing", numberSchema(0.0, 0.1, "s: low-pass time constant of the velocity")}};
  static_assert(std::size(kUdpFields) == 8, "every UDP field has its schema above");
  return {{"oneOf", {keyframes, csv, object(udp_fields, "a live UDP device", {"udp"})}}};
}

json bodySchema() {
  std::vector<std::string_view> shapes, collisions;
  for (const sim::ShapeInfo& s : sim::shapeInfos()) {
    if (std::find(shapes.begin(), shapes.end(), s.shape) == shapes.end()) shapes.push_back(s.shape);
    if (!s.collision.empty()) collisions.push_back(s.collision);
  }
  json p = {{"shape", enumSchema(shapes, "the body's shape")},
            {"collision", enumSchema(collisions, "how a mesh collides")},
            {"mesh", {{"type", "string"}, {"description", "mesh file, relative to the scene file"}}},
            {"up_axis", enumSchema(kUpAxes, "the mesh file's up axis, turned to +y")},
            {"static", {{"type", "boolean"}, {"description", "a static body (planes always are)"}}},
            {"density", numberSchema(kMinDensity, kMaxDensity, "kg/m^3, instead of mass")},
            {"orientation", {{"type", "array"}, {"items", {{"type", "number"}}}, {"minItems", 4}, {"maxItems", 4},
                             {"description", "quaternion [x, y, z, w]"}}},
            {"rotation", vec3Schema("rotation about x, then y, then z (deg)")}};
  for (const sim::Setting<sim::BodyDesc>& s : sim::bodySettings()) p[std::string(s.name)] = settingSchema(s);
  return object(p, "a rigid body", {"shape"});
}

json fingerSchema() {
  json p = {{"device", deviceSchema()}};
  for (const sim::Setting<sim::FingerDesc>& s : sim::fingerSettings()) p[std::string(s.name)] = settingSchema(s);
  return object(p, "a finger: a god-object proxy coupled to a device", {"device"});
}

json expectSchema() {
  const auto at_most = [](double hi, const std::string& d) { return numberSchema(0.0, hi, d); };
  json body = object({{"max_speed", at_most(1e6, "m/s")},
                      {"max_angular_speed", at_most(1e6, "rad/s")},
                      {"stays_above", numberSchema(-1e6, 1e6, "m: the centre's height never below")},
                      {"ends_above", numberSchema(-1e6, 1e6, "m: the centre's height at the end")},
                      {"max_rotation_deg", at_most(180.0, "deg from the pose at `after`")},
                      {"after", at_most(1e6, "s: checks start then")}},
                     "what a dynamic body must do");
  json finger = object({{"min_sgo", {{"type", "integer"}, {"minimum", 0}, {"maximum", sim::kMaxSgo * sim::kMaxRings}}},
                        {"window", {{"type", "array"}, {"items", {{"type", "number"}}}, {"minItems", 2}, {"maxItems", 2},
                                    {"description", "[from, to] s"}}},
                        {"max_force", at_most(1e9, "N")},
                        {"max_penetration", at_most(1e6, "m")}},
                       "what a finger must do");
  return object({{"finite", {{"type", "boolean"}}},
                 {"max_speed", at_most(1e6, "m/s")},
                 {"max_angular_speed", at_most(1e6, "rad/s")},
                 {"energy_growth", at_most(1e9, "J per quiet second")},
                 {"max_penetration", at_most(1e6, "m")},
                 {"no_tunnelling", {{"type", "boolean"}}},
                 {"bodies", namedObjects(body, "per dynamic body")},
                 {"fingers", namedObjects(finger, "per finger")}},
                "what the run must show (checked by run and check)");
}

}  // namespace

nlohmann::json sceneSchema() {
  json top, world;
  for (const sim::Setting<sim::SceneDesc>& s : sim::sceneSettings()) {
    const std::size_t dot = s.name.find('.');
    if (dot == std::string_view::npos) top[std::string(s.name)] = settingSchema(s);
    else world[std::string(s.name.substr(dot + 1))] = settingSchema(s);
  }
  json properties = top;
  properties["name"] = {{"type", "string"}};
  properties["summary"] = {{"type", "string"}, {"description", "one line for `godfinger list`"}};
  properties["world"] = object(world, "world-wide physics settings");
  properties["effects"] = {{"type", "array"}, {"items", enumSchema(effectNames(), "an effect the scene calls for")},
                           {"description", "the effects the scene calls for: every other one is off"}};
  properties["bodies"] = namedObjects(bodySchema(), "the rigid bodies, by name");
  properties["fingers"] = namedObjects(fingerSchema(), "the fingers, by name");
  properties["cameras"] = namedObjects(object({{"position", vec3Schema("m")}, {"target", vec3Schema("m")},
                                               {"fov", numberSchema(1.0, 170.0, "vertical field of view (deg)")}},
                                              "a camera"),
                                       "cameras, by name");
  json load = {{"body", {{"type", "string"}, {"description", "a dynamic body's name"}}}};
  for (const sim::Setting<sim::LoadDesc>& s : sim::loadSettings()) load[std::string(s.name)] = settingSchema(s);
  properties["loads"] = {{"type", "array"}, {"items", object(load, "a known external load", {"body"})}};
  json change = {{"finger", {{"type", "string"}}}, {"t", numberSchema(0.0, 1e6, "s")}};
  for (const sim::Setting<sim::FingerDesc>& s : sim::fingerSettings()) {
    if (s.live) change[std::string(s.name)] = settingSchema(s);
  }
  properties["changes"] = {{"type", "array"}, {"items", object(change, "a scripted change of live settings", {"finger", "t"})}};
  properties["record"] = object(
      {{"trace", {{"type", "boolean"}}},
       {"contacts", {{"type", "array"}, {"items", {{"type", "number"}, {"minimum", 0}}}, {"description", "snapshot times (s)"}}},
       {"forces", {{"type", "array"}, {"items", {{"type", "string"}}}, {"description", "dynamic bodies for forces.csv"}}},
       {"force_chart", {{"type", "boolean"}}},
       {"force_chart_title", {{"type", "string"}}}},
      "what a run writes besides summary.json");
  properties["expect"] = expectSchema();
  json action = object({{"t", numberSchema(0.0, 1e6, "s")}, {"widget", {{"type", "string"}}}, {"value", {{"type", "string"}}}},
                       "scripted overlay input", {"t"});
  properties["render"] = object({{"width", {{"type", "integer"}, {"minimum", 16}, {"maximum", 1920}}},
                                 {"height", {{"type", "integer"}, {"minimum", 16}, {"maximum", 1080}}},
                                 {"antialiasing", enumSchema(std::array<const char*, 3>{"fxaa", "msaa", "none"}, "")},
                                 {"msaa_samples", {{"type", "integer"}, {"minimum", 2}, {"maximum", 8}}},
                                 {"actions", {{"type", "array"}, {"items", action}}}},
                                "how frames are drawn");
  json schema = object(properties, "a godfinger scene file (TOML), field by field: assets/scenes/README.md",
                       {"duration", "effects", "bodies"});
  schema["$schema"] = "https://json-schema.org/draft/2020-12/schema";
  schema["title"] = "godfinger scene";
  return schema;
}

}  // namespace gf::app
