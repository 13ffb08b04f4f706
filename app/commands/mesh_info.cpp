#include "app/commands/mesh_info.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstdio>

#include "app/commands/commands.hpp"
#include "app/scene/data_folder.hpp"
#include "app/scene/input_error.hpp"
#include "sim/mesh/mesh.hpp"
#include "sim/mesh/mesh_import.hpp"

namespace gf::app {
namespace {

nlohmann::json vec(const sim::Vec3& v) { return {v.x(), v.y(), v.z()}; }

// A scale to suggest when the mesh at `scale` is far larger than a hand-held object: its size
// read as millimetres or centimetres. 0: none.
double suggestedScale(double extent_m, double scale) {
  if (extent_m > 20.0 && extent_m * 1e-3 >= 0.005) return scale * 1e-3;  // millimetres
  if (extent_m > 2.0) return scale * 1e-2;                                // centimetres
  return 0.0;
}

std::string format(const char* f, double v) {
  char text[64];
  std::snprintf(text, sizeof text, f, v);
  return text;
}

}  // namespace

nlohmann::json meshInfoJson(const MeshInfoOptions& o) {
  const sim::MeshFileInfo file = sim::describeMeshFile(o.path);
  const sim::Mesh read = sim::loadMesh(o.path, 1.0);
  const sim::Mesh mesh = sim::loadMesh(o.path, o.scale);
  nlohmann::json parts = nlohmann::json::array();
  int raw_vertices = 0, raw_triangles = 0;
  for (const sim::MeshPart& p : file.parts) {
    const Eigen::Matrix4d& t = p.transform;
    parts.push_back({{"mesh", p.mesh},
                     {"node", p.node},
                     {"vertices", p.vertices},
                     {"triangles", p.triangles},
                     {"translation", {t(0, 3), t(1, 3), t(2, 3)}},
                     {"transformed", !t.isIdentity(1e-12)}});
    raw_vertices += p.vertices;
    raw_triangles += p.triangles;
  }
  const sim::MeshBuildReport& r = mesh.report();
  const bool closed = r.boundary_edges == 0 && r.non_manifold_edges == 0;
  const sim::MassProperties mp = sim::massProperties(mesh);
  const bool outward = mp.volume > 0.0 && r.inconsistent_edges == 0;
  const sim::Vec3 extent = mesh.boundsMax() - mesh.boundsMin();
  nlohmann::json j = {
      {"file", o.path},
      {"format", file.format},
      {"parts", parts},
      {"part_count", parts.size()},
      {"declared", {{"unit_m", file.declared_unit_m > 0.0 ? nlohmann::json(file.declared_unit_m) : nlohmann::json(nullptr)},
                    {"up_axis", file.declared_up.empty() ? nlohmann::json(nullptr) : nlohmann::json(file.declared_up)},
                    {"applied_by_the_importer", file.unit_and_up_applied},
                    {"unit_applied", file.unit_applied}}},
      {"scale", o.scale},
      {"read", {{"vertices", raw_vertices}, {"triangles", raw_triangles}}},
      {"welded", {{"vertices", mesh.vertexCount()}, {"triangles", mesh.faceCount()},
                  {"merged_vertices", r.welded_vertices}, {"dropped_degenerate", r.dropped_degenerate},
                  {"dropped_duplicates", r.dropped_duplicates}}},
      {"bounds_as_read", {{"min", vec(read.boundsMin())}, {"max", vec(read.boundsMax())}}},
      {"bounds_m", {{"min", vec(mesh.boundsMin())}, {"max", vec(mesh.boundsMax())}, {"size", vec(extent)}}},
      {"checks", {{"closed", closed}, {"boundary_edges", r.boundary_edges}, {"non_manifold_edges", r.non_manifold_edges},
                  {"inconsistent_winding_edges", r.inconsistent_edges}, {"outward", outward}}},
  };
  const sim::SolidCheck solid = sim::solidCheck(mesh);  // the rule a dynamic body meets in a scene
  if (solid.solid) {
    const double mass = o.mass > 0.0 ? o.mass : o.density * mp.volume;
    const Eigen::Matrix3d inertia = (mass / mp.volume) * mp.inertia;
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> principal(inertia);
    j["solid"] = {{"volume_m3", mp.volume},
                  {"mass_kg", mass},
                  {"density_kg_m3", mass / mp.volume},
                  {"centre_of_mass_m", vec(mp.centroid)},
                  {"inertia_kg_m2", {vec(inertia.row(0).transpose()), vec(inertia.row(1).transpose()),
                                     vec(inertia.row(2).transpose())}},
                  {"principal_moments_kg_m2", vec(principal.eigenvalues())}};
  } else {
    j["solid"] = nullptr;
    j["solid_why_not"] = solid.why_not + ": usable as a static body or a walk mesh only (a dynamic body is refused)";
  }
  const double suggest = suggestedScale(extent.maxCoeff(), o.scale);
  j["suggested_scale"] = suggest > 0.0 ? nlohmann::json(suggest) : nlohmann::json(nullptr);
  if (suggest > 0.0) {
    j["suggestion"] = "the mesh is " + format("%.3g", extent.maxCoeff()) + " m across at scale " + format("%g", o.scale) +
                      (suggest == o.scale * 1e-3 ? "; read as millimetres" : "; read as centimetres") +
                      ", scale = " + format("%g", suggest);
  }
  return j;
}

std::string meshInfoText(const nlohmann::json& j) {
  std::string t;
  const auto line = [&](const std::string& s) { t += s + "\n"; };
  const auto v3 = [](const nlohmann::json& v) {
    char text[96];
    std::snprintf(text, sizeof text, "(%.6g, %.6g, %.6g)", v[0].get<double>(), v[1].get<double>(), v[2].get<double>());
    return std::string(text);
  };
  line(j["file"].get<std::string>() + " (" + (j["format"].get<std::string>().empty() ? "format unnamed" : j["format"].get<std::string>()) + ")");
  line("parts: " + std::to_string(j["part_count"].get<int>()));
  for (const nlohmann::json& p : j["parts"]) {
    line("  " + (p["mesh"].get<std::string>().empty() ? std::string("(unnamed)") : p["mesh"].get<std::string>()) + " under node '" +
         p["node"].get<std::string>() + "': " + std::to_string(p["vertices"].get<int>()) + " vertices, " +
         std::to_string(p["triangles"].get<int>()) + " triangles" +
         (p["transformed"].get<bool>() ? ", moved to " + v3(p["translation"]) + " by its node" : ""));
  }
  const nlohmann::json& d = j["declared"];
  const bool unit_only = d["unit_applied"].get<bool>() && !d["applied_by_the_importer"].get<bool>();
  line("declared unit: " + (d["unit_m"].is_null() ? std::string("none") : format("%g m", d["unit_m"].get<double>())) +
       (unit_only ? " (applied on reading)" : "") + ", up axis: " + (d["up_axis"].is_null() ? std::string("none") : d["up_axis"].get<std::string>()) +
       (d["applied_by_the_importer"].get<bool>() ? " (applied on reading)" : ""));
  line("welded: " + std::to_string(j["welded"]["vertices"].get<int>()) + " vertices, " +
       std::to_string(j["welded"]["triangles"].get<int>()) + " triangles (read " + std::to_string(j["read"]["vertices"].get<int>()) +
       " and " + std::to_string(j["read"]["triangles"].get<int>()) + "; " +
       std::to_string(j["welded"]["dropped_degenerate"].get<int>()) + " degenerate and " +
       std::to_string(j["welded"]["dropped_duplicates"].get<int>()) + " duplicate triangles dropped)");
  line("bounds as read: " + v3(j["bounds_as_read"]["min"]) + " to " + v3(j["bounds_as_read"]["max"]));
  line("bounds at scale " + format("%g", j["scale"].get<double>()) + ": " + v3(j["bounds_m"]["min"]) + " to " +
       v3(j["bounds_m"]["max"]) + " m, size " + v3(j["bounds_m"]["size"]) + " m");
  const nlohmann::json& c = j["checks"];
  line(std::string("closed: ") + (c["closed"].get<bool>() ? "yes" : "no") + " (" + std::to_string(c["boundary_edges"].get<int>()) +
       " boundary edges, " + std::to_string(c["non_manifold_edges"].get<int>()) + " non-manifold edges); outward: " +
       (c["outward"].get<bool>() ? "yes" : "no") + " (" + std::to_string(c["inconsistent_winding_edges"].get<int>()) +
       " edges between faces of opposite winding)");
  if (j["solid"].is_null()) {
    line("solid: " + j["solid_why_not"].get<std::string>());
  } else {
    const nlohmann::json& s = j["solid"];
    line("volume " + format("%.6g", s["volume_m3"].get<double>()) + " m^3; mass " + format("%.6g", s["mass_kg"].get<double>()) +
         " kg (density " + format("%.6g", s["density_kg_m3"].get<double>()) + " kg/m^3)");
    line("centre of mass " + v3(s["centre_of_mass_m"]) + " m; principal moments " + v3(s["principal_moments_kg_m2"]) +
         " kg m^2");
  }
  if (!j["suggested_scale"].is_null()) line("suggestion: " + j["suggestion"].get<std::string>());
  return t;
}

namespace {

class MeshInfoCommand final : public Command {
 public:
  CLI::App* add(CLI::App& app) override {
    MeshInfoOptions& o = options_;
    CLI::App* m = app.add_subcommand("mesh-info", "What a mesh file holds: parts, size, unit and up axis, whether it "
                                                  "is closed and outward, volume, centre of mass and inertia");
    m->add_option("file", o.path, "Mesh file (OBJ, PLY, STL, OFF, glTF, Collada, ...)")->required();
    m->add_option("--scale", o.scale, "File units to metres, as a body's scale (default 1)")
        ->check(settingCheck(sim::bodySettings(), "scale"));
    m->add_option("--mass", o.mass, "Mass (kg) for the inertia (default: from --density)")->check(CLI::Range(1e-9, 1e9));
    m->add_option("--density", o.density, "Density (kg/m^3) when no mass is given (default 1000)")
        ->check(CLI::Range(1e-6, 1e6));
    m->add_flag("--json", json_, "Print JSON instead of text");
    return m;
  }

  int run() override {
    try {
      options_.path = resolveDataPath(options_.path);
      const nlohmann::json info = meshInfoJson(options_);
      std::fputs(json_ ? (info.dump(2) + "\n").c_str() : meshInfoText(info).c_str(), stdout);
    } catch (const sim::MeshLoadError& e) {
      throw commandLineError("file", e.what());
    }
    return 0;
  }

 private:
  MeshInfoOptions options_;
  bool json_ = false;
};

}  // namespace

std::unique_ptr<Command> makeMeshInfoCommand(const std::vector<std::string>&) {
  return std::make_unique<MeshInfoCommand>();
}

}  // namespace gf::app
