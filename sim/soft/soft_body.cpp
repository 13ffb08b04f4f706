#include "sim/soft/soft_body.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace gf::sim {
namespace {

// The surface's nodes (each once, in the order first met) and its triangles in their indices.
void surfaceIndex(const TetMesh& mesh, std::vector<int>& nodes, std::vector<std::array<std::int32_t, 3>>& triangles) {
  std::vector<int> vertex_of(mesh.nodes.size(), -1);
  for (const std::array<int, 3>& t : mesh.surface) {
    std::array<std::int32_t, 3> local{};
    for (std::size_t k = 0; k < 3; ++k) {
      int& v = vertex_of[static_cast<std::size_t>(t[k])];
      if (v < 0) {
        v = static_cast<int>(nodes.size());
        nodes.push_back(t[k]);
      }
      local[k] = v;
    }
    triangles.push_back(local);
  }
}

}  // namespace

SoftBody::SoftBody(const TetMesh& mesh, const SoftBodySettings& settings, const std::vector<int>& pinned, int fingers)
    : settings_(settings), mesh_(mesh) {
  if (mesh.tets.empty() || mesh.surface.empty()) throw std::invalid_argument("soft body: a mesh with no tetrahedra");
  if (!(settings.contact_stiffness >= 1e2 && settings.contact_stiffness <= 1e7)) {
    throw std::invalid_argument("contact_stiffness: must be in 1e2..1e7 N/m, got " + std::to_string(settings.contact_stiffness));
  }
  solid_ = std::make_unique<FemSolid>(mesh, settings.material);
  solid_->setContactStiffness(settings.contact_stiffness);
  solid_->fixNodes(pinned);
  std::vector<std::array<std::int32_t, 3>> triangles;
  surfaceIndex(mesh, surface_nodes_, triangles);
  triangles_ = std::make_shared<const std::vector<std::array<int, 3>>>(mesh.surface);
  surface_points_.resize(surface_nodes_.size());
  for (std::size_t v = 0; v < surface_nodes_.size(); ++v) surface_points_[v] = mesh.nodes[static_cast<std::size_t>(surface_nodes_[v])];
  surface_ = std::make_unique<Mesh>(buildMesh(surface_points_, triangles));
  for (const std::array<std::int32_t, 3>& t : triangles) {
    rest_areas_.push_back((surface_points_[t[1]] - surface_points_[t[0]]).cross(surface_points_[t[2]] - surface_points_[t[0]]));
  }
  const MeshBuildReport& report = surface_->report();
  if (report.welded_vertices > 0 || report.dropped_degenerate > 0 || report.dropped_duplicates > 0) {
    throw std::invalid_argument("soft body: its surface has coinciding nodes or flat triangles");
  }
  pinned_.assign(mesh.nodes.size(), 0);
  for (int n : pinned) pinned_[static_cast<std::size_t>(n)] = 1;
  for (int n : surface_nodes_) {
    if (!pinned_[static_cast<std::size_t>(n)]) free_surface_nodes_.push_back(n);
  }
  for (int k = 0; k < fingers; ++k) solid_->addPartner(surface_nodes_);
  rigid_partner_ = solid_->addPartner(surface_nodes_);
  node_contacts_ = std::make_unique<NodeContacts>(static_cast<int>(mesh.nodes.size()), mesh.surface);
  for (double m : solid_->masses()) mass_ += m;
  for (std::size_t n = 0; n < mesh.nodes.size(); ++n) rest_centre_ += solid_->masses()[n] * mesh.nodes[n] / mass_;
  frame_.position = rest_centre_;
  finger_pressed_.assign(static_cast<std::size_t>(fingers), 0);
  // Per finger, a friction spring per node and one for a face's point (the last).
  slides_.assign(static_cast<std::size_t>(fingers), std::vector<Vec3>(mesh.nodes.size() + 1, Vec3::Zero()));
  slid_.assign(static_cast<std::size_t>(fingers), std::vector<char>(mesh.nodes.size() + 1, 0));
}

SoftBody::~SoftBody() = default;

bool SoftBody::validPress(const SoftPress& p, int fingers) const {
  if (p.finger < 0 || p.finger >= fingers) return false;
  if (p.face >= 0) return p.face < surface_->faceCount();
  return p.node >= 0 && p.node < solid_->nodeCount();
}

std::size_t SoftBody::keyOf(const SoftPress& p) const {
  return p.face >= 0 || p.key < 0 || p.key >= solid_->nodeCount() ? static_cast<std::size_t>(solid_->nodeCount())
                                                                    : static_cast<std::size_t>(p.key);
}

