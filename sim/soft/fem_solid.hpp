// A soft solid by the finite-element method: linear tetrahedra, corotational linear elasticity
// (each element's rotation taken out by polar decomposition, so large rotations cost no spurious
// force), implicit Euler with Rayleigh stiffness damping, solved by a sparse Cholesky
// factorisation each step. Some nodes may be held: fixed, or moved with one rigid translational
// degree of freedom of their own (a bone, with a mass and the force on it), solved in the same
// system so a stiff pad on a light bone stays stable. Pure Eigen: no Bullet here.
#pragma once

#include <Eigen/SparseCore>

#include <array>
#include <memory>
#include <vector>

#include "sim/math.hpp"
#include "sim/mesh/tet_pad.hpp"
#include "sim/soft/sparse_ldlt.hpp"

namespace gf::sim {

/// An isotropic elastic material. SI units.
struct FemMaterial {
  double young_pa = 1e5;          ///< Young's modulus
  double poisson = 0.45;          ///< Poisson's ratio, below 0.5
  double density_kg_m3 = 1100.0;  ///< mass density
  double damping_s = 0.002;       ///< Rayleigh stiffness-proportional damping (s)
};

/// A node pressed into a rigid surface: `depth` (m, > 0; any, `bilateral`) below it along -`normal` (unit, out of
/// the surface) at the step's start. With friction, the node is held in the tangent plane by a
/// spring to its anchor on the surface (`slide`: from the node to the anchor at the step's
/// start, m), both springs stiff and implicit in the step, the tangential one's force capped at
/// `friction` times the normal force: past it the node slips, its friction at the cap along the
/// spring's stretch (a return mapping; the anchor is dragged behind it). The surface moves at
/// `surface_velocity` (m/s) during the step.
struct FemContact {
  int node = 0;
  Vec3 normal = Vec3::UnitY();
  double depth = 0.0;
  Vec3 surface_velocity = Vec3::Zero();
  Vec3 slide = Vec3::Zero();  ///< tangential (the part along `normal` is ignored)
  double friction = 0.0;      ///< Coulomb coefficient; 0: frictionless
  /// The surface is partner `partner`'s (addPartner; -1: none): its translation moves with the
  /// partner's velocity solved in the step, `surface_velocity` less the partner's velocity at the
  /// step's start the rest (its turning).
  int partner = -1;
  /// A point of a face instead of a node: `node` and `others` (-1: none) weighted by `weights`
  /// (barycentric, summing to 1), the spring's force shared by them in those parts. Unused for
  /// a node's own contact (both -1).
  std::array<int, 2> others{-1, -1};
  Vec3 weights = Vec3(1.0, 0.0, 0.0);
  /// Held to the surface both ways (a glued face or a plane of symmetry): its spring pulls as
  /// well as pushes, never lets go, and acts at any `depth` (negative: above the surface). With
  /// friction it sticks (glued: no cap, which a pulling normal force would make negative).
  bool bilateral = false;
};

/// What a contact did over the last step: the force on its node at the step's end (N), and
/// whether its friction was at its cap (slipping) or it let go (its spring would have pulled).
struct FemContactResult {
  Vec3 force = Vec3::Zero();
  bool slipping = false;
  bool released = false;
};

/// The rotation nearest to `f` (maximising trace(Rᵀ f)), found by turning `start` (say, the
/// last one) until the turn is under 1e-9 rad; a proper rotation even for an inverted `f`.
Eigen::Quaterniond nearestRotation(const Eigen::Matrix3d& f, Eigen::Quaterniond start);

/// Throws std::invalid_argument naming the field when `m` is not a material the solid can take.
void validateMaterial(const FemMaterial& m);

class FemSolid {
 public:
  /// The solid of `mesh` at rest where its nodes are, of `material`. Throws std::invalid_argument
  /// for a bad material or a tetrahedron of no volume. Allocates.
  FemSolid(const TetMesh& mesh, const FemMaterial& material);
  ~FemSolid();
  FemSolid(const FemSolid&) = delete;
  FemSolid& operator=(const FemSolid&) = delete;

