// `godfinger patch`: one god-finger contact area on a mesh, with its close-up picture.
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "app/commands/commands.hpp"
#include "app/runs/contacts.hpp"
#include "app/runs/files.hpp"
#include "app/scene/data_folder.hpp"
#include "app/scene/input_error.hpp"
#include "render/render_thread.hpp"
#include "sim/contact/contact_record.hpp"
#include "sim/patch/god_finger.hpp"
#include "sim/mesh/mesh_import.hpp"

namespace gf::app {
namespace {

const sim::Setting<sim::FingerDesc>& fingerSetting(std::string_view name) {
  return *sim::findSetting(sim::fingerSettings(), name);
}

CLI::Validator fingerCheck(std::string_view name) { return settingCheck(sim::fingerSettings(), name); }

struct PatchArgs {
  std::string mesh, out, point, normal, push;
  double scale = 1.0;
  double rounding = 0.0;  ///< collision margin rounding the mesh's edges (m)
  double max_distance = 0.001;  ///< farthest --point may be from the surface (m)
  sim::FingerDesc finger;  ///< its god-finger settings, tau_a aside
  double tau_a_deg = sim::givenValue(fingerSetting("tau_a"), sim::FingerDesc{});
};

sim::Vec3 parseVec3(const std::string& option, const std::string& text) {
  sim::Vec3 v;
  std::size_t pos = 0;
  for (int i = 0; i < 3; ++i) {
    const std::size_t end = i < 2 ? text.find(',', pos) : text.size();
    if (end == std::string::npos) throw commandLineError(option, "expected X,Y,Z, got '" + text + "'");
    const std::string cell = text.substr(pos, end - pos);
    char* stop = nullptr;
    v[i] = std::strtod(cell.c_str(), &stop);
    if (cell.empty() || *stop != '\0' || !std::isfinite(v[i])) {
      throw commandLineError(option, "expected three finite numbers X,Y,Z, got '" + text + "'");
    }
    pos = end + 1;
  }
  return v;
}

// The close-up of a computed patch: the mesh as a static body, the patch as one finger's contact.
void writePatchCloseUp(const PatchArgs& a, const std::shared_ptr<const sim::Mesh>& mesh,
                       const sim::ContactRecord& record, const std::string& prefix) {
  sim::SceneDesc scene;
  sim::BodyDesc body;
  body.shape = sim::ShapeKind::kConcaveMesh;
  body.mesh_path = a.mesh;
  body.mesh_scale = a.scale;
  body.mesh = mesh;  // drawn from the mesh already loaded
  body.mass = 0.0;
  scene.bodies.push_back(body);
  scene.fingers.push_back(a.finger);
  sim::Snapshot snap;
  snap.bodies.resize(1);  // the mesh frame is the world frame
  sim::toContactSnapshot(record, snap.bodies[0], snap.fingers.emplace_back().contacts.emplace_back());
  render::renderCloseUps(scene, snap, prefix, 480);
}

class PatchCommand final : public Command {
 public:
  CLI::App* add(CLI::App& app) override;
  int run() override;

