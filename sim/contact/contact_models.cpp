#include "sim/contact/contact_models.hpp"

#include <algorithm>
#include <cmath>

#include "sim/contact/bullet_math.hpp"
#include "sim/patch/patch_ring.hpp"

namespace gf::sim {
namespace {

// A block is at its friction limit when its force and torsion lie on the limit ellipse within
// this fraction: the block's projection puts them there up to rounding, while a sticking
// contact stays well inside.
constexpr double kLimitMargin = 1e-3;
// In a sliding contact a point slips when its friction is at least this share of mu times its
// load: all of them while the contact slides or spins, all but those near the centre of its
// turn when it does both (where the two parts cancel).
constexpr double kSlipFraction = 0.5;
// A point closer than this to the loads' centre across the normal is the centre itself: it
// takes no part of the torsion (m).
constexpr double kCentreLever = 1e-9;
// Loads whose second moment's determinant about the tangent axes is below this share of its
// trace squared lie on one point or one line: no pressure moment is put into them.
constexpr double kCollinear = 1e-9;
// addPressureMoment's passes: at most this many, until the moment is made within this share.
constexpr int kPressurePasses = 8;
constexpr double kPressureTolerance = 1e-6;

// A contact whose proxy side slid further than this from its anchor since it started sticking
// has slid (m): it anchors afresh where it is. A sticking contact's slip is micrometres.
constexpr double kAnchorReach = 1e-3;
// Likewise a contact whose body turned further than this against the proxy (rad).
constexpr double kAnchorTurn = 0.02;

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

// The block's anchor (FrictionAnchor): last step's slip and turn while the contact kept
// sticking (within kAnchorReach and kAnchorTurn), none for a new contact or after a slide.
void anchorBlock(const ContactToSolve& in, FrictionBlock& block) {
  FrictionAnchor a = in.memory ? in.memory->anchor : FrictionAnchor{};
  if (a.set) a.slip -= a.slip.dot(block.normal) * block.normal;
  if (!a.set || !(a.slip.length() <= kAnchorReach) || !(std::abs(a.turn) <= kAnchorTurn)) a = FrictionAnchor{};
  in.contact.anchor = a;
  block.slip = a.slip;
  block.turn_slip = a.turn;
  block.anchor_stiffness = in.stiffness;
  block.anchor_damping = in.damping;
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
  const auto add = [&](const btVector3& point, double share, double separation, int which) {
    const auto i = static_cast<std::size_t>(p.count);
    out.points[i] = point;
    out.shares[i] = share;
    out.separations[i] = separation;
    out.which[i] = which;
    ++p.count;
    p.share += share;
  };
  for (int pass = 0; pass < 2 && !(p.share > 0.0); ++pass) {
    const bool all = pass == 1;
    p = {};
    p.all = all;
    if (all || c.truth.separation <= 0.0) add(c.truth.point_world, truth_share, c.truth.separation, -1);
    p.first_sgo = p.count;
    const int rim = static_cast<int>(c.record.patch.sgos.size());
    for (int i = 0; i < c.sgo_count; ++i) {
      if (all || c.sgo_separation[i] <= 0.0) {
        add(c.sgo_world[i], injectedPoint(c.record.patch, i).load_share, c.sgo_separation[i], i);
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
// by up to 13 % while the body spun. Also sets the block's twist_moment from the same points.
double patchTorsion(const FingerContact& c, FrictionBlock& block, AggregateScratch& s) {
  const Pressing p = pressingPoints(c, truthShare(c), s);
  double lever = 0.0, moment = 0.0;
  for (int i = 0; i < p.count; ++i) {
    const btVector3 r = s.points[static_cast<std::size_t>(i)] - block.centre;
    const double arm = (r - r.dot(block.normal) * block.normal).length();
    lever += s.shares[static_cast<std::size_t>(i)] * arm;
    moment += s.shares[static_cast<std::size_t>(i)] * arm * arm;
  }
  block.twist_moment = moment;
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
  anchorBlock(in, block);
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
  anchorBlock(in, block);
  block.torsion = block.friction * block.press.mean_lever;
  // The points' shares were scaled to sum to 1: the moment is over the contact's stiffness.
  double moment = 0.0;
  for (int i = 0; i < p.count; ++i) {
    const auto k = static_cast<std::size_t>(i);
    moment += s.shares[k] * s.levers[k] * s.levers[k];
  }
  block.twist_moment = p.share * moment;
  // The rim's pressing SGOs' levers are patchRolling's (the same points, centre and normal).
  block.rolling = !p.all && p.rim > 0 ? meanOf(s.levers.data() + p.first_sgo, p.rim) : patchRolling(c, block);
  if (in.memory) {
    block.press.warm_normal = in.memory->normal_impulse;
    block.press.warm_tilt = in.memory->tilt_impulse;
  }
  c.block = out.solver.addBlock(block);
}

// The position of point j of a contact: 0 the true contact, 1 + i its patch point i.
btVector3 pointOf(const FingerContact& c, int j) {
  return j == 0 ? c.truth.point_world : c.sgo_world[static_cast<std::size_t>(j - 1)];
}

// How the block's friction moment about the normal is split over the points with normal
// impulses `lambda` (N s, summing to `normal`): the loads' centre, the moment about n there
// (the torsion row's and the friction force's lever from the block's centre, N m s, body
// side), and for torsionImpulse L = sum_j lambda_j |r_j| and the loads' mean unit lever m.
struct TorsionSplit {
  btVector3 centre{0, 0, 0};
  double torsion = 0.0;
  double levers = 0.0;
  btVector3 mean{0, 0, 0};
};

// r_j: point j's lever from `centre` across n.
btVector3 leverAcross(const FingerContact& c, int j, const btVector3& centre, const btVector3& n) {
  const btVector3 r = pointOf(c, j) - centre;
  return r - r.dot(n) * n;
}

btVector3 unitLever(const FingerContact& c, int j, const btVector3& centre, const btVector3& n) {
  const btVector3 r = leverAcross(c, j, centre, n);
  return r.length() > kCentreLever ? r / r.length() : btVector3(0, 0, 0);
}

TorsionSplit torsionSplit(const FingerContact& c, const FrictionBlock& block, const double* lambda, double normal) {
  const btVector3& n = block.normal;
  TorsionSplit t;
  t.centre = c.truth.point_world;
  if (!(normal > 0.0)) return t;
  t.centre.setZero();
  for (int j = 0; j <= c.sgo_count; ++j) t.centre += (lambda[j] / normal) * pointOf(c, j);
  t.torsion = -block.torque + n.dot((block.centre - t.centre).cross(-block.force));
  for (int j = 0; j <= c.sgo_count; ++j) {
    t.levers += lambda[j] * leverAcross(c, j, t.centre, n).length();
    t.mean += (lambda[j] / normal) * unitLever(c, j, t.centre, n);
  }
  return t;
}

// Point j's part of the torsion (N s, body side): torsion lambda_j / L along n x (u_j - m), u_j
// its unit lever: each point mu lambda_j across its lever at the limit, as in a patch spinning
// about its centre, less the mean direction m that would leave a net force.
btVector3 torsionImpulse(const FingerContact& c, const FrictionBlock& block, const TorsionSplit& t, const double* lambda, int j) {
  if (!(t.levers > 0.0)) return btVector3(0, 0, 0);
  const btVector3& n = block.normal;
  return (t.torsion * lambda[j] / t.levers) * n.cross(unitLever(c, j, t.centre, n) - t.mean);
}

// One pass of addPressureMoment: d_j = w_j (u_j . g) with w_j = lambda_j / N, u_j = (x_j - c) x n
// about the loads' centre c and S g = `moment` (tangent plane, basis t1, t2), S their second
// moment sum_j w_j u_j u_j^T; then clamped at zero and scaled back to N. False when the loads
// lie on one point or one line (nothing to tilt).
bool tiltPass(const FingerContact& c, const btVector3& n, const btVector3& t1, const btVector3& t2,
              const btVector3& moment, double normal, double* lambda) {
  btVector3 centre(0, 0, 0);
  for (int j = 0; j <= c.sgo_count; ++j) centre += (lambda[j] / normal) * pointOf(c, j);
  double s11 = 0.0, s12 = 0.0, s22 = 0.0;
  for (int j = 0; j <= c.sgo_count; ++j) {
    const btVector3 u = (pointOf(c, j) - centre).cross(n);
    const double w = lambda[j] / normal, u1 = u.dot(t1), u2 = u.dot(t2);
    s11 += w * u1 * u1, s12 += w * u1 * u2, s22 += w * u2 * u2;
  }
  const double m1 = moment.dot(t1), m2 = moment.dot(t2), det = s11 * s22 - s12 * s12;
  if (!(det > kCollinear * (s11 + s22) * (s11 + s22))) return false;
  const double g1 = (s22 * m1 - s12 * m2) / det, g2 = (s11 * m2 - s12 * m1) / det;
  double sum = 0.0;
  for (int j = 0; j <= c.sgo_count; ++j) {
    const btVector3 u = (pointOf(c, j) - centre).cross(n);
    lambda[j] = std::max(0.0, lambda[j] + lambda[j] / normal * (u.dot(t1) * g1 + u.dot(t2) * g2));
    sum += lambda[j];
  }
  if (!(sum > 0.0)) return false;
  std::for_each(lambda, lambda + c.sgo_count + 1, [&](double& l) { l *= normal / sum; });
  return true;
}

// The moment about the tangent axes (N m s, pressing rows' side) the points' normal impulses
// must make about `centre` besides the solver's `moment`: the points carry the friction at
// their loads' centre instead of the block's centre and the torsion at their depths (on a
// curved body both lie inside the tangent plane), and the pressure makes up the difference.
btVector3 pressureTarget(const FingerContact& c, const FrictionBlock& block, const btVector3& moment, const double* lambda,
                         double normal) {
  const btVector3& n = block.normal;
  const TorsionSplit t = torsionSplit(c, block, lambda, normal);
  btVector3 target = moment + (block.centre - t.centre).cross(block.force);
  for (int j = 0; j <= c.sgo_count; ++j) {
    const double depth = (pointOf(c, j) - t.centre).dot(n);
    target += depth * n.cross(torsionImpulse(c, block, t, lambda, j));
  }
  return target - target.dot(n) * n;
}

// Shifts the points' normal impulses `lambda` (tiltPass) until, about their first centre, they
// make `moment` (N m s, the pressing rows' side: the body takes -moment) and pressureTarget's
// rest, keeping their sum: where a pass would pull a point (the moment is near what the
// points' hull can carry) the load moves to the far side over the next passes.
void addPressureMoment(const FingerContact& c, const FrictionBlock& block, const btVector3& moment, double* lambda) {
  const btVector3& n = block.normal;
  double normal = 0.0;
  for (int j = 0; j <= c.sgo_count; ++j) normal += lambda[j];
  if (!(normal > 0.0)) return;
  btVector3 centre(0, 0, 0);
  for (int j = 0; j <= c.sgo_count; ++j) centre += (lambda[j] / normal) * pointOf(c, j);
  btVector3 t1, t2;
  btPlaneSpace1(n, t1, t2);
  for (int pass = 0; pass < kPressurePasses; ++pass) {
    btVector3 made(0, 0, 0);
    for (int j = 0; j <= c.sgo_count; ++j) made += lambda[j] * (pointOf(c, j) - centre).cross(n);
    const btVector3 target = pressureTarget(c, block, moment, lambda, normal);
    btVector3 deficit = target - made;
    deficit -= deficit.dot(n) * n;
    if (!(deficit.length() > kPressureTolerance * target.length())) return;
    if (!tiltPass(c, n, t1, t2, deficit, normal, lambda)) return;
  }
}

// The normal impulse on each of the contact's points (N s) into `lambda` (index 0 the true
// contact, 1 + i its patch point i), as solvedLoads describes; returns their sum.
double pointImpulses(const FingerContact& c, const FrictionBlock& block, AggregateScratch& s, double* lambda) {
  std::fill_n(lambda, c.sgo_count + 1, 0.0);
  btVector3 moment(0, 0, 0);  // the pressing rows' moment the points' own impulses do not make
  if (!c.aggregate) {
    for (int j = 0; j <= c.sgo_count; ++j) lambda[j] = std::max(0.0, c.solved.normal[static_cast<std::size_t>(j)]);
  } else {
    const Pressing p = pressingPoints(c, truthShare(c), s);
    for (int j = 0; j < p.count; ++j) {
      const auto k = static_cast<std::size_t>(j);
      lambda[s.which[k] + 1] = s.shares[k] / p.share * std::max(0.0, block.normal_impulse);
    }
    moment = block.press.tilt;
  }
  addPressureMoment(c, block, moment, lambda);
  double sum = 0.0;
  for (int j = 0; j <= c.sgo_count; ++j) sum += lambda[j];
  return sum;
}

// Whether the block's friction is at its limit: (|f| / (mu N))^2 + (tau / (tau_max N))^2 = 1.
bool atFrictionLimit(const FrictionBlock& block) {
  const double normal = block.normal_impulse;
  if (!block.solved || !(block.friction > 0.0) || !(normal > 0.0)) return false;
  double gauge = std::pow(block.force.length() / (block.friction * normal), 2);
  if (block.torsion > 0.0) gauge += std::pow(block.torque / (block.torsion * normal), 2);
  return gauge >= (1.0 - kLimitMargin) * (1.0 - kLimitMargin);
}

}  // namespace

void keepSolved(FingerContact& c, const std::vector<btPersistentManifold*>& injected, double dt) {
  c.solved.dt = dt;
  c.solved.body_basis = c.truth.object->getWorldTransform().getBasis();
  if (c.aggregate) return;
  c.solved.normal[0] = c.manifold->getContactPoint(0).m_appliedImpulse;
  for (int i = 0; i < c.sgo_count; ++i) c.solved.normal[static_cast<std::size_t>(1 + i)] = solvedImpulses(injected, c.first_injected, i).normal;
}

FrictionAnchor anchorToKeep(const FingerContact& c, const FrictionBlock& block) {
  if (!block.solved) return FrictionAnchor{};
  FrictionAnchor a = c.anchor;
  a.set = true;
  a.slip += block.moved;
  a.turn += block.turned;
  // At its limit the contact turns about its normal, and slides too unless its friction force
  // is a small part of mu N (a patch whose points lift has a torsion limit of micrometres times
  // N, which a still press reaches while the force stays far inside its own).
  if (atFrictionLimit(block)) {
    a.turn = 0.0;
    if (!(block.force.length() < kSlipFraction * block.friction * block.normal_impulse)) a.slip.setZero();
  }
  return a;
}

void solvedLoads(const FingerContact& c, const FrictionBlock& block, AggregateScratch& s, ContactLoads& out) {
  const double dt = c.solved.dt;
  std::array<double, kMaxPatchPoints + 1> lambda;
  std::fill_n(lambda.begin(), c.sgo_count + 1, 0.0);
  const double normal = block.solved ? pointImpulses(c, block, s, lambda.data()) : 0.0;
  const btVector3& n = block.normal;
  const TorsionSplit t = torsionSplit(c, block, lambda.data(), normal);
  const btMatrix3x3 to_body = c.solved.body_basis.transpose();
  const bool sliding = atFrictionLimit(block);
  btVector3 total(0, 0, 0);
  out.points.resize(static_cast<std::size_t>(c.sgo_count));
  for (int j = 0; j <= c.sgo_count; ++j) {
    const double w = normal > 0.0 ? lambda[static_cast<std::size_t>(j)] / normal : (j == 0 ? 1.0 : 0.0);
    const btVector3 friction = block.solved ? (-w * block.force + torsionImpulse(c, block, t, lambda.data(), j)) / dt
                                            : btVector3(0, 0, 0);
    const double load = lambda[static_cast<std::size_t>(j)] / dt;
    total += friction - load * n;
    PointLoad& l = j == 0 ? out.point : out.points[static_cast<std::size_t>(j - 1)];
    l = {load, toEigen(to_body * friction), sliding && load > 0.0 && friction.length() >= kSlipFraction * block.friction * load};
  }
  out.force = toEigen(to_body * total);
  out.rolling_moment = block.solved ? toEigen(to_body * (-block.rolling_impulse / dt)) : Vec3::Zero();
  // torsionImpulse shares the torsion over the points' levers; with none (one point) it stays here.
  const bool unshared = block.solved && !(t.levers > 0.0);
  out.torsion_moment = unshared ? toEigen(to_body * ((t.torsion / dt) * n)) : Vec3::Zero();
  out.sliding = sliding;
}

void GodObjectModel::addRows(const ContactToSolve& c, SolveRows& out) const {
  addPointRows(c, 0.0, false, out);  // no torsion limit: a point turns freely
}

void SoftFingerModel::addRows(const ContactToSolve& c, SolveRows& out) const {
  // 0 without the friction effect; the 6-DOF pad scales the torsion radius like its ellipse.
  const PatchContact& pc = c.contact.record.contact;
  const PadEllipse pad = padEllipse(c.settings.patch, pc.pad_normal_local, pc.outward_normal_local.normalized());
  addPointRows(c, c.settings.patch.torsional_friction * padTorsionFactor(pad), false, out);
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
    case ContactModel::kFemPad: return god_object;  // the bone's own contacts (the pad is the World's: world_pad.cpp)
  }
  return god_object;
}

}  // namespace gf::sim