  /// Holds `nodes` (indices) to a bone: one rigid translation of `mass_kg` that they follow, its
  /// velocity solved with the solid's. Call before the first step.
  void setBone(const std::vector<int>& nodes, double mass_kg);
  /// Holds `nodes` where they are (zero velocity). Call before the first step.
  void fixNodes(const std::vector<int>& nodes);
  /// A rigid partner that contacts of any of `nodes` may press: its translation solved with the
  /// solid, so a light body between stiff contacts stays stable (its turning stays explicit).
  /// Returns its index (0, 1, ... in the order added). Call before the first step; setPartner()
  /// before each step that has it.
  int addPartner(const std::vector<int>& nodes);
  /// Partner `k`'s step: `mass_kg` (> 0) at `velocity` (m/s) at the step's start, pushed by
  /// `force` (N) besides the contacts.
  void setPartner(int k, double mass_kg, const Vec3& velocity, const Vec3& force = Vec3::Zero());
  /// Partner `k`'s velocity at the step's end as the solid's step saw it (m/s).
  const Vec3& partnerVelocity(int k) const { return partners_[static_cast<std::size_t>(k)].v; }
  int partnerCount() const { return static_cast<int>(partners_.size()); }

  /// Each contact a stiff spring of `n_per_m` (N/m) along its normal, implicit in the step
  /// (k n nᵀ in the system, so a stiff one stays stable), pushing while the node is below
  /// (pulling too, for a bilateral contact).
  void setContactStiffness(double n_per_m) { contact_stiffness_ = n_per_m; }
  /// One implicit Euler step of `dt` s under `node_forces` (N per node; empty for none),
  /// `bone_force` (N) and `contacts` (the nodes pressed into rigid surfaces at its start).
  /// Its own storage is sized by the first step; each factorisation allocates a work copy.
  void step(double dt, const std::vector<Vec3>& node_forces, const Vec3& bone_force,
            const std::vector<FemContact>& contacts = {});
  /// The force each contact of the last step put on its node at the step's end (N: the normal
  /// spring's k × the depth then, and the friction); its opposite is the force on the surface.
  /// The solve is repeated (at most kMaxContactPasses times), each contact's mode from the last
  /// pass: one that would pull let go, one whose spring's trial force passed its cap slipping at
  /// the cap along the stretch, linearised about that pass (its turning implicit), one back
  /// within its cap sticking again; when the modes have not settled by then, one more solve with
  /// the modes as they stand. Either way these are exactly the forces the nodes moved under:
  /// never pulling (but a bilateral contact's) and, once settled, within the cap (a slipping
  /// one's friction moved by at most kSlipSettled of its cap in the last pass); unsettled, a contact may be past its cap by what
  /// that last solve left.
  const std::vector<Vec3>& contactForces() const { return contact_forces_; }
  const std::vector<FemContactResult>& contactResults() const { return contact_results_; }
  static constexpr int kMaxContactPasses = 4;
  /// The solves the last step took (1 .. kMaxContactPasses + 1) and whether its modes settled.
  int lastPasses() const { return last_passes_; }
  bool lastSettled() const { return last_settled_; }

  /// Elements turned inside out now (det F ≤ 0): a pad pressed past its thickness. Allocates nothing.
  int invertedElements() const;
  /// Back to rest on the bone where it is: every node at its rest place moved by the bone's
  /// offset, every velocity (the bone's too) zero. What a caller does when invertedElements() > 0.
  void resetToRest();

  /// Its state (positions, velocities, the bone's offset and velocity, the elements' rotations),
  /// kept by keepState() and put back by restoreState(), at rest (every velocity zero).
  void keepState();
  void restoreState();

  /// The elastic forces on the nodes now (N per node), corotational. Allocates.
  std::vector<Vec3> elasticForces() const;

  int nodeCount() const { return static_cast<int>(x_.size()); }
  const std::vector<Vec3>& positions() const { return x_; }
  std::vector<Vec3>& positions() { return x_; }
  const std::vector<Vec3>& velocities() const { return v_; }
  std::vector<Vec3>& velocities() { return v_; }
  const std::vector<double>& masses() const { return mass_; }
  /// Puts the bone at `offset` from where it started, moving at `velocity`: every node
  /// translated with it (a bone moved by something else, carrying its tissue).
  void moveBone(const Vec3& offset, const Vec3& velocity);
  /// The bone's translation from where it started (m) and its velocity (m/s).
  const Vec3& boneOffset() const { return bone_offset_; }
  const Vec3& boneVelocity() const { return bone_v_; }

