// Mesh files (OBJ, PLY, STL, OFF, glTF, and the rest assimp reads) into welded Meshes.
#pragma once

#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>

#include "sim/mesh/mesh.hpp"
#include "sim/mesh/raw_mesh.hpp"

namespace gf::sim {

/// Reads every triangle of every mesh in the file, node transforms applied, in the file's
/// declared unit (FBX's UnitScaleFactor, in centimetres; Collada's <unit>), times `scale`. OFF
/// files are read by our own reader (off_file.hpp), the rest by assimp.
/// Points and lines are ignored. Throws MeshLoadError when the file cannot be read or holds no
/// triangle, or a coordinate is not finite. Allocates; call at load time only.
RawMesh readMeshFile(const std::string& path, double scale = 1.0);

/// One part of a mesh file as placed in its scene: a mesh under a node (a mesh instanced by two
/// nodes is two parts), with the node's transform from the file's root (file units, after what
/// the importer applies for the file's declared unit and up axis).
struct MeshPart {
  std::string mesh;  ///< the mesh's name in the file ("" when it has none)
  std::string node;  ///< the node placing it
  int vertices = 0, triangles = 0;
  Eigen::Matrix4d transform = Eigen::Matrix4d::Identity();
};

/// What a mesh file declares and holds before welding.
struct MeshFileInfo {
  std::string format;              ///< the importer's name for it ("Collada Importer", ...)
  std::vector<MeshPart> parts;
  double declared_unit_m = 0.0;    ///< metres per file unit the file declares; 0: none
  std::string declared_up;         ///< "X", "Y" or "Z" (with a sign when negative); "": none
  bool unit_and_up_applied = false;  ///< the importer turned them into the root's transform
  bool unit_applied = false;  ///< readMeshFile gives metres from the declared unit (Collada, FBX)
};

/// Reads the file's parts, node transforms and declared unit and up axis (Collada's <unit> and
/// <up_axis>, FBX's UnitScaleFactor and UpAxis; glTF is metres and Y up by definition). Throws
/// MeshLoadError as readMeshFile does. Load time only.
MeshFileInfo describeMeshFile(const std::string& path);

/// readMeshFile followed by buildMesh; throws MeshLoadError also when nothing is left after
/// dropping degenerate triangles.
Mesh loadMesh(const std::string& path, double scale = 1.0, const MeshBuildSettings& settings = {});

/// Meshes loaded from files, one per (path, scale): a file a run uses several times is read
/// once. Load time only; one thread.
class MeshCache {
 public:
  /// The mesh of `path` at `scale`, loaded on the first call (throws MeshLoadError).
  std::shared_ptr<const Mesh> load(const std::string& path, double scale);
  /// Files read so far.
  int filesRead() const { return files_read_; }

 private:
  std::map<std::pair<std::string, double>, std::shared_ptr<const Mesh>> meshes_;
  int files_read_ = 0;
};

}  // namespace gf::sim
