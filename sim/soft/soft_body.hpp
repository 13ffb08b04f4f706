// A soft body: a FemSolid of its own, free or pinned in places, under gravity, its surface nodes
// pressed into the World's rigid bodies (NodeContacts) and its surface pressed by fingers. A
// finger presses points of its surface's faces (SoftPress: the god-finger's SGOs, or the god-
// object's one point), each a contact between the face's point and the finger's pad whose
// springs the solid's step takes implicitly, the finger's translation solved with it (a partner
// of the solid: its mass, its velocity and the coupling's force), so a light proxy against stiff
// contacts stays stable. Its surface is kept as a Mesh that follows the nodes, which the patch's
// walk reads as it reads a rigid body's. A step that turns an element inside out or loses finite
// values is undone. Pure Eigen: no Bullet here.
#pragma once

#include <memory>
#include <span>
#include <vector>

#include "sim/math.hpp"
#include "sim/mesh/mesh.hpp"
#include "sim/mesh/tet_pad.hpp"
#include "sim/soft/fem_solid.hpp"
#include "sim/soft/node_contacts.hpp"

namespace gf::sim {

/// A soft body's material and contacts (a scene's soft_* body).
struct SoftBodySettings {
  FemMaterial material;              ///< Young's modulus, Poisson's ratio, density, damping
  double contact_stiffness = 1e5;    ///< N/m: each contact's normal and friction springs
  double friction = 0.8;             ///< Coulomb coefficient, times a rigid body's own
};

/// A finger's press on one point of a soft body's surface in one step.
struct SoftPress {
  int finger = -1;                  ///< the finger (0 .. fingers - 1 of the SoftBody)
  int face = -1;                    ///< the surface triangle holding the point (surface()), or
  int node = -1;                    ///< (face -1) a node of the surface, pressed itself
  Vec3 weights = Vec3(1.0, 0.0, 0.0);  ///< the point's barycentric coordinates in that face
  /// The finger pad's outward normal at the point (unit): the way the pad pushes the body.
  Vec3 normal = Vec3::UnitY();
  double depth = 0.0;               ///< how far the point is inside the pad (m); ≤ 0: not pressed
  double friction = 0.0;            ///< Coulomb coefficient
  /// The point's identity from step to step, so its friction spring carries over: its node's
  /// index for a node's press, -1 for a face's point (one per finger).
  int key = -1;
};

/// What a press did in the last step.
struct SoftPressResult {
  Vec3 point = Vec3::Zero();   ///< the surface point at the step's end (world, m)
  Vec3 force = Vec3::Zero();   ///< on the body at the point (N): the opposite of the finger's
  bool slipping = false;
};

/// A finger as a soft body's step takes it: its proxy's mass, velocity and the force on it.
struct SoftFinger {
  double mass = 1.0;               ///< kg
  Vec3 velocity = Vec3::Zero();    ///< m/s at the step's start
  Vec3 force = Vec3::Zero();       ///< N: the coupling's, besides the presses
};

class SoftBody {
 public:
  /// The body of `mesh` (world, at rest), `pinned` nodes held where they are, pressable by
  /// `fingers` fingers. Throws std::invalid_argument naming the field for a material or a mesh
  /// it cannot take. Allocates.
  SoftBody(const TetMesh& mesh, const SoftBodySettings& settings, const std::vector<int>& pinned, int fingers);
  ~SoftBody();
  SoftBody(const SoftBody&) = delete;
  SoftBody& operator=(const SoftBody&) = delete;

  /// One step of `dt` s under `gravity` (m/s²), against the rigid `surfaces`, with each finger's
  /// state and this step's `presses`. Undone (resets()) when it turns an element inside out or
  /// loses finite values: back at the step's start at rest, its contacts dropped; twice running,
  /// at rest in its shape where its frame now is. Allocates only while its storage grows.
  void step(double dt, const Vec3& gravity, const PadSurfaces& surfaces, std::span<const SoftFinger> fingers,
            const std::vector<SoftPress>& presses);

  /// The load on the body over its next steps, replaced (setLoad) or added to (addLoad): a force
  /// (N) through its centre of mass and a torque (N m), spread over its nodes as forces in
  /// proportion to their masses, the torque's as m_i α × r_i with α = I⁻¹ torque (I about the
  /// centre now), so they add up to the force and the torque and nothing else.
  void setLoad(const Vec3& force, const Vec3& torque) {
    load_force_ = force;
    load_torque_ = torque;
  }
  void addLoad(const Vec3& force, const Vec3& torque) {
    load_force_ += force;
    load_torque_ += torque;
  }

