#include "app/runs/contacts.hpp"

#include <cmath>

#include "sim/scene/settings.hpp"

namespace gf::app {
namespace {

nlohmann::json vec(const sim::Vec3& v) { return {v.x(), v.y(), v.z()}; }

// Names of sim::Feature and sim::WalkStop values, in enum order.
constexpr const char* kFeatureNames[] = {"face", "edge", "vertex"};
constexpr const char* kStopNames[] = {"distance",       "angular_threshold", "friction_cone", "boundary",
                                      "crossing_limit", "degenerate",        "facing_away",   "dropped"};

static_assert(std::size(kFeatureNames) == static_cast<std::size_t>(sim::Feature::kVertex) + 1,
              "a name for every sim::Feature");
static_assert(std::size(kStopNames) == static_cast<std::size_t>(sim::WalkStop::kDropped) + 1,
              "a name for every sim::WalkStop");

const char* featureName(sim::Feature f) { return kFeatureNames[static_cast<std::size_t>(f)]; }
const char* stopName(sim::WalkStop s) { return kStopNames[static_cast<std::size_t>(s)]; }

// What each walk stop means, for patchExplanation.
constexpr const char* kStopMeanings[] = {"walked their full d_i",
                                         "stopped at a sharp edge (the next face beyond tau_a)",
                                         "stopped where the next face leaves the friction cone",
                                         "stopped at a boundary edge of the open mesh",
                                         "ran out of edge crossings",
                                         "stopped on degenerate geometry",
                                         "stopped where the next face turns away from the press",
                                         "were dropped (they point off the hit's edge or vertex, paper Fig. 3b)"};
static_assert(std::size(kStopMeanings) == std::size(kStopNames), "a meaning for every sim::WalkStop");

nlohmann::json paths(const std::vector<sim::Vec3>& points, const std::vector<std::int32_t>& offsets) {
  nlohmann::json out = nlohmann::json::array();
  for (std::size_t k = 0; k + 1 < offsets.size(); ++k) {
    nlohmann::json line = nlohmann::json::array();
    for (std::int32_t i = offsets[k]; i < offsets[k + 1]; ++i) line.push_back(vec(points[i]));
    out.push_back(std::move(line));
  }
  return out;
}

// The settings of `table` in `desc`, keyed by jsonKey(), in the unit users give them.
template <class Desc>
nlohmann::json settingsJson(std::span<const sim::Setting<Desc>> table, const Desc& desc, bool live_only) {
  nlohmann::json out = nlohmann::json::object();
  for (const sim::Setting<Desc>& s : table) {
    if (live_only && !s.live) continue;
    if (s.kind == sim::SettingKind::kVector) {
      out[sim::jsonKey(s)] = vec(s.get_vector(desc) / s.si_per_unit);
    } else if (s.kind == sim::SettingKind::kChoice) {
      out[sim::jsonKey(s)] = std::string(sim::choiceName(s, desc));
    } else if (s.kind == sim::SettingKind::kInteger) {
      out[sim::jsonKey(s)] = std::lround(sim::givenValue(s, desc));
    } else {
      out[sim::jsonKey(s)] = sim::givenValue(s, desc);
    }
  }
  return out;
}

}  // namespace

nlohmann::json fingerSettingsJson(const sim::FingerDesc& finger, bool live_only) {
  return settingsJson(sim::fingerSettings(), finger, live_only);
}

nlohmann::json sceneSettingsJson(const sim::SceneDesc& scene) { return settingsJson(sim::sceneSettings(), scene, false); }

nlohmann::json patchJson(const sim::Patch& p, const sim::PatchSettings& s) {
  nlohmann::json radial = nlohmann::json::array();
  for (std::size_t i = 0; i < p.radial.size(); ++i) {
    radial.push_back({{"direction", vec(p.radial[i])}, {"d_i_m", p.d_i[i]}, {"stop", stopName(p.radial_stop[i])}});
  }
  nlohmann::json sgos = nlohmann::json::array();
  for (const sim::Sgo& g : p.sgos) {
    sgos.push_back({{"position", vec(g.position)}, {"face", g.face}, {"radial", g.radial},
                    {"walked_m", g.walked}, {"stop", stopName(g.stop)}, {"load_share", g.load_share}});
  }
  sim::FingerDesc finger;
  finger.patch = s;
  return {{"frame", "mesh"},
          {"valid", p.valid},
          {"settings", fingerSettingsJson(finger, true)},
          {"hit", {{"point", vec(p.hit.point)}, {"face", p.hit.face},
                   {"feature", featureName(p.hit.feature)}, {"feature_index", p.hit.feature_index}}},
          {"press_dir", vec(p.press_dir)},
          {"ring_tangent", vec(p.ring_tangent)},
          {"press_depth_m", p.press_depth},
          {"radius_m", p.radius},
          {"radial", radial},
          {"sgos", sgos},
          {"paths", paths(p.path_points, p.path_offsets)}};
}

void addLoadsJson(const sim::ContactSnapshot& c, nlohmann::json& out) {
  const auto load = [](const sim::PointLoad& l) {
    return nlohmann::json{{"normal_n", l.normal}, {"tangential_n", vec(l.tangential)}, {"slipping", l.slipping}};
  };
  const sim::Vec3& n = c.outward_normal_world;
  nlohmann::json sgos = nlohmann::json::array();
  for (const sim::PointLoad& l : c.loads) sgos.push_back(load(l));
  out["force_n"] = vec(c.force);
  out["normal_force_n"] = -c.force.dot(n);
  out["tangential_force_n"] = (c.force - c.force.dot(n) * n).norm();
  out["rolling_moment_nm"] = vec(c.rolling_moment);
  out["torsion_moment_nm"] = vec(c.torsion_moment);
  out["sliding"] = c.sliding;
  out["point_load"] = load(c.point_load);
  out["sgo_loads"] = std::move(sgos);
}

nlohmann::json contactsJson(const sim::Snapshot& snap, const sim::SceneDesc& scene) {
  nlohmann::json fingers = nlohmann::json::array();
  for (std::size_t f = 0; f < snap.fingers.size(); ++f) {
    const sim::FingerSnapshot& fs = snap.fingers[f];
    nlohmann::json contacts = nlohmann::json::array();
    for (const sim::ContactSnapshot& c : fs.contacts) {
      nlohmann::json sgos = nlohmann::json::array();
      for (const sim::Vec3& g : c.sgos_world) sgos.push_back(vec(g));
      nlohmann::json& contact = contacts.emplace_back(nlohmann::json{{"body", c.body >= 0 ? scene.bodies[c.body].name : std::string()},
                          {"point", vec(c.point_world)},
                          {"outward_normal", vec(c.outward_normal_world)},
                          {"separation_m", c.separation},
                          {"press_depth_m", c.press_depth},
                          {"radius_m", c.radius},
                          {"feature", featureName(c.feature)},
                          {"sgos", sgos},
                          {"paths", paths(c.path_points_world, c.path_offsets)}});
      addLoadsJson(c, contact);
      // On a soft body: how far its surface sank under the contact (the SGOs above are the
      // pressed surface nodes, where they are).
      if (c.body >= 0 && sim::isSoftShape(scene.bodies[static_cast<std::size_t>(c.body)].shape)) contact["indentation_m"] = c.indentation;
    }
    fingers.push_back({{"name", scene.fingers[f].name},
                       {"device", vec(fs.device)},
                       {"proxy", vec(fs.proxy)},
                       {"coupling_force_n", vec(fs.coupling_force)},
                       {"feedback_force_n", vec(fs.feedback_force)},
                       {"sgo_count", fs.sgo_count},
                       {"contacts", contacts}});
  }
  return {{"scene", scene.name}, {"frame", "world"}, {"time_s", snap.time}, {"step", snap.step}, {"fingers", fingers}};
}

std::string patchExplanation(const sim::Patch& patch, const sim::PatchSettings& settings) {
  if (!patch.valid) return "no patch: the contact or the settings cannot be computed from";
  if (!(patch.radius > 0.0)) {
    return "no SGOs: the push does not press into the surface (press depth " + std::to_string(patch.press_depth) +
           " m <= 0), so Eq. 1 gives radius 0";
  }
  std::size_t counts[std::size(kStopNames)] = {};
  for (sim::WalkStop stop : patch.radial_stop) ++counts[static_cast<std::size_t>(stop)];
  std::string text;
  for (std::size_t k = 1; k < std::size(kStopNames); ++k) {
    if (counts[k] == 0) continue;
    text.append(text.empty() ? "" : "; ").append(std::to_string(counts[k])).append(" of ");
    text.append(std::to_string(settings.n_sgo)).append(" radial vectors ").append(kStopMeanings[k]);
  }
  if (text.empty()) return text;
  const char* feature = featureName(patch.hit.feature);
  return std::string("the hit is on ") + (feature[0] == 'e' ? "an " : "a ") + feature + ": " + text;
}

}  // namespace gf::app
