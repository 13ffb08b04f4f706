#include "app/scene/schema.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "app/scene/sections.hpp"
#include "sim/scene/settings.hpp"

namespace gf::app {
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
  json q = {{"type", "array"}, {"items", {{"type", "number"}}}, {"minItems", 4}, {"maxItems", 4},
            {"description", "device orientation, a unit quaternion [w, x, y, z] (|q| within 0.001 of 1)"}};
  json keyframe = object({{"t", numberSchema(0.0, 1e6, "s")}, {"p", vec3Schema("device position (m)", 1e3)}, {"q", q}},
                         "a keyframe", {"t", "p"});
  json interpolation = enumSchema(kInterpolations, "between keyframes: smooth (zero velocity at each) or linear");
  json keyframes = object({{"keyframes", {{"type", "array"}, {"items", keyframe}, {"minItems", 1}}},
                           {"interpolation", interpolation}},
                          "scripted keyframes", {"keyframes"});
  json csv = object({{"csv", {{"type", "string"}, {"description", "recorded device: a CSV t,x,y,z or t,x,y,z,qw,qx,qy,qz (s, m)"}}}},
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
  json web = object({{"web", {{"const", true}, {"description", "the pointer of the browser view (`--serve`) drives it"}}},
                     {"start", vec3Schema("scene position held until the page moves it (m)", 1e3)}},
                    "the browser view's pointer", {"web"});
  json udp = object(udp_fields, "a live UDP device", {"udp"});
  // Every kind of device may be tilted: the fixed rotation after each orientation it gives.
  for (json* kind : {&keyframes, &csv, &udp, &web}) {
    (*kind)["properties"]["tilt_deg"] =
        numberSchema(-180.0, 180.0, "deg: a fixed rotation about tilt_axis after every orientation (default 0)");
    (*kind)["properties"]["tilt_axis"] = vec3Schema("the tilt's axis in the device frame, non-zero (default [1, 0, 0])", 1e3);
  }
  return {{"oneOf", {keyframes, csv, udp, web}}};
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
            {"rotation", vec3Schema("rotation about x, then y, then z (deg)")},
            {"tets", {{"type", "string"}, {"description", "soft_mesh: a TetGen .node (its .ele beside it) or legacy .vtk file, relative to the scene file"}}},
            {"pinned", {{"type", "array"},
                        {"items", object({{"min", vec3Schema("the box's lowest corner (m, body frame)")},
                                          {"max", vec3Schema("the box's highest corner (m, body frame)")}},
                                         "a box of a soft body's nodes held where they start", {"min", "max"})},
                        {"description", "soft bodies: boxes of nodes held fixed"}}}};
  for (const sim::Setting<sim::BodyDesc>& s : sim::bodySettings()) p[std::string(s.name)] = settingSchema(s);
  return object(p, "a rigid or soft body", {"shape"});
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
                      {"max_drift", at_most(1e6, "m: the centre's distance from where it was at `after`")},
                      {"max_tilt_deg", at_most(180.0, "deg: how far the vertical turned since `after`")},
                      {"after", at_most(1e6, "s: checks start then")},
                      {"rests_after", at_most(1e6, "s: no later step faster than rest_speed or tilting faster than rest_tilt_rate")},
                      {"rest_speed", at_most(1e6, "m/s (default 0.001)")},
                      {"rest_tilt_rate", at_most(1e6, "rad/s about a horizontal axis (default 0.05)")},
                      {"max_roll_ratio", at_most(1e6, "a sphere's turn x radius / distance on the ground, roll_window")},
                      {"roll_window", {{"type", "array"},
                                       {"items", {{"type", "number"}}},
                                       {"minItems", 2},
                                       {"maxItems", 2},
                                       {"description", "[from, to] s of max_roll_ratio (default the whole run)"}}}},
                     "what a dynamic body must do");
  json finger = object({{"min_sgo", {{"type", "integer"}, {"minimum", 0}, {"maximum", sim::kMaxSgo * sim::kMaxRings}}},
                        {"window", {{"type", "array"}, {"items", {{"type", "number"}}}, {"minItems", 2}, {"maxItems", 2},
                                    {"description", "[from, to] s"}}},
                        {"max_force", at_most(1e9, "N")},
                        {"max_force_change", at_most(1e9, "N: the coupling force's change from its value at the window's start")},
                        {"max_penetration", at_most(1e6, "m")}},
                       "what a finger must do");
  return object({{"finite", {{"type", "boolean"}}},
                 {"max_speed", at_most(1e6, "m/s")},
                 {"max_angular_speed", at_most(1e6, "rad/s")},
                 {"min_port_energy", numberSchema(-1e6, 0.0, "J: the lowest a finger's device port energy may go (default -0.001)")},
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
  json zone = object({{"min", vec3Schema("m: the lower corner")}, {"max", vec3Schema("m: the upper corner, above min on every axis")}},
                     "an axis-aligned box", {"min", "max"});
  properties["targets"] = namedObjects(
      object({{"body", {{"type", "string"}, {"description", "the body whose ghost is drawn (not a plane)"}}},
              {"position", vec3Schema("m: the ghost's position (default: where the body starts)")},
              {"orientation", {{"type", "array"}, {"items", {{"type", "number"}}}, {"minItems", 4}, {"maxItems", 4},
                               {"description", "the ghost's quaternion [x, y, z, w] (default: the body's)"}}},
              {"rotation", vec3Schema("the ghost's rotation about x, then y, then z (deg)")},
              {"zone", zone}},
             "where a task wants a body, drawn in the frames: a ghost, a zone or both"),
      "targets, by name");
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
       {"trace_rate", numberSchema(kMinTraceRateHz, 1e5, "trace.csv rows a second (Hz); haptic_rate_hz / trace_rate "
                                                         "must be whole; default: every haptic step")},
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
                                 {"body_pattern", enumSchema(view::kBodyPatternNames, "rigid bodies striped in their own frames, or plain")},
                                 {"proxy", enumSchema(view::kProxyLookNames, "proxies drawn as spheres or as fingertips")},
                                 {"load_arrows", {{"type", "boolean"}, {"description", "each point's normal load and friction drawn as arrows"}}},
                                 {"reserve_top_left", {{"type", "boolean"}, {"description", "the insets and time stamp keep out of the top-left corner"}}},
                                 {"actions", {{"type", "array"}, {"items", action}}}},
                                "how frames are drawn");
  json schema = object(properties, "a godfinger scene file (TOML), field by field: assets/scenes/README.md",
                       {"duration", "effects", "bodies"});
  schema["$schema"] = "https://json-schema.org/draft/2020-12/schema";
  schema["title"] = "godfinger scene";
  return schema;
}

}  // namespace gf::app
