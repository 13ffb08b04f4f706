// Builds the Bullet collision shape and the walk mesh of a body description. Internal to sim/.
#pragma once

#include <btBulletDynamicsCommon.h>

#include <memory>
#include <vector>

#include "sim/contact/bullet_math.hpp"
#include "sim/scene/scene_desc.hpp"

namespace gf::sim {

/// Everything a body needs besides its btRigidBody. The walk mesh is in the body frame (the
/// frame of the collision shape: centre of mass at the origin, principal axes for meshes).
struct BodyShapes {
  std::shared_ptr<const Mesh> walk_mesh;
  std::unique_ptr<btStridingMeshInterface> mesh_interface;  ///< concave meshes only
  std::vector<std::unique_ptr<btCollisionShape>> parts;  ///< children of a compound `shape`
  std::unique_ptr<btCollisionShape> shape;
  btVector3 local_inertia{0, 0, 0};  ///< kg m^2, principal
  /// Radius (m) with which the collision shape rounds the walk mesh's edges and corners (its
  /// collision margin; 0 where the shape is the exact surface: sphere, capsule, plane, static
  /// triangle mesh). Contacts near an edge land up to this far from it (PatchContact::rounding).
  double rounding = 0.0;
  /// Transform from the description's frame (mesh file frame, scaled) to the body frame.
  btTransform desc_from_body = btTransform::getIdentity();
};

/// Creates shapes for `desc`, whose settings must be legal (validateBody; the World checks the
/// whole scene first). Throws DescriptionError naming the body and field when its geometry
/// cannot be built (an unreadable mesh, an open mesh for a dynamic body). Allocates; call at
/// load time only.
BodyShapes makeBodyShapes(const BodyDesc& desc);

}  // namespace gf::sim
