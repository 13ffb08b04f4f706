// The contact pipeline of a World, between Bullet's collision detection and its solve: each
// proxy's manifolds gathered into one contact per touched body, the contact recorded in the
// body's frame, its god-finger patch when the finger's model wants one, its rows added by the
// model; after the solve, the impulses remembered to warm-start the next step.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <utility>

#include "sim/assert.hpp"
#include "sim/world/world_impl.hpp"

namespace gf::sim {
namespace {

// A patch starts when the proxy touches (separation <= 0) and lasts while the separation stays
// below this (m): a few micrometres of gap in one step do not drop the contact area.
constexpr double kPatchReleaseGap = 1e-4;
// The pad plane keeps the orientation the finger met the body with (the proxy does not turn)
// while the contact normal stays within this angle of it (rad), and follows beyond: a tilt of
// the body loads one side of the pad, a finger moved around a curved body keeps its pad on it.
constexpr double kPadFollowAngle = 0.2617993877991494;  // 15 degrees

// The pad plane's normal this step (world): last step's while the contact normal `n` stays
// within kPadFollowAngle of it, else turned towards n to that angle; n for a new patch.
Vec3 padNormal(const Vec3& n, const ContactMemory* mem) {
  Vec3 pad = mem && mem->had_patch ? mem->pad_normal : n;
  if (pad.dot(n) < std::cos(kPadFollowAngle)) {
    const Vec3 across = pad - pad.dot(n) * n;
    pad = across.norm() > 1e-12 ? Vec3(std::cos(kPadFollowAngle) * n + std::sin(kPadFollowAngle) * across.normalized()) : n;
  }
  return pad;
}

// The 6-DOF pad's outward normal in the body frame (`to_local` turns world into body): the
// device's orientation applied to the finger's pad_axis; zero for the disc pad model.
Vec3 padNormalLocal(const PatchSettings& s, const Quat& device, const btMatrix3x3& to_local) {
  if (s.pad_model != PadModel::kOriented) return Vec3::Zero();
  return toEigen(to_local * toBt(device * s.pad_axis.normalized()));
}

}  // namespace

void World::Impl::beforeSolve() {
  for (Finger& f : fingers) f.contact_count = 0;
  solver.clearBlocks();
  const int n = dispatcher.getNumManifolds();  // injected manifolds are appended after these
  for (int i = 0; i < n; ++i) {
    btPersistentManifold& m = *dispatcher.getManifoldByIndexInternal(i);
    const btCollisionObject* b0 = m.getBody0();
    const btCollisionObject* b1 = m.getBody1();
    if (b0->getUserIndex() == kProxyTag) gatherProxyManifold(m, b0);
    else if (b1->getUserIndex() == kProxyTag) gatherProxyManifold(m, b1);
  }
  // Every contact's patch first, then the overlaps between them, then the models' rows.
  for (Finger& f : fingers) {
    for (int k = 0; k < f.contact_count; ++k) handleContact(f, f.contacts[k]);
  }
  handleOverlaps();
  for (Finger& f : fingers) {
    const FingerDesc& fd = desc.fingers[static_cast<std::size_t>(&f - fingers.data())];
    for (int k = 0; k < f.contact_count; ++k) {
      FingerContact& c = f.contacts[k];
      f.model->addRows({c, f.memoryOf(c.truth.object->getUserIndex()), f.settings, f.proxy.get(),
                        fd.proxy.contact_stiffness, fd.proxy.contact_damping}, rows);
      counters.sgos_injected += c.sgo_count;
    }
  }
}

void World::Impl::afterSolve() {
  for (Finger& f : fingers) rememberImpulses(f);
  releaseInjected(dispatcher, injected);
}

// Groups the manifolds of a proxy by touched body: the deepest point of all of them is the
// finger's contact with that body; the other manifolds are emptied for this step.
void World::Impl::gatherProxyManifold(btPersistentManifold& m, const btCollisionObject* proxy) {
  const int finger = proxy->getUserIndex2();
  Finger& f = fingers[finger];
  TrueContact truth;
  if (!deepestContact(m, proxy, truth)) return;
  const int body = truth.object->getUserIndex();
  for (int k = 0; k < f.contact_count; ++k) {
    FingerContact& c = f.contacts[k];
    if (c.truth.object->getUserIndex() != body) continue;
    if (truth.separation < c.truth.separation) {
      c.manifold->clearManifold();
      c.truth = truth;
      c.manifold = &m;
    } else {
      m.clearManifold();
    }
    return;
  }
  if (f.contact_count == kMaxContactsPerFinger) {  // beyond the tracked contacts: a plain point
    const FingerDesc& fd = desc.fingers[finger];
    keepOnlyPoint(m, truth.index, {fd.proxy.contact_stiffness, fd.proxy.contact_damping,
                                   f.settings.patch.friction}, {});
    return;
  }
  FingerContact& c = f.contacts[f.contact_count++];
  c.truth = truth;
  c.manifold = &m;
}

// One contact: recorded in the body's frame, and its patch if the finger's model wants one (a
// patch starts on touching and survives a small gap, kPatchReleaseGap); beforeSolve adds the
// model's rows once every contact has its patch.
void World::Impl::handleContact(Finger& f, FingerContact& c) {
  const ContactMemory* mem = f.memoryOf(c.truth.object->getUserIndex());
  // The walks carried from the body's last contact with this finger (swapped back after).
  if (mem) {
    std::swap(c.walks, f.memory_walks[static_cast<std::size_t>(mem - f.memory.data())]);
  } else {
    c.walks.valid = false;
  }
  c.sgo_count = 0;
  recordContact(f, mem, c);
  const bool touching = c.truth.separation <= 0.0 ||
                        (mem && mem->had_patch && c.truth.separation <= kPatchReleaseGap);
  if (f.model->wantsPatch() && touching) {
    computeContactPatch(f, c, mem);
  } else {
    c.walks.valid = false;
  }
}

// The contact in the touched body's frame (the frame of its walk mesh), with the press depth
// of Eq. 1 and the ring's reference carried from the last step; no patch yet.
void World::Impl::recordContact(const Finger& f, const ContactMemory* mem, FingerContact& c) const {
  const btTransform& t = c.truth.object->getWorldTransform();
  const btMatrix3x3 to_local = t.getBasis().transpose();
  const btVector3 v_world = toBt(f.device.position) - f.proxy->getCenterOfMassPosition();
  c.v_local = toEigen(to_local * v_world);
  ContactRecord& r = c.record;
  r.body = c.truth.object->getUserIndex();
  r.contact = {toEigen(t.invXform(c.truth.point_world)), toEigen(to_local * c.truth.outward_normal_world),
               c.truth.separation, bodies[r.body].shapes.rounding,
               mem ? mem->ring_tangent_local : Vec3::Zero(), padNormalLocal(f.settings.patch, f.device.orientation, to_local)};
  r.press_depth = pressDepth(c.v_local, r.contact.outward_normal_local.normalized());
  clearPatch(r.patch);
}

// The patch of a god-finger contact (timed and counted), then its points in the world.
void World::Impl::computeContactPatch(const Finger& f, FingerContact& c, const ContactMemory* mem) {
  ContactRecord& r = c.record;
  const Mesh& mesh = *bodies[r.body].shapes.walk_mesh;
  const auto start = std::chrono::steady_clock::now();
  const long warm_before = c.walks.warm_walks, cold_before = c.walks.cold_walks, slack_before = c.walks.slack_walks;
  computePatch(mesh, r.contact, c.v_local, f.settings.patch, r.patch, &c.walks);
  counters.patch_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ++counters.patch_calls;
  counters.warm_walks += c.walks.warm_walks - warm_before;
  counters.cold_walks += c.walks.cold_walks - cold_before;
  counters.slack_walks += c.walks.slack_walks - slack_before;
  if (check_walks) checkWalks(mesh, f, c);
  if (!r.patch.valid) {
    ++counters.invalid_patches;
    return;
  }
  placePatchPoints(c, mem);
}

// checkWarmWalks: the contact's patch from scratch, and the largest distance between its points
// (SGOs, filled points and the walks' path points) and the patch's.
void World::Impl::checkWalks(const Mesh& mesh, const Finger& f, FingerContact& c) {
  placePendingCrossings(c.walks, c.record.patch);
  const Patch& warm = c.record.patch;
  computePatch(mesh, c.record.contact, c.v_local, f.settings.patch, check_patch);
  ++counters.walk_checks;
  double& worst = counters.walk_check_error;
  if (warm.sgos.size() != check_patch.sgos.size() || warm.inner.size() != check_patch.inner.size() ||
      warm.path_points.size() != check_patch.path_points.size()) {
    worst = std::numeric_limits<double>::infinity();
    return;
  }
  for (std::size_t k = 0; k < warm.sgos.size(); ++k) {
    worst = std::max(worst, (warm.sgos[k].position - check_patch.sgos[k].position).norm());
  }
  for (std::size_t k = 0; k < warm.inner.size(); ++k) {
    worst = std::max(worst, (warm.inner[k].position - check_patch.inner[k].position).norm());
  }
  for (std::size_t k = 0; k < warm.path_points.size(); ++k) {
    worst = std::max(worst, (warm.path_points[k] - check_patch.path_points[k]).norm());
  }
}

// A patch's points in the world and their depths. Every point has the contact's depth (the
// paper, Sec. 3.2) while the body's surface keeps the orientation the finger met it with; a
// tilt of the surface since (the contact normal turned from the pad's normal, which the proxy,
// not turning, keeps) deepens the points on one side and lifts the others by their offset along
// the turn, so the pad pushes back. Beyond kPadFollowAngle the pad turns with the surface: a
// finger moved around a curved body keeps its pad on it.
void World::Impl::placePatchPoints(FingerContact& c, const ContactMemory* mem) {
  const Vec3 pad = padNormal(toEigen(c.truth.outward_normal_world), mem);
  c.pad_normal = pad;
  const btTransform& t = c.truth.object->getWorldTransform();
  const btVector3 tilt = toBt(pad) - c.truth.outward_normal_world;
  const auto place = [&](const Sgo& p) {
    const int i = c.sgo_count++;
    c.sgo_world[i] = t * toBt(p.position);
    c.sgo_separation[i] = c.truth.separation - (c.sgo_world[i] - c.truth.point_world).dot(tilt);
    counters.crossing_limit_stops += p.stop == WalkStop::kCrossingLimit;
  };
  for (const Sgo& p : c.record.patch.sgos) place(p);
  for (const Sgo& p : c.record.patch.inner) place(p);
}

// What each contact leaves for the next step (ContactMemory): its points' and its block's
// solved impulses, the ring's frame and the pad's normal; and what snapshots need to split its
// loads over its points (keepSolved).
void World::Impl::rememberImpulses(Finger& f) {
  const PatchSettings& s = f.settings.patch;
  f.memory_count = f.contact_count;
  for (int k = 0; k < f.contact_count; ++k) {
    FingerContact& c = f.contacts[k];
    GF_ASSERT(c.manifold != nullptr && "impulses are read between beforeSolve and afterSolve only");
    ContactMemory& mem = f.memory[k];
    const Patch& patch = c.record.patch;
    mem.body = c.record.body;
    mem.truth = c.aggregate ? WarmStart{} : solvedImpulses(c.manifold->getContactPoint(0));
    mem.had_patch = c.sgo_count > 0;
    mem.n_sgo = c.sgo_count > 0 && !c.aggregate ? s.n_sgo : 0;
    mem.ring_tangent_local = patch.ring_tangent;
    mem.pad_normal = c.pad_normal;
    std::swap(f.memory_walks[static_cast<std::size_t>(k)], c.walks);
    // Only the radials of the layers this patch has are read back (warmStartByAngle).
    mem.layer_count = mem.n_sgo > 0 ? (s.fill == PatchFill::kFilled ? s.rings : 1) : 0;
    for (int l = 0; l < mem.layer_count; ++l) std::fill_n(mem.layers[l].begin(), mem.n_sgo, WarmStart{});
    for (int i = 0; i < c.sgo_count && !c.aggregate; ++i) {
      const Sgo& p = injectedPoint(patch, i);
      mem.layers[layerOf(p)][p.radial] = solvedImpulses(injected, c.first_injected, i);
    }
    const FrictionBlock& block = solver.block(c.block);
    mem.friction_force = block.solved ? block.force : btVector3(0, 0, 0);
    mem.friction_torque = block.solved ? block.torque : 0.0;
    mem.rolling_impulse = block.solved ? block.rolling_impulse : btVector3(0, 0, 0);
    mem.normal_impulse = block.solved ? block.normal_impulse : 0.0;
    mem.tilt_impulse = block.solved && block.aggregate ? block.press.tilt : btVector3(0, 0, 0);
    mem.anchor = anchorToKeep(c, block);
    keepSolved(c, injected, world.getSolverInfo().m_timeStep);
    c.manifold = nullptr;  // Bullet may free it at the next collision pass
    c.truth.object = nullptr;
  }
}

}  // namespace gf::sim