 private:
  PatchArgs args_;
};

CLI::App* PatchCommand::add(CLI::App& app) {
  PatchArgs& a = args_;
  CLI::App* p = app.add_subcommand("patch", "Compute one god-finger contact area on a mesh; write patch.json "
                                              "and its close-up patch.png");
  p->add_option("--mesh", a.mesh, "Mesh file (OBJ, PLY, STL, OFF, glTF, ...)")->required();
  p->add_option("--scale", a.scale, "Factor from mesh units to metres")
      ->check(settingCheck(sim::bodySettings(), "scale"));
  p->add_option("--point", a.point, "Contact point X,Y,Z on the mesh (m)")->required();
  p->add_option("--normal", a.normal, "Outward surface normal X,Y,Z at the point (default: the normal of the face "
                                      "closest to the point; at an edge or vertex, of the face there the push presses "
                                      "into most)");
  p->add_option("--max-distance", a.max_distance, "Farthest the point may be from the mesh surface (m; default 0.001)")
      ->check(CLI::Range(0.0, 1.0));
  p->add_option("--push", a.push, "Coupling vector v = device - god-object X,Y,Z (m)")->required();
  p->add_option("--rounding", a.rounding, "Collision margin rounding the mesh's edges and corners (m): a point "
                                          "this close to an edge, with a normal between its faces', is an edge hit")
      ->check(CLI::Range(0.0, 0.01));
  p->add_option("--n-sgo", a.finger.patch.n_sgo, "Number of SGOs")->check(fingerCheck("n_sgo"));
  p->add_option("--r-max", a.finger.patch.r_max, "Largest contact radius r_max (m)")->check(fingerCheck("r_max"));
  p->add_option("--d0", a.finger.patch.d0, "Press depth scale D'_0 (m)")->check(fingerCheck("d0"));
  p->add_option("--alpha", a.finger.patch.alpha, "Stretch base alpha of Eq. 2")->check(fingerCheck("alpha"));
  p->add_option("--tau-a", a.tau_a_deg, "Angular threshold tau_a (degrees)")->check(fingerCheck("tau_a"));
  p->add_option("--friction", a.finger.patch.friction, "Friction coefficient theta")->check(fingerCheck("friction"));
  p->add_option("--out", a.out, "Output folder (created if missing)")->required();
  return p;
}


int PatchCommand::run() {
  PatchArgs& a = args_;
  sim::ContactRecord record;
  record.body = 0;
  const sim::Vec3 point = parseVec3("--point", a.point);
  record.contact = {point, a.normal.empty() ? sim::Vec3::Zero() : parseVec3("--normal", a.normal), 0.0, a.rounding};
  const sim::Vec3 push = parseVec3("--push", a.push);
  if (!a.normal.empty() && record.contact.outward_normal_local.norm() < 1e-9) {
    throw commandLineError("--normal", "must not be zero");
  }
  if (a.finger.patch.n_sgo < sim::kMinSgo) {
    throw commandLineError("--n-sgo", "a patch needs at least " + std::to_string(sim::kMinSgo) + " SGOs");
  }
  sim::setGiven(fingerSetting("tau_a"), a.finger, a.tau_a_deg);
  const sim::PatchSettings& settings = a.finger.patch;
  std::shared_ptr<const sim::Mesh> mesh;
  try {
    a.mesh = resolveDataPath(a.mesh);
    mesh = std::make_shared<const sim::Mesh>(sim::loadMesh(a.mesh, a.scale));
  } catch (const sim::MeshLoadError& e) {
    throw commandLineError("--mesh", e.what());
  }
  // The point must lie on the surface (within --max-distance); without --normal, the closest
  // face's normal is the contact normal.
  const sim::SurfacePoint closest = mesh->closestPoint(point, settings.feature_tolerance);
  if (closest.face < 0) throw commandLineError("--mesh", a.mesh + ": no faces");
  if (closest.query_distance > a.max_distance) {
    char text[256];
    std::snprintf(text, sizeof text,
                  "is %.6g m from the mesh surface (closest surface point %.6g,%.6g,%.6g; --max-distance %.6g m)",
                  closest.query_distance, closest.point.x(), closest.point.y(), closest.point.z(), a.max_distance);
    throw commandLineError("--point", text);
  }
  if (a.normal.empty()) record.contact.outward_normal_local = sim::pressedNormal(*mesh, closest, push);
  record.contact.outward_normal_local.normalize();
  sim::computePatch(*mesh, record.contact, push, settings, record.patch);
  record.press_depth = record.patch.press_depth;
  if (record.patch.valid) record.contact.point_local = record.patch.hit.point;  // c_p on the mesh
  const sim::Patch& patch = record.patch;
  nlohmann::json j = patchJson(patch, settings);
  j["mesh"] = a.mesh;
  j["scale"] = a.scale;
  j["normal_from"] = a.normal.empty() ? "closest face (at an edge or vertex: the one pressed most)" : "--normal";
  const std::string why = patchExplanation(patch, settings);
  j["explanation"] = why;
  std::error_code ec;
  std::filesystem::create_directories(a.out, ec);
  if (ec) throw std::runtime_error(a.out + ": cannot create folder: " + ec.message());
  const std::string path = (std::filesystem::path(a.out) / "patch.json").string();
  writeFileAtomically(path, j.dump(1) + "\n");
  const std::string picture = (std::filesystem::path(a.out) / "patch").string();
  writePatchCloseUp(a, mesh, record, picture);
  std::printf("radius %.6g m, %zu of %d SGOs%s%s; wrote %s and %s.png\n", patch.radius, patch.sgos.size(),
              settings.n_sgo, why.empty() ? "" : ": ", why.c_str(), path.c_str(), picture.c_str());
  return 0;
}

}  // namespace

std::unique_ptr<Command> makePatchCommand(const std::vector<std::string>&) { return std::make_unique<PatchCommand>(); }

}  // namespace gf::app
