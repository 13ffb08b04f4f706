// The sections of a scene file about looking and recording: effects, [render], cameras, [record].
#include "app/scene/sections.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <tuple>

#include "sim/scene/settings.hpp"
#include "render/view/view_desc.hpp"

namespace gf::app {
namespace {

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

// widget = "FINGER/FIELD" names a finger of the scene and a widget of its panel; the value is
// one the widget's setting accepts (in the unit the widget shows).
void checkWidget(Reader& r, const sim::SceneDesc& scene, const view::WidgetAction& a) {
  const std::size_t slash = a.widget.find('/');
  const std::string finger = a.widget.substr(0, slash);
  const std::string field = slash == std::string::npos ? "" : a.widget.substr(slash + 1);
  const bool known_finger = std::any_of(scene.fingers.begin(), scene.fingers.end(),
                                        [&](const sim::FingerDesc& f) { return f.name == finger; });
  const view::OverlayWidget* widget = view::findOverlayWidget(field);
  if (!known_finger || !widget) {
    std::vector<std::string_view> names;
    for (const view::OverlayWidget& w : view::kOverlayWidgets) names.push_back(w.field);
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

}  // namespace

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

// [render]: frame size, anti-aliasing, how bodies and proxies look, point-load arrows and
// scripted overlay input.
void readView(Reader& parent, SessionDesc& s) {
  ViewSettings& v = s.view;
  if (const toml::node* n = parent.find("render")) {
    if (!n->is_table()) parent.fail(n, "render", "expected a table");
    Reader r(*n->as_table(), "render", parent.file());
    v.width = r.integer("width", v.width, 16, 1920);
    v.height = r.integer("height", v.height, 16, 1080);
    const std::string aa = r.string("antialiasing", view::antialiasingName(v.antialiasing));
    if (const std::optional<view::Antialiasing> parsed = view::parseAntialiasing(aa)) {
      v.antialiasing = *parsed;
    } else {
      r.fail(r.find("antialiasing"), "antialiasing", "expected \"fxaa\", \"msaa\" or \"none\"");
    }
    v.msaa_samples = r.integer("msaa_samples", v.msaa_samples, 2, 8);
    v.load_arrows = r.boolean("load_arrows", v.load_arrows);
    v.reserve_top_left = r.boolean("reserve_top_left", v.reserve_top_left);
    const int pattern = r.choice("body_pattern", view::kBodyPatternNames, static_cast<int>(v.body_pattern));
    v.body_pattern = static_cast<view::BodyPattern>(pattern);
    v.proxy = static_cast<view::ProxyLook>(r.choice("proxy", view::kProxyLookNames, static_cast<int>(v.proxy)));
    if (const toml::node* k = r.find("actions")) {
      const toml::array* a = k->as_array();
      if (!a) r.fail(k, "actions", "expected an array of {t = s, widget = \"FINGER/FIELD\", value = \"...\"}");
      for (const toml::node& e : *a) {
        if (!e.is_table()) r.fail(&e, "actions", "expected {t = s, widget = \"FINGER/FIELD\", value = \"...\"}");
        Reader ar(*e.as_table(), r.field("actions"), r.file());
        view::WidgetAction act;
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

// [targets.NAME]: `body` (its ghost, at `position` and `orientation`/`rotation`, by default where
// the body starts) and/or `zone = { min, max }`.
void readTargets(Reader& parent, SessionDesc& s) {
  for (const auto& [name, t] : parent.namedTables("targets")) {
    Reader r(*t, parent.field("targets." + name), parent.file());
    view::Target target;
    target.name = name;
    if (const toml::node* n = r.find("body")) {
      const std::string body = r.string("body", "");
      const auto& bodies = s.scene.bodies;
      const auto it = std::find_if(bodies.begin(), bodies.end(), [&](const sim::BodyDesc& b) { return b.name == body; });
      if (it == bodies.end()) r.fail(n, "body", "no body '" + body + "' in the scene");
      if (it->shape == sim::ShapeKind::kPlane) r.fail(n, "body", "'" + body + "' is a plane: it has no ghost to draw");
      target.body = static_cast<int>(it - bodies.begin());
      target.position = r.vec3("position", it->position);
      target.orientation = r.orientation(it->orientation);
    } else {
      for (const char* key : {"position", "orientation", "rotation"}) {
        if (r.has(key)) r.fail(r.find(key), key, "places a body's ghost: give the body");
      }
    }
    if (const std::optional<std::pair<Vec3, Vec3>> zone = r.box("zone")) {
      target.has_zone = true;
      std::tie(target.zone_min, target.zone_max) = *zone;
    }
    if (target.body < 0 && !target.has_zone) r.fail(nullptr, "body", "missing: a target is a body's ghost, a zone or both");
    r.finish();
    s.targets.push_back(std::move(target));
  }
}

view::Camera readCamera(const std::string& name, const toml::table& t, const Reader& parent) {
  Reader r(t, parent.field("cameras." + name), parent.file());
  view::Camera c;
  c.name = name;
  c.position = r.vec3("position", c.position);
  c.target = r.vec3("target", c.target);
  c.fov_deg = r.number("fov", c.fov_deg, 1.0, 170.0);
  if ((c.position - c.target).norm() < 1e-6) r.fail(r.find("target"), "target", "equals the camera position");
  r.finish();
  return c;
}

namespace {

// record.trace_rate: rows at a whole fraction of the haptic rate, so each row is a step's state at
// its exact time (a 1 kHz run at 100 Hz: t = 0.01, 0.02, ...).
void readTraceRate(Reader& r, SessionDesc& s) {
  const double haptic = s.scene.world.haptic_rate_hz;
  s.record.trace_rate = r.number("trace_rate", 0.0, kMinTraceRateHz, haptic);
  if (s.record.trace_rate == 0.0) return;
  const double every = haptic / s.record.trace_rate;
  if (std::abs(every - std::round(every)) > 1e-9 * every) {
    char text[200];
    std::snprintf(text, sizeof text, "%g Hz does not divide the haptic_rate (%g Hz): a row every %g steps; give a "
                  "rate whose steps are whole, e.g. %g Hz", s.record.trace_rate, haptic, every, haptic / std::round(every));
    r.fail(r.find("trace_rate"), "trace_rate", text);
  }
}

}  // namespace

void readRecord(Reader& parent, SessionDesc& s) {
  const toml::node* n = parent.find("record");
  if (!n) return;
  if (!n->is_table()) parent.fail(n, "record", "expected a table");
  Reader r(*n->as_table(), "record", parent.file());
  s.record.trace = r.boolean("trace", true);
  readTraceRate(r, s);
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

}  // namespace gf::app
