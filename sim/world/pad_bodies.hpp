// The World's rigid bodies as the soft solids see them (PadSurfaces): world_pad.cpp's pads and
// world_soft.cpp's soft bodies. Internal to sim/world.
#pragma once

#include <algorithm>

#include "sim/world/world_impl.hpp"

namespace gf::sim {

// The World's rigid bodies as a pad or a soft body asks for them: their Bullet bounds, their walk meshes (in the body
// frame, bodyFrame) and their velocities.
class World::Impl::PadBodies final : public PadSurfaces {
 public:
  explicit PadBodies(const Impl& w) : w_(w) {}

  void near(const Vec3& lo, const Vec3& hi, std::vector<int>& out) const override {
    out.clear();
    for (std::size_t i = 0; i < w_.bodies.size(); ++i) {
      if (w_.bodies[i].soft) continue;  // soft bodies touch rigid ones only
      btVector3 a, b;
      w_.bodies[i].rigid->getAabb(a, b);
      if ((toEigen(a).cwiseMax(lo).array() <= toEigen(b).cwiseMin(hi).array()).all()) out.push_back(static_cast<int>(i));
    }
  }

  bool inside(int body, const Vec3& p, double& depth, Vec3& normal) const override {
    const Mesh& mesh = *w_.bodies[static_cast<std::size_t>(body)].shapes.walk_mesh;
    const Pose frame = w_.bodyFrame(body);
    const Vec3 local = frame.orientation.conjugate() * (p - frame.position);
    const SurfacePoint hit = mesh.closestPoint(local, kFeatureTolerance);
    if (hit.face < 0) return false;
    const Vec3 d = local - hit.point;
    if (!below(mesh, hit, d)) return false;
    depth = d.norm();
    const Vec3 n = hit.feature == Feature::kFace || depth < kFeatureTolerance ? mesh.faceNormal(hit.face) : Vec3(-d / depth);
    normal = frame.orientation * n;
    return depth > 0.0;
  }

  Pose frame(int body) const override { return w_.bodyFrame(body); }

  double friction(int body) const override {
    return w_.desc.effects.friction ? w_.desc.bodies[static_cast<std::size_t>(body)].friction : 0.0;
  }

  double mass(int body) const override {
    const double inverse = w_.bodies[static_cast<std::size_t>(body)].rigid->getInvMass();
    return inverse > 0.0 ? 1.0 / inverse : 0.0;
  }

  Vec3 velocity(int body) const override { return toEigen(w_.bodies[static_cast<std::size_t>(body)].rigid->getLinearVelocity()); }

  Vec3 velocityAt(int body, const Vec3& p) const override {
    const btRigidBody& r = *w_.bodies[static_cast<std::size_t>(body)].rigid;
    return toEigen(r.getVelocityInLocalPoint(toBt(p) - r.getCenterOfMassPosition()));
  }

 private:
  static constexpr double kFeatureTolerance = 1e-9;  // m

  // `d` (from the closest point to the query, body frame) points into the solid: below every
  // face at the closest feature (one face, an edge's two, a corner's fan).
  static bool below(const Mesh& mesh, const SurfacePoint& hit, const Vec3& d) {
    const auto under = [&](int face) { return face < 0 || d.dot(mesh.faceNormal(face)) < 0.0; };
    if (!under(hit.face)) return false;
    if (hit.feature == Feature::kEdge) return under(mesh.link(hit.face, hit.feature_index).face);
    if (hit.feature == Feature::kVertex) {
      const int v = mesh.triangles()[static_cast<std::size_t>(hit.face)][static_cast<std::size_t>(hit.feature_index)];
      return std::all_of(mesh.vertexFacesBegin(v), mesh.vertexFacesEnd(v), under);
    }
    return true;
  }

  const Impl& w_;
};

}  // namespace gf::sim
