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
  solid_->addPartner(skin_nodes_);
  nodes_ = std::make_unique<NodeContacts>(static_cast<int>(mesh_.nodes.size()), *skin_);
}

FemPad::~FemPad() = default;

void FemPad::follow(const Vec3& centre, const Vec3& velocity) {
  if (!(centre.allFinite() && velocity.allFinite())) return;
  solid_->moveBone(centre - centre0_, velocity);
}

void FemPad::step(double dt, const Vec3& bone_force, double friction, const PadSurfaces& surfaces) {
  nodes_->find(solid_->positions(), skin_nodes_, boneCentre(), surfaces, friction, false, fem_contacts_);
  nodes_->choosePartner(*solid_, 0, surfaces, fem_contacts_);
  solid_->keepState();
  solid_->step(dt, {}, bone_force, fem_contacts_);
  bool finite = solid_->boneOffset().allFinite() && solid_->boneVelocity().allFinite();
  for (const Vec3& p : solid_->positions()) finite = finite && p.allFinite();
  const int inverted = finite ? solid_->invertedElements() : 0;
  if (finite && inverted == 0) {
    nodes_->read(dt, *solid_, fem_contacts_, surfaces, settings_.contact_stiffness);
    reset_last_step_ = false;
    return;
  }
  nodes_->clear();  // the step is undone: its forces with it
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
}

// Every node inside a surface put on it (a pad put back at rest where its bone is pressed in
// would start deep in the body, its springs a kick): it starts flattened instead.
void FemPad::liftOut(const PadSurfaces& surfaces) {
  std::vector<Vec3>& x = solid_->positions();
  double depth = 0.0;
  Vec3 normal = Vec3::UnitY();
  for (int n : skin_nodes_) {
    Vec3& p = x[static_cast<std::size_t>(n)];
    for (int b : nodes_->nearBodies()) {
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
