// [fingers.NAME]: a finger's settings and its device (keyframes, a recorded CSV or a live UDP device).
#include "app/scene/sections.hpp"

#include <arpa/inet.h>

#include <charconv>
#include <cmath>
#include <numbers>
#include <optional>

#include "app/scene/scene_file.hpp"
#include "sim/scene/settings.hpp"

namespace gf::app {
namespace {

// tilt_deg lies in [-kMaxTiltDeg, kMaxTiltDeg]; tilt_axis is at least kMinTiltAxis long.
constexpr double kMaxTiltDeg = 180.0, kMinTiltAxis = 1e-9;

// A keyframe's `q = [w, x, y, z]`: the device's orientation, a unit quaternion within
// kOrientationTolerance (then normalised), else refused naming the field.
sim::Quat readOrientation(Reader& kr, const toml::node& n) {
  const toml::array* a = n.as_array();
  if (!a || a->size() != 4) kr.fail(&n, "q", "expected a unit quaternion [w, x, y, z] (4 numbers)");
  double c[4];
  for (std::size_t i = 0; i < 4; ++i) {
    const toml::node& e = *a->get(i);
    if (!e.is_number()) kr.fail(&e, "q", std::string("expected a number, got ") + typeName(e));
    c[i] = e.value<double>().value_or(0.0);
    if (!std::isfinite(c[i])) kr.fail(&e, "q", "must be finite");
  }
  const sim::Quat q(c[0], c[1], c[2], c[3]);
  if (!(std::abs(q.norm() - 1.0) <= kOrientationTolerance)) {
    kr.fail(&n, "q", "must be a unit quaternion [w, x, y, z] (|q| within " + sim::numberText(kOrientationTolerance) +
                         " of 1), got |q| = " + sim::numberText(q.norm()));
  }
  return q.normalized();
}

// The keyframes of a device table: each {t, p, q}, then the track's own rules (times increasing).
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
    if (const toml::node* q = kr.find("q")) kf.orientation = readOrientation(kr, *q);
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

// `web = true` with an optional `start`: the browser view's pointer drives the finger.
WebDeviceDesc readWebDevice(Reader& r, sim::Vec3& start) {
  const toml::node* n = r.find("web");
  if (!n->is_boolean() || !n->as_boolean()->get()) {
    r.fail(n, "web", "expected true: the finger follows the pointer of `--serve`'s page");
  }
  for (const char* key : kUdpFields) {
    if (std::string_view(key) != "start" && r.has(key)) r.fail(r.nodeOf(key), key, "belongs to a UDP device (udp = ...)");
  }
  start = r.vec3("start", sim::Vec3::Zero());
  if (start.cwiseAbs().maxCoeff() > sim::kMaxSceneCoordinate) {
    r.fail(r.nodeOf("start"), "start", "each coordinate must be in [-1000, 1000] m");
  }
  WebDeviceDesc w;
  w.file = sourceOf(*n, r.file());
  w.line = static_cast<int>(n->source().begin.line);
  w.column = static_cast<int>(n->source().begin.column);
  return w;
}

// `tilt_deg` and `tilt_axis` (device frame): the fixed rotation that follows every orientation
// the device gives (q_k * R(tilt_axis, tilt_deg)), so a study sweeps the pad angle as one number.
sim::Quat readTilt(Reader& r) {
  const double degrees = r.number("tilt_deg", 0.0, -kMaxTiltDeg, kMaxTiltDeg);
  const Vec3 axis = r.vec3("tilt_axis", Vec3::UnitX());
  if (!(axis.norm() >= kMinTiltAxis) || axis.cwiseAbs().maxCoeff() > sim::kMaxSceneCoordinate) {
    r.fail(r.nodeOf("tilt_axis"), "tilt_axis", "expected a non-zero axis [x, y, z] in the device frame");
  }
  return sim::Quat(Eigen::AngleAxisd(degrees * std::numbers::pi / 180.0, axis.normalized()));
}

// Every keyframe's orientation followed by `tilt`.
void applyTilt(sim::DeviceTrack& d, const sim::Quat& tilt) {
  for (sim::DeviceTrack::Keyframe& k : d.keyframes) k.orientation = (k.orientation * tilt).normalized();
}

// Where the device's positions come from: keyframes, a recorded CSV, a live UDP device (then
// `udp` is set) or the browser's pointer (then `web` is set); a live device's track holds it at
// its start, where the proxy starts.
sim::DeviceTrack readDeviceSource(Reader& r, const std::string& base_dir, std::optional<UdpDeviceDesc>& udp,
                                  std::optional<WebDeviceDesc>& web) {
  sim::DeviceTrack d;
  if (static_cast<int>(r.has("csv")) + static_cast<int>(r.has("keyframes")) + static_cast<int>(r.has("udp")) +
          static_cast<int>(r.has("web")) != 1) {
    r.fail(nullptr, "keyframes", "give exactly one of keyframes, csv, udp and web");
  }
  if (r.has("web")) {
    if (r.has("interpolation")) r.fail(r.find("interpolation"), "interpolation", "a live device is not interpolated");
    sim::Vec3 start;
    web = readWebDevice(r, start);
    d.keyframes.push_back({0.0, start});
    return d;
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
  return d;
}

// A finger's device: its source, then the tilt that follows every orientation it gives.
sim::DeviceTrack readDevice(Reader& parent, const std::string& base_dir, std::optional<UdpDeviceDesc>& udp,
                            std::optional<WebDeviceDesc>& web) {
  const toml::node* n = parent.find("device");
  if (!n) parent.fail(nullptr, "device", "missing: the finger needs a device (keyframes, csv, udp or web)");
  if (!n->is_table()) parent.fail(n, "device", "expected a table");
  Reader r(*n->as_table(), parent.field("device"), parent.file());
  const sim::Quat tilt = readTilt(r);
  sim::DeviceTrack d = readDeviceSource(r, base_dir, udp, web);
  applyTilt(d, tilt);
  if (udp) udp->tilt = tilt;
  r.finish();
  return d;
}

}  // namespace

sim::FingerDesc readFinger(const std::string& name, const toml::table& t, const Reader& parent,
                           const std::string& base_dir, double haptic_rate_hz, std::optional<UdpDeviceDesc>& udp,
                           std::optional<WebDeviceDesc>& web) {
  Reader r(t, parent.field("fingers." + name), parent.file());
  sim::FingerDesc f;
  f.name = name;
  for (const sim::Setting<sim::FingerDesc>& s : sim::fingerSettings()) r.setting(s, f, std::string(s.name));
  f.device = readDevice(r, base_dir, udp, web);
  // A live device's force ramp sets how fast its force may change unless the finger says.
  if (udp && !r.has("max_force_rate")) f.coupling.max_force_rate = f.coupling.max_force / udp->force_ramp;
  r.failOn(sim::validateFinger(f));
  r.failOn(sim::validateCouplingStability(f, haptic_rate_hz));
  r.finish();
  return f;
}

}  // namespace gf::app