// Each press a contact of its face's point with its finger (the finger's partner), its friction
// spring stretched as its key's was at the last step's end; each pressing finger's step.
void SoftBody::addPresses(std::span<const SoftFinger> fingers, const std::vector<SoftPress>& presses) {
  std::fill(finger_pressed_.begin(), finger_pressed_.end(), 0);
  press_contact_.clear();
  for (const SoftPress& p : presses) {
    press_contact_.push_back(-1);
    if (!validPress(p, static_cast<int>(fingers.size()))) continue;
    FemContact c{p.node, p.normal, p.depth, fingers[static_cast<std::size_t>(p.finger)].velocity, Vec3::Zero(), p.friction, p.finger};
    if (p.face >= 0) {
      const std::array<std::int32_t, 3>& t = surface_->triangles()[static_cast<std::size_t>(p.face)];
      c.node = surfaceNode(t[0]);
      c.others = {surfaceNode(t[1]), surfaceNode(t[2])};
      c.weights = p.weights;
    }
    const std::size_t key = keyOf(p);
    if (slid_[static_cast<std::size_t>(p.finger)][key]) c.slide = slides_[static_cast<std::size_t>(p.finger)][key];
    press_contact_.back() = static_cast<int>(contacts_.size());
    contacts_.push_back(c);
    finger_pressed_[static_cast<std::size_t>(p.finger)] = 1;
  }
  for (std::size_t k = 0; k < fingers.size(); ++k) {
    const SoftFinger& f = fingers[k];
    if (finger_pressed_[k]) solid_->setPartner(static_cast<int>(k), f.mass, f.velocity, f.force);
    else solid_->setPartner(static_cast<int>(k), 1.0, Vec3::Zero());  // no contact: a still unknown of its own
  }
}

void SoftBody::step(double dt, const Vec3& gravity, const PadSurfaces& surfaces, std::span<const SoftFinger> fingers,
                    const std::vector<SoftPress>& presses) {
  node_contacts_->find(solid_->positions(), free_surface_nodes_, frame_.position, surfaces, settings_.friction, true, contacts_);
  node_contacts_->choosePartner(*solid_, rigid_partner_, surfaces, contacts_);
  addPresses(fingers, presses);
  nodeForces(gravity);
  solid_->keepState();
  solid_->step(dt, gravity_forces_, Vec3::Zero(), contacts_);
  bool finite = true;
  for (const Vec3& p : solid_->positions()) finite = finite && p.allFinite();
  for (std::size_t k = 0; k < fingers.size(); ++k) finite = finite && solid_->partnerVelocity(static_cast<int>(k)).allFinite();
  undone_ = !(finite && solid_->invertedElements() == 0);
  if (undone_) {
    undo();
  } else {
    node_contacts_->read(dt, *solid_, contacts_, surfaces, settings_.contact_stiffness);
    readPresses(presses);
    undone_last_ = false;
  }
  for (std::size_t v = 0; v < surface_nodes_.size(); ++v) surface_points_[v] = solid_->positions()[static_cast<std::size_t>(surface_nodes_[v])];
  surface_->moveVertices(surface_points_);
  fitFrame();
}

// Each node's weight and share of the load (setLoad).
void SoftBody::nodeForces(const Vec3& gravity) {
  const std::vector<double>& m = solid_->masses();
  const std::vector<Vec3>& x = solid_->positions();
  gravity_forces_.resize(m.size());
  Vec3 alpha = Vec3::Zero();
  if (load_torque_.squaredNorm() > 0.0) {
    Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
    for (std::size_t n = 0; n < m.size(); ++n) {
      const Vec3 r = x[n] - frame_.position;
      inertia += m[n] * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
    }
    alpha = inertia.ldlt().solve(load_torque_);
  }
  for (std::size_t n = 0; n < m.size(); ++n) {
    gravity_forces_[n] = m[n] * (gravity + load_force_ / mass_ + alpha.cross(x[n] - frame_.position));
  }
}

// Each press's force and point, and its friction spring's stretch kept for its key (f / k).
void SoftBody::readPresses(const std::vector<SoftPress>& presses) {
  press_results_.assign(presses.size(), SoftPressResult{});
  for (std::vector<char>& slid : slid_) std::fill(slid.begin(), slid.end(), 0);
  const std::vector<FemContactResult>& results = solid_->contactResults();
  const std::vector<Vec3>& x = solid_->positions();
  for (std::size_t i = 0; i < presses.size(); ++i) {
    const int ci = press_contact_[i];
    if (ci < 0) continue;
    const FemContact& c = contacts_[static_cast<std::size_t>(ci)];
    const FemContactResult& r = results[static_cast<std::size_t>(ci)];
    SoftPressResult& out = press_results_[i];
    out.point = x[static_cast<std::size_t>(c.node)];
    if (c.others[0] >= 0) {
      out.point = c.weights[0] * x[static_cast<std::size_t>(c.node)] + c.weights[1] * x[static_cast<std::size_t>(c.others[0])] +
                  c.weights[2] * x[static_cast<std::size_t>(c.others[1])];
    }
    if (r.released) continue;
    out.force = r.force;
    out.slipping = r.slipping;
    const std::size_t f = static_cast<std::size_t>(presses[i].finger);
    const std::size_t key = keyOf(presses[i]);
    slides_[f][key] = (r.force - r.force.dot(c.normal) * c.normal) / settings_.contact_stiffness;
    slid_[f][key] = 1;
  }
}

