// Contact models: what the solver sees of one finger's contact with one body. The World asks
// the finger's model (chosen once per change of its settings, fingerModel) whether the contact
// gets a god-finger patch, then lets it add the contact's rows: contact points with their shares
// of the stiffness and damping plus one friction block (points solver), or one aggregate block
// (sim/contact/patch_friction.hpp). The models are stateless; everything a contact needs comes
// in a ContactToSolve and goes out through SolveRows. Haptic thread. Internal to sim/.
#pragma once

#include <array>
#include <vector>

#include "sim/contact/finger_contact.hpp"
#include "sim/contact/patch_friction.hpp"
#include "sim/scene/effective_settings.hpp"

namespace gf::sim {

/// One finger contact as a model turns it into rows, during beforeSolve: the World has filled
/// its true contact and record and, when the model asked for a patch, its patch's points.
struct ContactToSolve {
  FingerContact& contact;             ///< the model sets its block, aggregate and injected points
  const ContactMemory* memory;        ///< last step's impulses of the finger on this body, or null
  const EffectiveSettings& settings;  ///< the finger's
  const btCollisionObject* proxy;     ///< the finger's proxy
  double stiffness;  ///< the proxy's contact stiffness, shared by the contact's points (N/m)
  double damping;    ///< the proxy's contact damping, shared likewise (N s/m)
};

/// An aggregate block's points, load shares and depths (the true contact first): storage the
/// World keeps so that building a block does not allocate.
struct AggregateScratch {
  std::array<btVector3, kMaxPatchPoints + 1> points;    ///< world (m)
  std::array<double, kMaxPatchPoints + 1> shares;       ///< of the load; sum to 1 once scaled
  std::array<double, kMaxPatchPoints + 1> separations;  ///< m, negative when pressing
  std::array<double, kMaxPatchPoints + 1> levers;       ///< m, from the load's centre across the normal
  std::array<int, kMaxPatchPoints + 1> which;           ///< the contact's point: -1 the true one, else i
};

/// Where models put the rows of this step's contacts (the World's, valid during beforeSolve).
struct SolveRows {
  PatchFrictionSolver& solver;  ///< friction and aggregate blocks, and the points of each block
  btDispatcher& dispatcher;     ///< makes the manifolds of injected points
  std::vector<btPersistentManifold*>& injected;  ///< injected manifolds, released after the solve
  AggregateScratch& scratch;
};

/// A contact model as the World asks it. Implementations are stateless and shared.
class FingerModel {
 public:
  virtual ~FingerModel() = default;
  /// A touching contact gets a god-finger patch (computePatch) before addRows.
  virtual bool wantsPatch() const = 0;
  /// Adds the contact's rows to `out` in a fixed order (determinism): its block and points, or
  /// its aggregate block. Sets the contact's `block` and `aggregate`, and `first_injected` when
  /// it injects points. Does not allocate once `out.injected` has its reserve.
  virtual void addRows(const ContactToSolve& c, SolveRows& out) const = 0;
};

/// "god_object": one point (the true contact) and a friction block against sliding only.
class GodObjectModel final : public FingerModel {
 public:
  bool wantsPatch() const override { return false; }
  void addRows(const ContactToSolve& c, SolveRows& out) const override;
};

/// "soft_finger": one point and a friction block whose torsion limit is torsional_friction
/// times the normal force (MuJoCo's condim 4).
class SoftFingerModel final : public FingerModel {
 public:
  bool wantsPatch() const override { return false; }
  void addRows(const ContactToSolve& c, SolveRows& out) const override;
};

/// "god_finger" (ring or filled patch): the true contact and the patch's points, weighted by
/// their load shares, with the torsion limit the points give; as points, or as one aggregate
/// block when the finger's solver is "aggregate" and the contact has a patch.
class GodFingerModel final : public FingerModel {
 public:
  bool wantsPatch() const override { return true; }
  void addRows(const ContactToSolve& c, SolveRows& out) const override;
};

/// Keeps what solvedLoads needs of contact `c`'s solve in c.solved: its points' normal
/// impulses (points solver), the step `dt` (s) and the body's orientation. After the solve,
/// while its manifold and `injected` points are still there; a few copies per point.
void keepSolved(FingerContact& c, const std::vector<btPersistentManifold*>& injected, double dt);

/// The anchor a contact leaves for the next step: its own while its block ended the solve
/// sticking (inside its friction limit); at the limit, its point anchor only while its friction
/// force is under half of mu N (it turned rather than slid); none when its block was not solved.
FrictionAnchor anchorToKeep(const FingerContact& c, const FrictionBlock& block);

/// The forces the last solve put on the body at contact `c`'s points (keepSolved), with `block`
/// its solved friction block (valid until the next step's beforeSolve), into `out` in the
/// body's frame. Called for snapshots only: it costs more than the rest of the contact's step. Normal loads: the points solver's own impulses; the
/// aggregate's normal impulse by the points' load shares. Friction: the block's force in
/// proportion to the normal loads, and its moment about the normal (at the block's centre) by
/// their levers (each point mu times its load across its lever at the limit). Then the normal
/// loads shift linearly across the patch (clamped at zero, their sum kept) until, with the
/// friction, they make the block's moment about the tangent axes: the aggregate's tilt, and
/// what carrying the friction at the points' depths instead of the tangent plane changes. The
/// rolling rows' moment stays apart (ContactLoads::rolling_moment). A point slips when the
/// block is at its limit and the point's friction is at least kSlipFraction of mu times its
/// load. Does not allocate once `out` has held as many points.
void solvedLoads(const FingerContact& c, const FrictionBlock& block, AggregateScratch& scratch, ContactLoads& out);

/// The model object of an effective model (EffectiveSettings::patch.model); fem_pad's is the
/// god-object's, for its bone touching a body through the pad. Any thread; does
/// not allocate.
const FingerModel& fingerModel(ContactModel model);

}  // namespace gf::sim
