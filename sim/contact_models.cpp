#include "sim/detail/contact_models.hpp"

namespace gf::sim {
namespace {

// addPointRows' torsion for a god-finger patch: from its points (patchTorsion).
constexpr double kTorsionFromPoints = -1.0;

// The true contact's share of the contact's load, stiffness and damping: the patch's centre
// share when the patch has points, else all of it.
double truthShare(const FingerContact& c) {
  return c.sgo_count > 0 ? c.record.patch.centre_share : 1.0;
}

// The contact's friction block before its rows: its bodies, normal, friction (the finger's
// effective coefficient) and last step's impulses.
FrictionBlock frictionBlock(const ContactToSolve& in) {
  const FingerContact& c = in.contact;
  FrictionBlock block;
  block.proxy = in.proxy;
  block.object = c.truth.object;
  block.normal = c.truth.outward_normal_world;
  block.friction = in.settings.patch.friction;
  if (in.memory) {
    block.warm_force = in.memory->friction_force;
    block.warm_torque = in.memory->friction_torque;
    block.warm_rolling = in.memory->rolling_impulse;
  }
  return block;
}

// Points solver: each patch point's material (its share of the stiffness and damping, no
// friction of its own) and warm start (its radial's impulses by angle); returns the load's
// centre, the share-weighted sum of the true contact and the points.
btVector3 preparePatchPoints(const ContactToSolve& in, double truth_share) {
  FingerContact& c = in.contact;
  const ContactMemory* mem = in.memory;
  const int n = in.settings.patch.n_sgo;
  btVector3 centre = truth_share * c.truth.point_world;
  for (int i = 0; i < c.sgo_count; ++i) {
    const Sgo& p = injectedPoint(c.record.patch, i);
    c.sgo_material[i] = {in.stiffness * p.load_share, in.damping * p.load_share, 0.0};
    c.sgo_warm[i] = mem && layerOf(p) < mem->layer_count
                        ? warmStartByAngle(mem->layers[layerOf(p)].data(), mem->n_sgo, p.radial, n)
                        : WarmStart{};
    centre += p.load_share * c.sgo_world[i];
  }
  return centre;
}

// The load's centre moved onto the contact's tangent plane: on a curved body the points'
// centroid lies inside it, and friction acts on the surface.
btVector3 onTangentPlane(const btVector3& centre, const TrueContact& truth) {
  const btVector3 off = centre - truth.point_world;
  const btVector3& n = truth.outward_normal_world;
  return truth.point_world + off - off.dot(n) * n;
}

// The points an aggregate block stands for, into `out` (the true contact first): as in the
// points solver only the points that press (depth <= 0) push; while none presses (within the
// release gap) all of them do, speculatively. Returns how many and the sum of their shares,
// and where the rim's SGOs among them are.
struct Pressing {
  int count = 0;
  double share = 0.0;
  bool all = false;    // none pressed: all points are in
  int first_sgo = 0;   // the first SGO's index (1 when the true contact is in)
  int rim = 0;         // rim SGOs in (they come first among the SGOs)
};
Pressing pressingPoints(const FingerContact& c, double truth_share, AggregateScratch& out) {
  Pressing p;
  const auto add = [&](const btVector3& point, double share, double separation) {
    const auto i = static_cast<std::size_t>(p.count);
    out.points[i] = point;
    out.shares[i] = share;
    out.separations[i] = separation;
    ++p.count;
    p.share += share;
  };
  for (int pass = 0; pass < 2 && !(p.share > 0.0); ++pass) {
    const bool all = pass == 1;
    p = {};
    p.all = all;
    if (all || c.truth.separation <= 0.0) add(c.truth.point_world, truth_share, c.truth.separation);
    p.first_sgo = p.count;
    const int rim = static_cast<int>(c.record.patch.sgos.size());
    for (int i = 0; i < c.sgo_count; ++i) {
      if (all || c.sgo_separation[i] <= 0.0) {
        add(c.sgo_world[i], injectedPoint(c.record.patch, i).load_share, c.sgo_separation[i]);
        p.rim += i < rim;
      }
    }
  }
  return p;
}

// The block's points, whose normal impulses limit its friction: the true contact's kept manifold
// point, then the injected points.
void addBlockPoints(const ContactToSolve& in, SolveRows& out) {
  const FingerContact& c = in.contact;
  const bool proxy_is_a = c.manifold->getBody0() == in.proxy;
  out.solver.addPoint({&c.manifold->getContactPoint(0), proxy_is_a});
  for (int i = 0; i < c.sgo_count; ++i) {
    const auto m = static_cast<std::size_t>(c.first_injected + i / MANIFOLD_CACHE_SIZE);
    out.solver.addPoint({&out.injected[m]->getContactPoint(i % MANIFOLD_CACHE_SIZE), true});
  }
}

// A patch's torsion limit per unit normal impulse (m): mu times its pressing points' mean lever
// about the load's centre, weighted by their load shares, as the aggregate block takes it. Not
// from the points' solved impulses: damping on their normal rows turns a tilt wobble into push
// and pull, the clamp at zero keeps only the push, and load moved to the rim raised the limit
// by up to 13 % while the body spun.
double patchTorsion(const FingerContact& c, const FrictionBlock& block, AggregateScratch& s) {
  const Pressing p = pressingPoints(c, truthShare(c), s);
  double lever = 0.0;
  for (int i = 0; i < p.count; ++i) {
    const btVector3 r = s.points[static_cast<std::size_t>(i)] - block.centre;
    lever += s.shares[static_cast<std::size_t>(i)] * (r - r.dot(block.normal) * block.normal).length();
  }
  return p.share > 0.0 ? block.friction * lever / p.share : 0.0;
}

// A patch's rolling limit per unit normal impulse (m): its rim's mean lever about the load's
// centre, over the rim points that press (all of them while none does). The pressure can move
// as far as the rim, and no further.
double patchRolling(const FingerContact& c, const FrictionBlock& block) {
  const std::size_t rim = c.record.patch.sgos.size();
  for (int pass = 0; pass < 2; ++pass) {
    double lever = 0.0;
    int count = 0;
    for (std::size_t i = 0; i < rim; ++i) {
      if (pass == 0 && !(c.sgo_separation[i] <= 0.0)) continue;
      const btVector3 r = c.sgo_world[i] - block.centre;
      lever += (r - r.dot(block.normal) * block.normal).length();
      ++count;
    }
    if (count > 0) return lever / count;
  }
  return 0.0;
}

// The mean of x[0 .. count), summed in order.
double meanOf(const double* x, int count) {
  double sum = 0.0;
  for (int i = 0; i < count; ++i) sum += x[i];
  return sum / count;
}

// Points solver: the true contact and the patch's points are contact rows of Bullet's solver,
// each with its share of the stiffness and damping (by load share) and no friction of its own;
// the contact's friction is one block at the load's centre with the model's `torsion` limit,
// and for a god-finger patch (`rolling`) rolling rows limited by its rim (patchRolling).
void addPointRows(const ContactToSolve& in, double torsion, bool rolling, SolveRows& out) {
  FingerContact& c = in.contact;
  const double share = truthShare(c);
  FrictionBlock block = frictionBlock(in);
  c.aggregate = false;
  keepOnlyPoint(*c.manifold, c.truth.index, {in.stiffness * share, in.damping * share, 0.0},
                in.memory ? in.memory->truth : WarmStart{});
  const btVector3 centre = preparePatchPoints(in, share);
  if (c.sgo_count > 0) {
    c.first_injected = static_cast<int>(out.injected.size());
    injectPoints(out.dispatcher, in.proxy, c.truth.object, c.sgo_world.data(), c.sgo_count,
                 c.truth.outward_normal_world, c.sgo_separation.data(), c.sgo_material.data(),
                 c.sgo_warm.data(), out.injected);
  }
  block.centre = onTangentPlane(centre, c.truth);
  block.torsion = torsion == kTorsionFromPoints ? patchTorsion(c, block, out.scratch) : torsion;
  block.rolling = rolling && c.sgo_count > 0 ? patchRolling(c, block) : 0.0;
  c.block = out.solver.addBlock(block);
  addBlockPoints(in, out);
}

// Aggregate solver: one block whose normal and tilt rows the pressing points make, with their
// share of the stiffness and damping, and the same rolling rows as the points solver's; the
// manifold keeps no point for Bullet's own rows.
void addAggregateRows(const ContactToSolve& in, SolveRows& out) {
  FingerContact& c = in.contact;
  FrictionBlock block = frictionBlock(in);
  c.aggregate = true;
  AggregateScratch& s = out.scratch;
  const Pressing p = pressingPoints(c, truthShare(c), s);
  for (int i = 0; i < p.count; ++i) s.shares[static_cast<std::size_t>(i)] /= p.share;
  c.manifold->clearManifold();
  block.aggregate = true;
  aggregatePatch(s.points.data(), s.shares.data(), s.separations.data(), p.count, block.normal,
                 c.truth.point_world, in.stiffness * p.share, in.damping * p.share, block.centre,
                 block.press, s.levers.data());
  block.torsion = block.friction * block.press.mean_lever;
  // The rim's pressing SGOs' levers are patchRolling's (the same points, centre and normal).
  block.rolling = !p.all && p.rim > 0 ? meanOf(s.levers.data() + p.first_sgo, p.rim) : patchRolling(c, block);
  if (in.memory) {
    block.press.warm_normal = in.memory->normal_impulse;
    block.press.warm_tilt = in.memory->tilt_impulse;
  }
  c.block = out.solver.addBlock(block);
}

}  // namespace

void GodObjectModel::addRows(const ContactToSolve& c, SolveRows& out) const {
  addPointRows(c, 0.0, false, out);  // no torsion limit: a point turns freely
}

void SoftFingerModel::addRows(const ContactToSolve& c, SolveRows& out) const {
  addPointRows(c, c.settings.patch.torsional_friction, false, out);  // 0 without the friction effect
}

void GodFingerModel::addRows(const ContactToSolve& c, SolveRows& out) const {
  if (c.contact.sgo_count > 0 && c.settings.solver == ContactSolver::kAggregate) {
    addAggregateRows(c, out);
  } else {
    addPointRows(c, c.settings.friction_effect ? kTorsionFromPoints : 0.0, true, out);
  }
}

const FingerModel& fingerModel(ContactModel model) {
  static const GodObjectModel god_object;
  static const SoftFingerModel soft_finger;
  static const GodFingerModel god_finger;
  switch (model) {
    case ContactModel::kGodObject: return god_object;
    case ContactModel::kSoftFinger: return soft_finger;
    case ContactModel::kGodFinger: return god_finger;
  }
  return god_object;
}

}  // namespace gf::sim