  /// The surface now (world, m): vertex v is node surfaceNode(v); its faces wound outward.
  const Mesh& surface() const { return *surface_; }
  int surfaceNode(int vertex) const { return surface_nodes_[static_cast<std::size_t>(vertex)]; }
  /// The surface's triangles as node indices (shared with snapshots; immutable).
  const std::shared_ptr<const std::vector<std::array<int, 3>>>& surfaceTriangles() const { return triangles_; }
  const std::vector<Vec3>& nodes() const { return solid_->positions(); }
  /// The point of face `face` at barycentric `weights` at rest, carried by the body's frame now.
  Vec3 restPoint(int face, const Vec3& weights) const;
  /// The outward normal at rest at face `face`'s point of barycentric `weights`, carried by the
  /// body's frame now (unit): its corners' normals at rest interpolated, each the area-weighted
  /// mean of that corner's faces within kSmoothAngle of `face` at rest (so it turns smoothly from
  /// face to face on a curved surface and keeps a box's edges sharp).
  Vec3 restNormal(int face, const Vec3& weights) const;

  /// Each press of the last step (in order), and the velocity it left finger `k` with (m/s) when
  /// it pressed (pressed(k)).
  const std::vector<SoftPressResult>& pressResults() const { return press_results_; }
  bool pressed(int k) const { return finger_pressed_[static_cast<std::size_t>(k)] != 0; }
  Vec3 fingerVelocity(int k) const { return solid_->partnerVelocity(k); }
  /// The surface nodes pressed into rigid bodies in the last step.
  const std::vector<PadNodeContact>& surfaceContacts() const { return node_contacts_->contacts(); }
  /// Whether the last step was undone, and how many steps were so far.
  bool undone() const { return undone_; }
  long resets() const { return resets_; }

  /// Its frame: the centre of mass and the rotation that best carries the rest shape onto the
  /// nodes now; its centre's velocity and the angular velocity of its nodes about it.
  const Pose& frame() const { return frame_; }
  Vec3 velocity() const;
  Vec3 angularVelocity() const;
  double mass() const { return mass_; }
  double kineticEnergy() const;
  /// Elements turned inside out now.
  int invertedElements() const { return solid_->invertedElements(); }
  const FemSolid& solid() const { return *solid_; }

 private:
  bool validPress(const SoftPress& p, int fingers) const;
  std::size_t keyOf(const SoftPress& p) const;
  void addPresses(std::span<const SoftFinger> fingers, const std::vector<SoftPress>& presses);
  void readPresses(const std::vector<SoftPress>& presses);
  void undo();
  void fitFrame();
  void nodeForces(const Vec3& gravity);

  SoftBodySettings settings_;
  TetMesh mesh_;
  std::unique_ptr<FemSolid> solid_;
  std::unique_ptr<NodeContacts> node_contacts_;
  std::unique_ptr<Mesh> surface_;
  std::vector<int> surface_nodes_;
  std::vector<Vec3> rest_areas_;  // per surface face, at rest: its normal times twice its area
  static constexpr double kSmoothAngle = 0.5235987755982988;  // rad (30 deg)
  std::vector<Vec3> surface_points_;
  std::shared_ptr<const std::vector<std::array<int, 3>>> triangles_;
  std::vector<int> free_surface_nodes_;
  std::vector<Vec3> gravity_forces_;
  std::vector<FemContact> contacts_;
  std::vector<SoftPressResult> press_results_;
  std::vector<char> finger_pressed_;
  std::vector<int> press_contact_;  // per press of this step: its contact's index, -1 none
  std::vector<char> pinned_;        // per node
  std::vector<std::vector<Vec3>> slides_;  // per finger, per node (then a face's point): its friction spring's stretch (m)
  std::vector<std::vector<char>> slid_;    // per finger, likewise: pressed in the last step
  Vec3 rest_centre_ = Vec3::Zero();
  Vec3 load_force_ = Vec3::Zero(), load_torque_ = Vec3::Zero();
  Pose frame_;
  double mass_ = 0.0;
  int rigid_partner_ = 0;
  long resets_ = 0;
  bool undone_ = false, undone_last_ = false;
};

}  // namespace gf::sim
