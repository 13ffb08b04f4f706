// A deformable finger pad: a cap of soft tissue (FemSolid on a TetMesh of sim/mesh/tet_pad.hpp)
// on a rigid distal bone that translates with the finger's proxy. Each step its skin nodes are
// tested against the surfaces near them (PadSurfaces: the World's bodies), a node inside one
// becoming a contact whose normal and friction springs are implicit in the solid's step; each
// contact's force is read back from what the solve did, and its opposite is the force on the
// body. A node that sticks keeps an anchor in the body's frame; one past its friction cap
// slips, its anchor dragged along. A pad turned inside out is put back at rest on its bone and
// counted. Pure Eigen: no Bullet here (the World answers PadSurfaces from its bodies).
#pragma once

#include <memory>
#include <vector>

#include "sim/math.hpp"
#include "sim/mesh/tet_pad.hpp"
#include "sim/soft/fem_solid.hpp"
#include "sim/soft/node_contacts.hpp"

namespace gf::sim {

/// A finger's soft pad (`pad_*` of a finger in scene files). Its skin is the proxy's sphere
/// (proxy_radius), its bone a sphere `thickness` smaller. Defaults: a fingertip's pulp, 3 mm of
/// tissue over a 5 mm bone, ν 0.45 (nearly incompressible, as FE fingertip models take soft
/// tissue), 1100 kg/m³, and 300 kPa: a linear pad must be stiff enough in shear to reach its
/// friction limit under a twist before it turns inside out (at 100 kPa a 3 N press twisted at
/// μ 1 does; docs/soft-hand.md), so it indents about 0.5 mm at 1 N where a real fingertip's
/// softer, stiffening pulp gives more.
struct PadSettings {
  double thickness = 0.003;          ///< m: tissue between the bone and the skin
  double cap_angle = 0.6981317007977318;  ///< rad (40 deg): the pad's half-angle about its axis (pad_axis)
  double element_size = 0.0015;      ///< m: the tetrahedra's cells, thickness / 4 .. thickness
  double young = 3e5;                ///< Pa: Young's modulus of the tissue
  double poisson = 0.45;             ///< Poisson's ratio
  double density = 1100.0;           ///< kg/m³
  double damping = 0.002;            ///< s: Rayleigh stiffness-proportional damping
  double contact_stiffness = 1e5;    ///< N/m: each skin node's normal and friction springs
};

class FemPad {
 public:
  /// The pad of `settings` on a bone of `bone_mass` kg whose skin is a sphere of `skin_radius`
  /// (m) centred at `centre`, its cap facing `axis` (unit, world). Throws std::invalid_argument
  /// naming the field for settings the mesh or the material cannot take. Allocates.
  FemPad(const PadSettings& settings, double skin_radius, double bone_mass, const Vec3& axis, const Vec3& centre);
  ~FemPad();
  FemPad(const FemPad&) = delete;
  FemPad& operator=(const FemPad&) = delete;

  /// Puts the bone at `centre` moving at `velocity` (the proxy's), the tissue carried along.
  void follow(const Vec3& centre, const Vec3& velocity);
  /// One step of `dt` s: the bone pushed by `bone_force` (N, the coupling's), the skin against
  /// `surfaces` with Coulomb `friction`. A step that turned the pad inside out or lost finite
  /// values is undone (counted in resets()), its contacts dropped: the pad back at the step's
  /// start, at rest, every anchor let go; twice running, back at rest on the bone, every skin
  /// node inside a surface that faces its bone put on it. Its own storage is sized once; the
  /// sparse factorisation allocates a work copy each solve (Eigen's SimplicialLDLT).
  void step(double dt, const Vec3& bone_force, double friction, const PadSurfaces& surfaces);

  const std::vector<PadNodeContact>& contacts() const { return nodes_->contacts(); }
  /// The bone's centre now (m) and its velocity (m/s).
  Vec3 boneCentre() const { return centre0_ + solid_->boneOffset(); }
  Vec3 boneVelocity() const { return solid_->boneVelocity(); }
  double boneRadius() const { return bone_radius_; }
  /// Times the pad was put back at rest (inverted or not finite), and elements inverted then.
  long resets() const { return resets_; }
  int lastInverted() const { return last_inverted_; }
  /// The pad's nodes now (world, m) and its outer surface (skin and sides; not the bone's side).
  const std::vector<Vec3>& nodes() const { return solid_->positions(); }
  const std::shared_ptr<const std::vector<std::array<int, 3>>>& skin() const { return skin_; }
  const TetMesh& mesh() const { return mesh_; }
  const FemSolid& solid() const { return *solid_; }
  /// The tissue's kinetic energy (J) and momentum (N s), its nodes on the bone included; not the
  /// bone's own mass (the proxy's).
  double kineticEnergy() const;
  Vec3 momentum() const;

 private:
  void liftOut(const PadSurfaces& surfaces);

  PadSettings settings_;
  TetMesh mesh_;
  std::unique_ptr<FemSolid> solid_;
  Vec3 centre0_ = Vec3::Zero();
  double bone_radius_ = 0.0;
  std::vector<int> skin_nodes_;
  std::shared_ptr<const std::vector<std::array<int, 3>>> skin_;
  std::unique_ptr<NodeContacts> nodes_;
  std::vector<FemContact> fem_contacts_;
  long resets_ = 0;
  int last_inverted_ = 0;
  bool reset_last_step_ = false;
};

}  // namespace gf::sim
