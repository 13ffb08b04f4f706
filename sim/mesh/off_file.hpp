// OFF files (Geomview's Object File Format), read by our own reader rather than the importer's:
// comments anywhere, polygons of any size, counts checked against what the file holds.
#pragma once

#include <string>

#include "sim/mesh/raw_mesh.hpp"

namespace gf::sim::detail {

/// An OFF file's triangles and the counts its header gives.
struct OffFile {
  RawMesh mesh;       ///< positions times the scale (m), polygons split into triangles
  long vertices = 0;  ///< as the header counts them
  long faces = 0;
};

/// Reads an OFF file ([ST][C][N][4][n]OFF keyword, optional; ASCII). A `#` starts a comment to the
/// end of its line anywhere; blank lines are skipped; a vertex or face line may carry more numbers
/// (normals, colours, texture coordinates), which are ignored. Faces of 1 or 2 vertices (points,
/// lines) are skipped; polygons are split into triangles (ear clipping when not convex). Throws
/// MeshLoadError naming the file and line when the header's counts disagree with the lines the
/// file holds (fewer or more), a count exceeds what the file's size can hold, a face names a
/// vertex beyond the count, or a coordinate is not finite. Load time only.
OffFile readOffFile(const std::string& path, double scale);

}  // namespace gf::sim::detail