 private:
  struct Element;
  void assemble(double dt, const std::vector<Vec3>& node_forces, const Vec3& bone_force);
  /// One solve of the step with the contacts in their modes; true when every contact's result
  /// agrees with its mode (none pulls, no sticking one past its cap).
  /// With `adjust` false the modes stay as they are (the last solve of an unsettled step).
  bool solveContacts(double dt, const std::vector<FemContact>& contacts, bool adjust = true);
  struct Slip;
  bool restick(double cap, const Vec3& trial, FemContactResult& r, Slip& slip) const;
  static constexpr double kSlipSettled = 1e-3;  // a slipping friction that moved less (of its cap) has settled
  void buildPattern();
  Eigen::Matrix3d deformation(std::size_t e) const;
  void addElementForce(std::size_t e, const Eigen::Matrix3d& r, std::vector<Vec3>& out) const;
  int unknownOf(int node) const { return unknown_[static_cast<std::size_t>(node)]; }
  void addContactRows(double dt, const FemContact& c, std::size_t i);
  bool readContact(double dt, const FemContact& c, std::size_t i, bool adjust);
  bool coupled(const FemContact& c) const;
  Vec3 knownVelocity(const FemContact& c) const;
  void addDiagonal(int u, const Eigen::Matrix3d& block);
  /// Adds `block` to the system's 3×3 block of unknowns (ua, ub), which its pattern holds.
  void addBlock(int ua, int ub, const Eigen::Matrix3d& block);
  /// The contact's point's weights per unknown (fixed nodes left out; a bone's nodes merged):
  /// how many, into `u` and `w`.
  int contactUnknowns(const FemContact& c, std::array<int, 3>& u, std::array<double, 3>& w) const;

  std::vector<std::array<int, 4>> tets_;
  std::vector<Element> elements_;
  std::vector<Vec3> rest_, x_, v_;
  std::vector<double> mass_;
  FemMaterial material_;
  // Unknowns: -1 fixed, 0 the bone (when there is one), then one per free node.
  std::vector<int> unknown_;
  std::vector<int> bone_nodes_;
  double bone_mass_ = 0.0;
  Vec3 bone_offset_ = Vec3::Zero(), bone_v_ = Vec3::Zero();
  int unknowns_ = 0;
  double contact_stiffness_ = 1e5;
  // The partners (addPartner): each one's unknown, nodes and step.
  struct Partner {
    std::vector<int> nodes;
    std::vector<char> has;  // per node: among `nodes`
    int unknown = -1;
    double mass = 1.0;
    Vec3 v0 = Vec3::Zero(), force = Vec3::Zero(), v = Vec3::Zero();
  };
  std::vector<Partner> partners_;
  std::vector<Vec3> contact_forces_;
  struct Kept {
    std::vector<Vec3> x;
    std::vector<Eigen::Quaterniond> rotations;
    Vec3 bone_offset = Vec3::Zero();
    bool set = false;
  } kept_;
  std::vector<FemContactResult> contact_results_;
  // Per contact while it slips, its friction linearised about the last pass: `force` (mu N ŝ, N)
  // along `direction` (ŝ), turning at `stiffness` (c = mu N / |s|, N/m) across it.
  struct Slip {
    Vec3 force = Vec3::Zero(), direction = Vec3::Zero();
    double stiffness = 0.0;
  };
  std::vector<Slip> slips_;
  std::vector<Slip> node_slips_;  // per node: its contact's slip at the last step's end (stiffness 0: none)
  std::vector<double> base_values_;  // the system without contacts, this step
  Eigen::VectorXd base_rhs_;
  bool has_bone_ = false;
  int last_passes_ = 0;
  bool last_settled_ = true;
  bool analysed_ = false;
  std::vector<int> block_slots_;     // per element, per node pair, the 9 entries' value slots
  std::vector<int> diagonal_slots_;  // per unknown, its 3×3 diagonal block's value slots
  std::vector<Vec3> forces_;         // this step's elastic forces
  Eigen::SparseMatrix<double> system_;
  Eigen::VectorXd rhs_, solution_;
  std::unique_ptr<SparseLdlt> solver_;
};

}  // namespace gf::sim
