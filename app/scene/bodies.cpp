// [bodies.NAME]: shapes, meshes, masses and the mass ratios a pinch can hold.
#include "app/scene/sections.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>

#include "sim/scene/settings.hpp"

namespace gf::app {
namespace {

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
    case sim::ShapeKind::kSoftBox:
    case sim::ShapeKind::kSoftSphere:
    case sim::ShapeKind::kSoftCylinder:
    case sim::ShapeKind::kSoftMesh: {  // its tetrahedra's
      double volume = 0.0;
      if (b.soft.tets) {
        for (const auto& t : b.soft.tets->tets) {
          const auto& x = b.soft.tets->nodes;
          volume += sim::tetVolume(x[t[0]], x[t[1]], x[t[2]], x[t[3]]);
        }
      }
      return volume;
    }
  }
  return 0.0;
}

// A dynamic mesh body spreads its mass over the volume its mesh encloses: an open or inside-out
// mesh has none (the rule of sim::solidCheck, which `godfinger mesh-info` reports too).
void requireSolid(Reader& r, const sim::BodyDesc& b) {
  if (const sim::SolidCheck solid = sim::solidCheck(*b.mesh); !solid.solid) {
    r.fail(r.find("mesh"), "mesh", "'" + b.mesh_path + "': " + solid.why_not + "; a dynamic body takes its mass "
           "distribution from that volume: set static = true, or close the mesh (godfinger mesh-info shows its edges)");
  }
}

bool softBodySetting(const sim::Setting<sim::BodyDesc>& s) {
  for (std::string_view name : {"young", "poisson", "damping", "element_size", "contact_stiffness"}) {
    if (s.name == name) return true;
  }
  return false;
}

// `pinned`: boxes of nodes held fixed, each holding at least one node.
void readPins(Reader& r, sim::BodyDesc& b) {
  const toml::node* n = r.find("pinned");
  if (!n) return;
  const toml::array* a = n->as_array();
  if (!a) r.fail(n, "pinned", "expected an array of { min = [x, y, z], max = [x, y, z] } boxes (m, in the body's frame)");
  for (const toml::node& e : *a) {
    const toml::table* t = e.as_table();
    if (!t) r.fail(&e, "pinned", "expected { min = [x, y, z], max = [x, y, z] }");
    Reader pr(*t, r.field("pinned"), r.file());
    sim::PinRegion region{pr.vec3("min", sim::Vec3::Zero()), pr.vec3("max", sim::Vec3::Zero())};
    if (!pr.has("min") || !pr.has("max") || !region.min.allFinite() || !region.max.allFinite() ||
        !(region.min.array() <= region.max.array()).all()) {
      r.fail(&e, "pinned", "each box needs min and max, min <= max in every coordinate");
    }
    const bool holds = std::any_of(b.soft.tets->nodes.begin(), b.soft.tets->nodes.end(), [&](const sim::Vec3& p) {
      return (p.array() >= region.min.array()).all() && (p.array() <= region.max.array()).all();
    });
    if (!holds) r.fail(&e, "pinned", "the box holds no node of the body");
    pr.finish();
    b.soft.pinned.push_back(region);
  }
}

// Body settings every shape has (dimensions, scale and mass are read where they apply).
bool commonBodySetting(const sim::Setting<sim::BodyDesc>& s) {
  for (const sim::ShapeInfo& shape : sim::shapeInfos()) {
    for (std::string_view d : shape.dimensions) {
      if (d == s.name) return false;
    }
  }
  return s.name != "scale" && s.name != "mass" && !softBodySetting(s);
}

// A soft body's tetrahedra (`tets` for soft_mesh, with `scale`), its material and its pinned
// boxes (`pinned = [{ min = [x, y, z], max = [x, y, z] }, ...]`, m in the body's frame). Settings
// of soft bodies on a rigid one are refused.
void readSoft(Reader& r, const std::string& base_dir, sim::BodyDesc& b) {
  if (!sim::isSoftShape(b.shape)) {
    for (const sim::Setting<sim::BodyDesc>& s : sim::bodySettings()) {
      if (softBodySetting(s) && r.has(std::string(s.name))) {
        r.fail(r.find(std::string(s.name)), std::string(s.name), "only soft bodies (shape soft_*) have it");
      }
    }
    for (const char* field : {"pinned", "tets"}) {
      if (r.has(field)) r.fail(r.find(field), field, "only soft bodies (shape soft_*) have it");
    }
    return;
  }
  for (const sim::Setting<sim::BodyDesc>& s : sim::bodySettings()) {
    if (softBodySetting(s)) r.setting(s, b, std::string(s.name));
  }
  if (b.shape == sim::ShapeKind::kSoftMesh) {
    const toml::node* n = r.find("tets");
    if (!n || !n->is_string()) r.fail(n, "tets", "expected the tetrahedra's file (a TetGen .node, its .ele beside it, or a legacy .vtk)");
    b.soft.tet_path = resolvePath(base_dir, n->as_string()->get());
    r.setting(*sim::findSetting(sim::bodySettings(), "scale"), b, "scale");
  } else if (r.has("tets")) {
    r.fail(r.find("tets"), "tets", "only shape soft_mesh reads a file");
  }
  try {
    b.soft.tets = sim::softMesh(b);
  } catch (const std::exception& e) {  // a file that cannot be read, a size the generator refuses
    const char* field = b.shape == sim::ShapeKind::kSoftMesh ? "tets" : "element_size";
    r.fail(r.find(field), field, e.what());
  }
  readPins(r, b);
}

}  // namespace

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
  readSoft(r, base_dir, b);
  const bool is_plane = b.shape == sim::ShapeKind::kPlane;
  const bool is_static = r.boolean("static", is_plane);
  if (is_plane && !is_static) r.fail(r.find("static"), "static", "a plane is always static");
  if (!is_static && sim::isMeshShape(b.shape)) requireSolid(r, b);
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
      r.fail(r.find("density"), "density",
             "gives a mass of " + sim::numberText(b.mass) + " kg (volume " + sim::numberText(volume) + " m^3): " + *why);
    }
  } else {
    r.setting(*sim::findSetting(sim::bodySettings(), "mass"), b, "mass", true);
  }
  for (const sim::Setting<sim::BodyDesc>& s : sim::bodySettings()) {
    if (commonBodySetting(s)) r.setting(s, b, std::string(s.name));
  }
  b.orientation = r.orientation(Eigen::Quaterniond::Identity());
  r.failOn(sim::validateBody(b));
  r.finish();
  return b;
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
    const auto [least, got] = sim::distinctTexts(lightest, body->mass, 6);
    const std::string why = "must be at least 1/100 of the heaviest proxy, " + least + " kg here (fingers." +
                            heaviest->name + ".proxy_mass " + sim::numberText(heaviest->proxy.mass) +
                            " kg): the solver cannot hold a lighter body in a pinch, got " + got;
    const char* field = br.has("density") ? "density" : "mass";  // the field the user wrote
    br.fail(br.find(field), field, why);
  }
}

}  // namespace gf::app
