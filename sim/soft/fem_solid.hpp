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

  /// One implicit Euler step of `dt` s under `node_forces` (N per node; empty for none) and
  /// `bone_force` (N). Allocates nothing once the first step has sized its storage.
  void step(double dt, const std::vector<Vec3>& node_forces, const Vec3& bone_force);

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
  void assemble(double dt, const std::vector<Vec3>& node_forces, const Vec3& bone_force);
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
  bool has_bone_ = false;
  bool analysed_ = false;
  std::vector<Eigen::Triplet<double>> triplets_;
  Eigen::SparseMatrix<double> system_;
  Eigen::VectorXd rhs_, solution_;
  std::unique_ptr<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>> solver_;
};

}  // namespace gf::sim