// Back to the step's start at rest, every contact and friction spring let go; twice running, the
// rest shape put where the body's frame is (its nodes' own motion undone).
void SoftBody::undo() {
  ++resets_;
  node_contacts_->clear();
  press_results_.clear();
  for (std::vector<char>& slid : slid_) std::fill(slid.begin(), slid.end(), 0);
  solid_->restoreState();
  if (undone_last_) {
    const Eigen::Matrix3d r = frame_.orientation.toRotationMatrix();
    std::vector<Vec3>& x = solid_->positions();
    for (std::size_t n = 0; n < x.size(); ++n) x[n] = frame_.position + r * (mesh_.nodes[n] - rest_centre_);
    // pinned nodes stay where they are held
    for (std::size_t n = 0; n < x.size(); ++n) {
      if (pinned_[n]) x[n] = mesh_.nodes[n];
    }
  }
  undone_last_ = true;
}

// The centre of mass, and the rotation nearest to Σ m (x − c)(X − C)ᵀ (shape matching).
void SoftBody::fitFrame() {
  const std::vector<Vec3>& x = solid_->positions();
  const std::vector<double>& m = solid_->masses();
  Vec3 centre = Vec3::Zero();
  for (std::size_t n = 0; n < x.size(); ++n) centre += m[n] * x[n];
  centre /= mass_;
  Eigen::Matrix3d a = Eigen::Matrix3d::Zero();
  for (std::size_t n = 0; n < x.size(); ++n) a += m[n] * (x[n] - centre) * (mesh_.nodes[n] - rest_centre_).transpose();
  if (!(centre.allFinite() && a.allFinite())) return;
  frame_.position = centre;
  frame_.orientation = nearestRotation(a, frame_.orientation);
}

Vec3 SoftBody::restPoint(int face, const Vec3& weights) const {
  const std::array<int, 3>& t = (*triangles_)[static_cast<std::size_t>(face)];
  Vec3 rest = Vec3::Zero();
  for (std::size_t k = 0; k < 3; ++k) rest += weights[static_cast<Eigen::Index>(k)] * mesh_.nodes[static_cast<std::size_t>(t[k])];
  return frame_.toWorld(rest - rest_centre_);
}

Vec3 SoftBody::restNormal(int face, const Vec3& weights) const {
  const std::array<std::int32_t, 3>& t = surface_->triangles()[static_cast<std::size_t>(face)];
  const Vec3 own = rest_areas_[static_cast<std::size_t>(face)].normalized();
  const double smooth = std::cos(kSmoothAngle);
  Vec3 n = Vec3::Zero();
  for (int k = 0; k < 3; ++k) {
    Vec3 corner = Vec3::Zero();
    for (const std::int32_t* g = surface_->vertexFacesBegin(t[static_cast<std::size_t>(k)]); g != surface_->vertexFacesEnd(t[static_cast<std::size_t>(k)]); ++g) {
      const Vec3& area = rest_areas_[static_cast<std::size_t>(*g)];
      if (area.dot(own) >= smooth * area.norm()) corner += area;
    }
    n += weights[k] * corner.normalized();
  }
  return frame_.orientation * n.normalized();
}

Vec3 SoftBody::velocity() const {
  Vec3 p = Vec3::Zero();
  for (std::size_t n = 0; n < solid_->masses().size(); ++n) p += solid_->masses()[n] * solid_->velocities()[n];
  return p / mass_;
}

Vec3 SoftBody::angularVelocity() const {
  const std::vector<Vec3>& x = solid_->positions();
  const std::vector<double>& m = solid_->masses();
  const Vec3 v = velocity();
  Vec3 l = Vec3::Zero();
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
  for (std::size_t n = 0; n < x.size(); ++n) {
    const Vec3 r = x[n] - frame_.position;
    l += m[n] * r.cross(solid_->velocities()[n] - v);
    inertia += m[n] * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
  }
  return inertia.ldlt().solve(l);
}

double SoftBody::kineticEnergy() const {
  double e = 0.0;
  for (std::size_t n = 0; n < solid_->masses().size(); ++n) e += 0.5 * solid_->masses()[n] * solid_->velocities()[n].squaredNorm();
  return e;
}

}  // namespace gf::sim
