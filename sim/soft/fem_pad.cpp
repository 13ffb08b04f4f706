#include "sim/soft/fem_pad.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace gf::sim {
namespace {

// The tet pad of `s` whose skin has `skin_radius`, turned from facing -y to facing `axis` and
// moved to `centre`.
TetMesh placedPad(const PadSettings& s, double skin_radius, const Vec3& axis, const Vec3& centre) {
  if (!(axis.allFinite() && axis.norm() > 0.0)) throw std::invalid_argument("pad_axis: must not be zero");
  const PadShape shape{skin_radius - s.thickness, s.thickness, s.cap_angle, s.element_size};
  TetMesh mesh = generatePad(shape);
  const Quat turn = Quat::FromTwoVectors(Vec3(0.0, -1.0, 0.0), axis.normalized());
  for (Vec3& p : mesh.nodes) p = turn * p + centre;
  return mesh;
}

Vec3 toLocal(const Pose& frame, const Vec3& world) { return frame.orientation.conjugate() * (world - frame.position); }

}  // namespace

FemPad::FemPad(const PadSettings& settings, double skin_radius, double bone_mass, const Vec3& axis,
               const Vec3& centre)
    : settings_(settings), mesh_(placedPad(settings, skin_radius, axis, centre)), centre0_(centre),
      bone_radius_(skin_radius - settings.thickness) {
  solid_ = std::make_unique<FemSolid>(mesh_, FemMaterial{settings.young, settings.poisson, settings.density, settings.damping});
  solid_->setBone(mesh_.bone_nodes, bone_mass);
  solid_->setContactStiffness(settings.contact_stiffness);
  std::vector<char> on_bone(mesh_.nodes.size(), 0), on_skin(mesh_.nodes.size(), 0);
  for (int n : mesh_.bone_nodes) on_bone[static_cast<std::size_t>(n)] = 1;
  auto skin = std::make_shared<std::vector<std::array<int, 3>>>();
  for (const std::array<int, 3>& t : mesh_.surface) {
    if (on_bone[t[0]] && on_bone[t[1]] && on_bone[t[2]]) continue;  // the bone's side
    skin->push_back(t);
    for (int n : t) on_skin[static_cast<std::size_t>(n)] |= !on_bone[static_cast<std::size_t>(n)];
  }
  skin_ = std::move(skin);
  for (std::size_t n = 0; n < on_skin.size(); ++n) {
    if (on_skin[n]) skin_nodes_.push_back(static_cast<int>(n));
  }
  solid_->enablePartner(skin_nodes_);
  anchors_.resize(mesh_.nodes.size());
  node_area_.resize(mesh_.nodes.size());
}

FemPad::~FemPad() = default;

void FemPad::follow(const Vec3& centre, const Vec3& velocity) {
  if (!(centre.allFinite() && velocity.allFinite())) return;
  solid_->moveBone(centre - centre0_, velocity);
}

// Each skin node inside a surface near the pad: a contact with the deepest one, its tangential
// spring pulling towards its anchor when it kept one on that body.
void FemPad::findContacts(const PadSurfaces& surfaces, double friction) {
  const std::vector<Vec3>& x = solid_->positions();
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (int n : skin_nodes_) {
    lo = lo.cwiseMin(x[static_cast<std::size_t>(n)]);
    hi = hi.cwiseMax(x[static_cast<std::size_t>(n)]);
  }
  surfaces.near(lo, hi, near_);
  fem_contacts_.clear();
  contact_body_.clear();
  for (int n : skin_nodes_) {
    const std::size_t i = static_cast<std::size_t>(n);
    double deepest = 0.0, depth = 0.0;
    Vec3 normal = Vec3::UnitY(), best_normal = normal;
    int body = -1;
    // A node pushed only out of a surface that faces its bone: one past a thin body's middle
    // finds the far face nearer, whose normal points away, and would be pushed through.
    const Vec3 inward = boneCentre() - x[i];
    for (int b : near_) {
      if (surfaces.inside(b, x[i], depth, normal) && depth > deepest && normal.dot(inward) > 0.0) {
        deepest = depth;
        best_normal = normal;
        body = b;
      }
    }
    Anchor& anchor = anchors_[i];
    if (body < 0) {
      anchor.body = -1;
      continue;
    }
    FemContact c{n, best_normal, deepest, surfaces.velocityAt(body, x[i]), Vec3::Zero(), friction, false};
    if (anchor.body == body) c.slide = surfaces.frame(body).toWorld(anchor.local) - x[i];
    fem_contacts_.push_back(c);
    contact_body_.push_back(body);
  }
}

