// A soft solid's nodes pressed into rigid surfaces, step by step: which nodes are inside which
// surface (each a FemContact for the solid's step, its friction spring pulling towards an anchor
// kept in the surface's frame while it sticks), which dynamic surface is solved with the solid
// (its partner), and what each contact did, read back from the solve. The finger pad (FemPad)
// and soft bodies (SoftBody) press the World's bodies through it. Pure Eigen: no Bullet here.
#pragma once

#include <array>
#include <vector>

#include "sim/math.hpp"
#include "sim/soft/fem_solid.hpp"

namespace gf::sim {

/// The rigid surfaces a soft solid may touch, as it asks for them each step (the World's bodies).
class PadSurfaces {
 public:
  virtual ~PadSurfaces() = default;
  /// Surfaces whose bounds meet [lo, hi] (world, m), into `out` (cleared first).
  virtual void near(const Vec3& lo, const Vec3& hi, std::vector<int>& out) const = 0;
  /// Whether world point `p` is inside surface `body`: its depth below the surface (m, > 0) and
  /// the surface's outward normal there (unit, world).
  virtual bool inside(int body, const Vec3& p, double& depth, Vec3& normal) const = 0;
  /// Body `body`'s frame now (its anchors are kept in it).
  virtual Pose frame(int body) const = 0;
  /// The velocity of body `body`'s material point at world `p` (m/s).
  virtual Vec3 velocityAt(int body, const Vec3& p) const = 0;
  /// Body `body`'s mass (kg; 0: static) and its centre of mass's velocity (m/s).
  virtual double mass(int body) const = 0;
  virtual Vec3 velocity(int body) const = 0;
  /// Body `body`'s Coulomb coefficient, which a soft body's own multiplies (a pad takes its
  /// finger's alone).
  virtual double friction(int /*body*/) const { return 1.0; }
};

/// One node pressed into a body in the last step.
struct PadNodeContact {
  int node = -1;
  int body = -1;
  Vec3 point = Vec3::Zero();   ///< the node at the step's end (world, m)
  Vec3 normal = Vec3::UnitY(); ///< the surface's outward normal (world)
  Vec3 force = Vec3::Zero();   ///< on the body (N, world): the opposite of the contact's on the node
  double depth = 0.0;          ///< below the surface at the step's start (m)
  double area = 0.0;           ///< the node's share of the surface (m², a third of its triangles')
  bool slipping = false;       ///< its friction at its cap
};

class NodeContacts {
 public:
  /// For a solid of `node_count` nodes whose outer surface is `surface` (its nodes' areas).
  NodeContacts(int node_count, std::vector<std::array<int, 3>> surface);

  /// This step's contacts, into `out` (cleared first): each of `nodes` (positions `x`) inside a
  /// surface near them that faces `inner` (a point inside the solid: a node past a thin body's
  /// middle finds the far face nearer, whose normal points away, and would be pushed through),
  /// with the deepest one, friction `friction` (times the surface's own when `combine`), its
  /// tangential spring towards the anchor it kept on that body.
  void find(const std::vector<Vec3>& x, const std::vector<int>& nodes, const Vec3& inner, const PadSurfaces& surfaces,
            double friction, bool combine, std::vector<FemContact>& out);
  /// The dynamic body pressed by the most of this step's contacts (the first `out`'s) solved with
  /// the solid as its partner `partner`: its contacts marked so; -1 when none.
  int choosePartner(FemSolid& solid, int partner, const PadSurfaces& surfaces, std::vector<FemContact>& out) const;
  /// What the contacts (the first of the solid's last step's) did: each one's force on its body,
  /// its anchor kept where its friction spring now pulls from (dragged along when it slipped),
  /// its share of the surface.
  void read(double dt, const FemSolid& solid, const std::vector<FemContact>& contacts, const PadSurfaces& surfaces,
            double contact_stiffness);
  /// Every contact and anchor dropped (a step undone).
  void clear();

  const std::vector<PadNodeContact>& contacts() const { return contacts_; }
  const std::vector<int>& nearBodies() const { return near_; }
  int count() const { return static_cast<int>(contact_body_.size()); }

 private:
  struct Anchor {
    int body = -1;
    Vec3 local = Vec3::Zero();  // in the body's frame
  };
  std::vector<std::array<int, 3>> surface_;
  std::vector<Anchor> anchors_;  // per node
  std::vector<int> near_;
  std::vector<int> contact_body_;
  std::vector<PadNodeContact> contacts_;
  std::vector<double> node_area_;
};

}  // namespace gf::sim
