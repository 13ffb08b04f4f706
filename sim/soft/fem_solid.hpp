// A soft solid by the finite-element method: linear tetrahedra, corotational linear elasticity
// (each element's rotation taken out by polar decomposition, so large rotations cost no spurious
// force), implicit Euler with Rayleigh stiffness damping, solved by a sparse Cholesky
// factorisation each step. Some nodes may be held: fixed, or moved with one rigid translational
// degree of freedom of their own (a bone, with a mass and the force on it), solved in the same
// system so a stiff pad on a light bone stays stable. Pure Eigen: no Bullet here.
#pragma once

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include <memory>
#include <vector>

#include "sim/math.hpp"
#include "sim/mesh/tet_pad.hpp"

namespace gf::sim {

/// An isotropic elastic material. SI units.
struct FemMaterial {
  double young_pa = 1e5;          ///< Young's modulus
  double poisson = 0.45;          ///< Poisson's ratio, below 0.5
  double density_kg_m3 = 1100.0;  ///< mass density
  double damping_s = 0.002;       ///< Rayleigh stiffness-proportional damping (s)
};

/// A node pressed into a rigid surface: `depth` (m, > 0) below it along -`normal` (unit, out of
/// the surface) at the step's start.
struct FemContact {
  int node = 0;
  Vec3 normal = Vec3::UnitY();
  double depth = 0.0;
};

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

  /// Each contact a stiff spring of `n_per_m` (N/m) along its normal, implicit in the step
  /// (k n nᵀ in the system, so a stiff one stays stable), pushing while the node is below.
  void setContactStiffness(double n_per_m) { contact_stiffness_ = n_per_m; }
  /// One implicit Euler step of `dt` s under `node_forces` (N per node; empty for none),
  /// `bone_force` (N) and `contacts` (the nodes pressed into rigid surfaces at its start).
  /// Allocates nothing once the first step has sized its storage.
  void step(double dt, const std::vector<Vec3>& node_forces, const Vec3& bone_force,
            const std::vector<FemContact>& contacts = {});
  /// The force each contact of the last step put on its node at the step's end (N, along its
  /// normal: k × the depth then, never pulling); its opposite is the force on the surface.
  const std::vector<Vec3>& contactForces() const { return contact_forces_; }

  /// Elements turned inside out now (det F ≤ 0): a pad pressed past its thickness. Allocates nothing.
  int invertedElements() const;
  /// Back to rest on the bone where it is: every node at its rest place moved by the bone's
  /// offset, every velocity (the bone's too) zero. What a caller does when invertedElements() > 0.
  void resetToRest();

  /// The elastic forces on the nodes now (N per node), corotational. Allocates.
  std::vector<Vec3> elasticForces() const;

  int nodeCount() const { return static_cast<int>(x_.size()); }
  const std::vector<Vec3>& positions() const { return x_; }
  std::vector<Vec3>& positions() { return x_; }
  const std::vector<Vec3>& velocities() const { return v_; }
  std::vector<Vec3>& velocities() { return v_; }
  const std::vector<double>& masses() const { return mass_; }
  /// The bone's translation from where it started (m) and its velocity (m/s).
  const Vec3& boneOffset() const { return bone_offset_; }
  const Vec3& boneVelocity() const { return bone_v_; }

 private:
  struct Element;
  void assemble(double dt, const std::vector<Vec3>& node_forces, const Vec3& bone_force,
                const std::vector<FemContact>& contacts);
  void buildPattern();
  Eigen::Matrix3d deformation(std::size_t e) const;
  void addElementForce(std::size_t e, const Eigen::Matrix3d& r, std::vector<Vec3>& out) const;
  int unknownOf(int node) const { return unknown_[static_cast<std::size_t>(node)]; }

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
  std::vector<Vec3> contact_forces_;
  bool has_bone_ = false;
  bool analysed_ = false;
  std::vector<int> block_slots_;     // per element, per node pair, the 9 entries' value slots
  std::vector<int> diagonal_slots_;  // per unknown, its 3×3 diagonal block's value slots
  std::vector<Vec3> forces_;         // this step's elastic forces
  Eigen::SparseMatrix<double> system_;
  Eigen::VectorXd rhs_, solution_;
  std::unique_ptr<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>> solver_;
};

}  // namespace gf::sim