// The contacts' forces as the solve left them: each one's opposite on its body, its anchor kept
// where its friction spring now pulls from (dragged along when it slipped), its share of the skin.
void FemPad::readContacts(double dt, const PadSurfaces& surfaces) {
  const std::vector<Vec3>& x = solid_->positions();
  const std::vector<FemContactResult>& results = solid_->contactResults();
  contacts_.clear();
  for (std::size_t k = 0; k < fem_contacts_.size(); ++k) {
    const FemContact& c = fem_contacts_[k];
    const std::size_t i = static_cast<std::size_t>(c.node);
    const FemContactResult& r = results[k];
    if (r.released) {
      anchors_[i].body = -1;
      continue;
    }
    const int body = contact_body_[k];
    const Vec3 friction = r.force - r.force.dot(c.normal) * c.normal;
    const Vec3 anchor = x[i] + friction / settings_.contact_stiffness - dt * c.surface_velocity;
    anchors_[i] = {body, toLocal(surfaces.frame(body), anchor)};
    node_area_[i] = 0.0;
    contacts_.push_back({c.node, body, x[i], c.normal, -r.force, c.depth, 0.0, r.slipping});
  }
  if (contacts_.empty()) return;
  for (const std::array<int, 3>& t : *skin_) {
    const double third = (x[t[1]] - x[t[0]]).cross(x[t[2]] - x[t[0]]).norm() / 6.0;
    for (int n : t) node_area_[static_cast<std::size_t>(n)] += third;
  }
  for (PadNodeContact& c : contacts_) c.area = node_area_[static_cast<std::size_t>(c.node)];
  for (const std::array<int, 3>& t : *skin_) {
    for (int n : t) node_area_[static_cast<std::size_t>(n)] = 0.0;
  }
}

// The dynamic body pressed by the most nodes this step is solved with the pad (its translation;
// FemSolid::enablePartner): the others' contacts, and every body's turning, stay explicit.
void FemPad::choosePartner(const PadSurfaces& surfaces) {
  int best = -1, best_count = 0;
  for (std::size_t k = 0; k < fem_contacts_.size(); ++k) {
    const int body = contact_body_[k];
    if (body == best || !(surfaces.mass(body) > 0.0)) continue;
    const int count = static_cast<int>(std::count(contact_body_.begin(), contact_body_.end(), body));
    if (count > best_count) {
      best = body;
      best_count = count;
    }
  }
  solid_->setPartner(best >= 0 ? surfaces.mass(best) : 1.0, best >= 0 ? surfaces.velocity(best) : Vec3::Zero());
  for (std::size_t k = 0; k < fem_contacts_.size(); ++k) fem_contacts_[k].on_partner = best >= 0 && contact_body_[k] == best;
}

void FemPad::step(double dt, const Vec3& bone_force, double friction, const PadSurfaces& surfaces) {
  findContacts(surfaces, friction);
  choosePartner(surfaces);
  solid_->keepState();
  solid_->step(dt, {}, bone_force, fem_contacts_);
  bool finite = solid_->boneOffset().allFinite() && solid_->boneVelocity().allFinite();
  for (const Vec3& p : solid_->positions()) finite = finite && p.allFinite();
  if (finite) {
    readContacts(dt, surfaces);
  } else {
    contacts_.clear();
  }
  const int inverted = finite ? solid_->invertedElements() : 0;
  if (finite && inverted == 0) {
    reset_last_step_ = false;
    return;
  }
  contacts_.clear();  // the step is undone: its forces with it
  // Back to the step's start at rest, every anchor let go: the skin's friction, which twisted or
  // sheared it inside out, slips; a pad crushed past its thickness is held where it last was.
  // Twice running (the step's start was no way out): back to rest on the bone.
  last_inverted_ = inverted;
  ++resets_;
  if (reset_last_step_) {
    solid_->resetToRest();
    liftOut(surfaces);
  } else {
    solid_->restoreState();
  }
  reset_last_step_ = true;
  for (Anchor& a : anchors_) a.body = -1;
}

// Every node inside a surface put on it (a pad put back at rest where its bone is pressed in
// would start deep in the body, its springs a kick): it starts flattened instead.
void FemPad::liftOut(const PadSurfaces& surfaces) {
  std::vector<Vec3>& x = solid_->positions();
  double depth = 0.0;
  Vec3 normal = Vec3::UnitY();
  for (int n : skin_nodes_) {
    Vec3& p = x[static_cast<std::size_t>(n)];
    for (int b : near_) {
      if (surfaces.inside(b, p, depth, normal) && normal.dot(boneCentre() - p) > 0.0) p += depth * normal;
    }
  }
}

double FemPad::kineticEnergy() const {
  const FemSolid& s = *solid_;
  double e = 0.0;
  for (std::size_t n = 0; n < s.masses().size(); ++n) e += 0.5 * s.masses()[n] * s.velocities()[n].squaredNorm();
  return e;
}

Vec3 FemPad::momentum() const {
  const FemSolid& s = *solid_;
  Vec3 p = Vec3::Zero();
  for (std::size_t n = 0; n < s.masses().size(); ++n) p += s.masses()[n] * s.velocities()[n];
  return p;
}

}  // namespace gf::sim
