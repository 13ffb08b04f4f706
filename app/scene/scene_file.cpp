#include "app/scene/scene_file.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "app/scene/sections.hpp"
#include "sim/scene/settings.hpp"

namespace gf::app {

namespace fs = std::filesystem;

namespace {

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
    std::optional<WebDeviceDesc> web;
    s.scene.fingers.push_back(readFinger(name, *t, r, base_dir, s.scene.world.haptic_rate_hz, udp, web));
    const int finger = static_cast<int>(s.scene.fingers.size()) - 1;
    if (udp) {
      udp->finger = finger;
      s.udp_devices.push_back(*udp);
    }
    if (web) {
      web->finger = finger;
      s.web_devices.push_back(*web);
    }
  }
  checkMassRatios(r, s.scene);
  if (std::optional<sim::FieldError> e = sim::validateOverlapStability(s.scene)) {
    // Named at the [world] table's overlap_stiffness (or the --set that gave it).
    const toml::node* w = r.nodeOf("world");
    if (w && w->is_table()) Reader(*w->as_table(), "world", r.file()).failOn(sim::FieldError{"overlap_stiffness", e->reason});
    r.failOn(e);
  }
  for (const auto& [name, t] : r.namedTables("cameras")) {
    checkName("cameras", name, t);
    s.cameras.push_back(readCamera(name, *t, r));
  }
  for (const auto& [name, t] : r.namedTables("targets")) checkName("targets", name, t);
  readTargets(r, s);
  readLoads(r, s.scene);
  readChanges(r, s.scene);
  readRecord(r, s);
  readExpect(r, s);
  readView(r, s);
  r.finish();
  return s;
}

}  // namespace

std::string resolvePath(const std::string& base_dir, const std::string& p) {
  const fs::path path(p);
  return path.is_absolute() || base_dir.empty() ? p : (fs::path(base_dir) / path).lexically_normal().string();
}

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

}  // namespace gf::app
