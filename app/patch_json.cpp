#include "app/patch_json.hpp"

#include <numbers>

namespace gf::app {
namespace {

nlohmann::json vec(const sim::Vec3& v) { return {v.x(), v.y(), v.z()}; }

const char* featureName(sim::Feature f) {
  switch (f) {
    case sim::Feature::kFace: return "face";
    case sim::Feature::kEdge: return "edge";
    case sim::Feature::kVertex: return "vertex";
  }
  return "face";
}

const char* stopName(sim::WalkStop s) {
  switch (s) {
    case sim::WalkStop::kDistance: return "distance";
    case sim::WalkStop::kAngularThreshold: return "angular_threshold";
    case sim::WalkStop::kFrictionCone: return "friction_cone";
    case sim::WalkStop::kBoundary: return "boundary";
    case sim::WalkStop::kCrossingLimit: return "crossing_limit";
    case sim::WalkStop::kDegenerate: return "degenerate";
    case sim::WalkStop::kDropped: return "dropped";
  }
  return "distance";
}

nlohmann::json paths(const std::vector<sim::Vec3>& points, const std::vector<std::int32_t>& offsets) {
  nlohmann::json out = nlohmann::json::array();
  for (std::size_t k = 0; k + 1 < offsets.size(); ++k) {
    nlohmann::json line = nlohmann::json::array();
    for (std::int32_t i = offsets[k]; i < offsets[k + 1]; ++i) line.push_back(vec(points[i]));
    out.push_back(std::move(line));
  }
  return out;
}

}  // namespace

nlohmann::json patchJson(const sim::Patch& p, const sim::PatchSettings& s) {
  nlohmann::json radial = nlohmann::json::array();
  for (std::size_t i = 0; i < p.radial.size(); ++i) {
    radial.push_back({{"direction", vec(p.radial[i])}, {"distance_m", p.distance[i]},
                      {"stop", stopName(p.radial_stop[i])}});
  }
  nlohmann::json sgos = nlohmann::json::array();
  for (const sim::Sgo& g : p.sgos) {
    sgos.push_back({{"position", vec(g.position)}, {"face", g.face}, {"radial", g.radial},
                    {"walked_m", g.walked}, {"stop", stopName(g.stop)}});
  }
  return {{"valid", p.valid},
          {"settings", {{"n_sgo", s.n_sgo}, {"r_max_m", s.r_max}, {"d0_m", s.d0}, {"alpha", s.alpha},
                        {"stretch_length_m", s.stretch_length},
                        {"tau_a_deg", s.tau_a * 180.0 / std::numbers::pi}, {"friction", s.friction}}},
          {"hit", {{"point", vec(p.hit.point)}, {"face", p.hit.face},
                   {"feature", featureName(p.hit.feature)}, {"feature_index", p.hit.feature_index}}},
          {"press_dir", vec(p.press_dir)},
          {"press_depth_m", p.press_depth},
          {"radius_m", p.radius},
          {"radial", radial},
          {"sgos", sgos},
          {"paths", paths(p.path_points, p.path_offsets)}};
}

nlohmann::json contactsJson(const sim::Snapshot& snap, const sim::SceneDesc& scene) {
  nlohmann::json fingers = nlohmann::json::array();
  for (std::size_t f = 0; f < snap.fingers.size(); ++f) {
    const sim::FingerSnapshot& fs = snap.fingers[f];
    nlohmann::json contacts = nlohmann::json::array();
    for (const sim::ContactSnapshot& c : fs.contacts) {
      nlohmann::json sgos = nlohmann::json::array();
      for (const sim::Vec3& g : c.sgos) sgos.push_back(vec(g));
      contacts.push_back({{"body", c.body >= 0 ? scene.bodies[c.body].name : std::string()},
                          {"point", vec(c.point)},
                          {"outward_normal", vec(c.outward_normal)},
                          {"distance_m", c.distance},
                          {"radius_m", c.radius},
                          {"feature", featureName(c.feature)},
                          {"sgos", sgos},
                          {"paths", paths(c.path_points, c.path_offsets)}});
    }
    fingers.push_back({{"name", scene.fingers[f].name},
                       {"device", vec(fs.device)},
                       {"proxy", vec(fs.proxy)},
                       {"coupling_force_n", vec(fs.coupling_force)},
                       {"feedback_force_n", vec(fs.feedback_force)},
                       {"sgo_count", fs.sgo_count},
                       {"contacts", contacts}});
  }
  return {{"scene", scene.name}, {"time_s", snap.time}, {"step", snap.step}, {"fingers", fingers}};
}

}  // namespace gf::app
