// Triangles to draw, built on the CPU at load time: body surfaces with shading normals and the
// unit shapes (sphere, cylinder, cone) that fingers, dots and arrows are drawn from.
#pragma once

#include <memory>
#include <vector>

#include "render/gl/vertex.hpp"
#include "sim/mesh/mesh.hpp"
#include "sim/scene/scene_desc.hpp"

namespace gf::render {

/// Unwelded triangles of `mesh` with a normal per corner: the average of the normals of the
/// faces around that vertex that turn less than `crease_deg` from this face. A box stays
/// faceted, a sphere or a cylinder's side comes out smooth, a cylinder keeps a sharp rim.
std::vector<Vertex> shadedTriangles(const sim::Mesh& mesh, double crease_deg);

/// The surface a body is drawn with, in the body's description frame (m): primitives finely
/// tessellated, meshes as the scene loaded them (body.mesh, shared with the World, so patches
/// are projected onto what is seen). Planes return nullptr: they are drawn as the ground.
/// Throws sim::MeshLoadError when body.mesh is null and its file cannot be read.
std::shared_ptr<const sim::Mesh> bodyRenderMesh(const sim::BodyDesc& body);

/// Radius 1 icosphere at the origin: 20 * 4^subdivisions triangles.
std::vector<Vertex> unitSphere(int subdivisions);
/// Radius 1 cylinder from y = 0 to y = 1, with caps.
std::vector<Vertex> unitCylinder(int segments);
/// Cone of base radius 1 at y = 0, tip at y = 1, with its base cap.
std::vector<Vertex> unitCone(int segments);

}  // namespace gf::render
