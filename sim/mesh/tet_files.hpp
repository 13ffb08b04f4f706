// Tetrahedral meshes from files, read by our own readers in double precision: TetGen's .node and
// .ele pair, and VTK's legacy ASCII unstructured grids. Both give a TetMesh whose tetrahedra all
// have positive volume (one read inverted is turned, two of its nodes swapped, without a word:
// files differ in which way they wind) and whose surface is boundaryTriangles'. Nodes no
// tetrahedron uses are kept, with their indices as in the file (a second-order mesh's mid-edge
// nodes among them); bone_nodes, cells_across and layers are left empty. The limits are those of
// the generated shapes (tet_shapes.hpp): kMaxTetrahedra and kMaxTetNodes. A file that cannot be
// used throws MeshLoadError naming the file, and the line and the item ("node 3", "tetrahedron
// 7", "cell 5") where there is one: "<path>: line <n>: <item>: <reason>". Pure geometry.
#pragma once

#include <string>

#include "sim/mesh/raw_mesh.hpp"
#include "sim/mesh/tet_pad.hpp"

namespace gf::sim {

/// The tetrahedra of TetGen's `node_path` (.node) and `ele_path` (.ele), coordinates times `scale`
/// (m per file unit, positive). A `#` starts a comment to the end of its line; blank lines are
/// skipped. The .node header gives the node count, the dimension (3; no other is read) and counts
/// of attributes and boundary markers, whose columns are ignored; node ids start at 0 or 1, as the
/// first node says, and go on one by one. The .ele header gives the tetrahedron count and nodes per
/// tetrahedron: 4, or 10 (second order: its first four, the corners, are kept; the mid-edge nodes
/// stay unused); region attributes are ignored. Throws MeshLoadError (see above) when the counts
/// disagree with the lines the files hold or exceed what their sizes can hold or the limits, a
/// node id is out of turn, a tetrahedron names a node beyond the count, a coordinate is not a
/// finite number, or a tetrahedron is flat (zero volume). Load time only; allocates.
TetMesh readTetGen(const std::string& node_path, const std::string& ele_path, double scale);

/// The tetrahedra of a VTK legacy file (`path`: "# vtk DataFile Version", a title, ASCII,
/// DATASET UNSTRUCTURED_GRID), coordinates times `scale` (m per file unit, positive): POINTS
/// (float or double), CELLS (each cell's node count and nodes, or version 5.1's OFFSETS and
/// CONNECTIVITY arrays) and CELL_TYPES. Tetrahedra (type 10) are kept, and second-order ones (24) by their four corners;
/// cells of lower dimension (vertices, lines, triangles, polygons, quads: types 1 to 9, 21 to 23),
/// often a boundary, are skipped; any other type is refused, naming its line. FIELD and METADATA
/// blocks are skipped; POINT_DATA, CELL_DATA and all after them are ignored. Throws MeshLoadError
/// (see above) as readTetGen does. Load time only; allocates.
TetMesh readVtkTets(const std::string& path, double scale);

}  // namespace gf::sim
