#include "sim/mesh/tet_files.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <sstream>
#include <string_view>
#include <system_error>
#include <vector>

#include "sim/mesh/tet_shapes.hpp"

namespace gf::sim {
namespace {

// Bytes a TetGen node line ("0 0 0 0\n"), a tetrahedron line ("0 0 0 0 0\n") and a VTK number
// ("0 ") take at least: a count beyond the file's size over these is refused before any memory is
// reserved for it.
constexpr double kMinNodeLineBytes = 8, kMinTetLineBytes = 10, kMinNumberBytes = 2;
// A tetrahedron is flat when six times its volume is at most this fraction of its longest edge
// cubed (a regular tetrahedron's is 0.71).
constexpr double kFlatVolume = 1e-12;
// A count bounded by the file's size alone.
constexpr double kUnbounded = std::numeric_limits<double>::infinity();

// A count as text: exact up to 1e15, any size (1e+18) beyond.
std::string text(double count) {
  std::ostringstream s;
  s << std::setprecision(15) << count;
  return s.str();
}

std::string upper(std::string word) {
  for (char& c : word) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return word;
}

// `word` as a number in whole (a leading '+' allowed), or false. Correctly rounded.
bool parseNumber(std::string_view word, double& value) {
  if (word.size() > 1 && word[0] == '+') word.remove_prefix(1);
  const auto [end, ec] = std::from_chars(word.data(), word.data() + word.size(), value);
  return ec == std::errc() && end == word.data() + word.size();
}

// `word` as a whole number in whole (a leading '+' allowed), or false.
bool parseInteger(std::string_view word, long long& value) {
  if (word.size() > 1 && word[0] == '+') word.remove_prefix(1);
  const auto [end, ec] = std::from_chars(word.data(), word.data() + word.size(), value);
  return ec == std::errc() && end == word.data() + word.size();
}

// A text file read line by line, its lines split into words; its errors name the file and line.
class TextFile {
 public:
  TextFile(const std::string& path, bool comments) : path_(path), in_(path), comments_(comments) {
    std::error_code ec;
    const std::uintmax_t size = std::filesystem::file_size(path, ec);
    if (!in_ || ec) {
      throw MeshLoadError(path + ": cannot read the tetrahedral mesh: " +
                          (ec ? ec.message() : std::string("cannot open the file")));
    }
    size_ = static_cast<double>(size);
  }

  // The next line as it is, or false at the end of the file.
  bool raw(std::string& line) {
    if (!std::getline(in_, line)) return false;
    ++number_;
    return true;
  }

  // The next line's words, blank lines (and, with comments, all after a '#') skipped; false at
  // the end of the file.
  bool next(std::vector<std::string>& words) {
    std::string line;
    while (raw(line)) {
      if (const std::size_t hash = line.find('#'); comments_ && hash != std::string::npos) {
        line.erase(hash);
      }
      words.clear();
      std::istringstream s(line);
      for (std::string w; s >> w;) words.push_back(w);
      if (!words.empty()) return true;
    }
    return false;
  }

  [[noreturn]] void failAt(long line, const std::string& item, const std::string& why) const {
    throw MeshLoadError(path_ + ": line " + std::to_string(line) + ": " + item + ": " + why);
  }
  [[noreturn]] void fail(const std::string& item, const std::string& why) const {
    failAt(number_, item, why);
  }

  // A header's count of `what`: at most `limit`, and no more than the file's size can hold at
  // `bytes` each. Checked before any memory is reserved for them.
  void requireCount(double count, double limit, double bytes, const std::string& item,
                    const std::string& what) const {
    if (count > limit) {
      fail(item, "the header counts " + text(count) + " " + what + ", more than the " +
                     text(limit) + " read");
    }
    if (count * bytes > size_) {
      fail(item, "the header counts " + text(count) + " " + what + ", more than the file's " +
                     text(size_) + " bytes can hold");
    }
  }

  long line() const { return number_; }

 private:
  std::string path_;
  std::ifstream in_;
  bool comments_;
  double size_ = 0.0;
  long number_ = 0;
};

// A point of the file times `scale`; refused when a coordinate is not a finite number.
Vec3 readPoint(const TextFile& file, const std::string& item,
               const std::array<std::string, 3>& words, double scale) {
  Vec3 p;
  for (int k = 0; k < 3; ++k) {
    if (!parseNumber(words[static_cast<std::size_t>(k)], p[k])) {
      file.fail(item, "coordinate '" + words[static_cast<std::size_t>(k)] + "' is not a number");
    }
  }
  p *= scale;
  if (!p.allFinite()) {
    file.fail(item, "coordinates (" + words[0] + ", " + words[1] + ", " + words[2] +
                        ") times the scale are not finite");
  }
  return p;
}

// Appends tetrahedron `t` (its nodes in range), turned to positive volume; a flat one is refused.
void addTet(TetMesh& mesh, std::array<int, 4> t, const TextFile& file, long line,
            const std::string& item) {
  const auto p = [&](std::size_t k) { return mesh.nodes[static_cast<std::size_t>(t[k])]; };
  const double volume = tetVolume(p(0), p(1), p(2), p(3));
  double longest = 0.0;
  for (std::size_t a = 0; a < 4; ++a) {
    for (std::size_t b = a + 1; b < 4; ++b) longest = std::max(longest, (p(a) - p(b)).norm());
  }
  if (!(std::abs(6.0 * volume) > kFlatVolume * longest * longest * longest)) {
    file.failAt(line, item, "flat (zero volume): its four nodes lie in one plane or coincide");
  }
  if (volume < 0.0) std::swap(t[1], t[2]);
  mesh.tets.push_back(t);
}

// A node index of the file (counted from `base`) as an index into `nodes` nodes, or refused.
int nodeIndex(const TextFile& file, const std::string& item, const std::string& word,
              long long base, std::size_t nodes) {
  long long v = 0;
  if (!parseInteger(word, v) || v < base || v - base >= static_cast<long long>(nodes)) {
    file.fail(item, "node '" + word + "' is not one of the " + std::to_string(nodes) + " nodes (" +
                        std::to_string(base) + ".." +
                        std::to_string(base + static_cast<long long>(nodes) - 1) + ")");
  }
  return static_cast<int>(v - base);
}

// ---- TetGen ----

// The .node file's nodes into `mesh`; returns the index base (0 or 1) the first node's id gives.
long long readTetGenNodes(TextFile& file, double scale, TetMesh& mesh) {
  std::vector<std::string> w;
  long long count = 0, dimension = 3;
  if (!file.next(w)) file.fail("header", "the file holds nothing");
  if (!parseInteger(w[0], count) || count < 0) {
    file.fail("header", "expected the node count, got '" + w[0] + "'");
  }
  if (w.size() > 1 && (!parseInteger(w[1], dimension) || dimension != 3)) {
    file.fail("header", "dimension " + w[1] + ": only 3 is read");
  }
  if (count == 0) {
    file.fail("header",
              "counts no nodes (a .node file that leaves them to a .poly file is not read)");
  }
  file.requireCount(static_cast<double>(count), kMaxTetNodes, kMinNodeLineBytes, "header", "nodes");
  mesh.nodes.reserve(static_cast<std::size_t>(count));
  long long base = 0;
  for (long long i = 0; i < count; ++i) {
    if (!file.next(w)) {
      file.fail("nodes", "the file ends after " + std::to_string(i) + " of the " +
                             std::to_string(count) + " nodes its header counts");
    }
    long long id = 0;
    if (!parseInteger(w[0], id)) {
      file.fail("node " + std::to_string(base + i), "expected its id, got '" + w[0] + "'");
    }
    if (i == 0 && id != 0 && id != 1) {
      file.fail("node " + w[0], "the first node's id must be 0 or 1");
    }
    if (i == 0) base = id;
    const std::string item = "node " + std::to_string(base + i);
    if (id != base + i) file.fail(item, "out of turn: the line gives id " + w[0]);
    if (w.size() < 4) file.fail(item, "expected its id and 3 coordinates");
    mesh.nodes.push_back(readPoint(file, item, {w[1], w[2], w[3]}, scale));
  }
  if (file.next(w)) {
    file.fail("nodes", "the header counts " + std::to_string(count) +
                           "; the file holds more (this line is beyond them)");
  }
  return base;
}

// The .ele file's tetrahedra into `mesh`, node indices counted from `base`.
void readTetGenElements(TextFile& file, long long base, TetMesh& mesh) {
  std::vector<std::string> w;
  long long count = 0, corners = 4;
  if (!file.next(w)) file.fail("header", "the file holds nothing");
  if (!parseInteger(w[0], count) || count < 0) {
    file.fail("header", "expected the tetrahedron count, got '" + w[0] + "'");
  }
  if (w.size() > 1 && (!parseInteger(w[1], corners) || (corners != 4 && corners != 10))) {
    file.fail("header", "nodes per tetrahedron " + w[1] + ": only 4 and 10 are read");
  }
  file.requireCount(static_cast<double>(count), kMaxTetrahedra, kMinTetLineBytes, "header",
                    "tetrahedra");
  mesh.tets.reserve(static_cast<std::size_t>(count));
  for (long long i = 0; i < count; ++i) {
    if (!file.next(w)) {
      file.fail("tetrahedra", "the file ends after " + std::to_string(i) + " of the " +
                                  std::to_string(count) + " tetrahedra its header counts");
    }
    const std::string item = "tetrahedron " + std::to_string(base + i);
    long long id = 0;
    if (!parseInteger(w[0], id)) file.fail(item, "expected its id, got '" + w[0] + "'");
    if (w.size() < static_cast<std::size_t>(corners) + 1) {
      file.fail(item, "expected its id and " + std::to_string(corners) + " nodes");
    }
    std::array<int, 4> t{};
    for (std::size_t k = 0; k < 4; ++k) {
      t[k] = nodeIndex(file, item, w[k + 1], base, mesh.nodes.size());
    }
    addTet(mesh, t, file, file.line(), item);
  }
  if (file.next(w)) {
    file.fail("tetrahedra", "the header counts " + std::to_string(count) +
                                "; the file holds more (this line is beyond them)");
  }
}

// ---- VTK ----

// A VTK file's words one by one, across lines; file().line() is the last word's line.
class Words {
 public:
  explicit Words(TextFile& file) : file_(file) {}

  const std::string* peek() {
    while (at_ == words_.size()) {
      if (!file_.next(words_)) return nullptr;
      at_ = 0;
    }
    return &words_[at_];
  }
  // The next word; `what` names what was expected when the file ends first.
  std::string take(const std::string& item, const std::string& what) {
    if (peek() == nullptr) file_.fail(item, "the file ends before " + what);
    return words_[at_++];
  }
  long long integer(const std::string& item, const std::string& what) {
    const std::string w = take(item, what);
    long long v = 0;
    if (!parseInteger(w, v)) file_.fail(item, "expected " + what + ", got '" + w + "'");
    return v;
  }
  // Skips to the next blank line (the end of a METADATA block).
  void skipBlock() {
    at_ = words_.size();
    std::string line;
    while (file_.raw(line) && line.find_first_not_of(" \t\r") != std::string::npos) {
    }
  }
  TextFile& file() { return file_; }

 private:
  TextFile& file_;
  std::vector<std::string> words_;
  std::size_t at_ = 0;
};

// The cells as CELLS lists them: cell i's nodes are nodes[offsets[i] .. offsets[i + 1]), its
// record starting on lines[i].
struct VtkCells {
  bool read = false;
  std::vector<int> nodes;
  std::vector<std::size_t> offsets{0};
  std::vector<long> lines;
};

void readVtkHeader(TextFile& file) {
  std::string line;
  std::vector<std::string> w;
  if (!file.raw(line) || upper(line).rfind("# VTK DATAFILE VERSION", 0) != 0) {
    file.fail("header", "expected '# vtk DataFile Version', got '" + line.substr(0, 40) + "'");
  }
  if (!file.raw(line)) file.fail("header", "the file ends before its title");
  if (!file.next(w)) file.fail("header", "the file ends before ASCII");
  if (upper(w[0]) == "BINARY") {
    file.fail("header", "BINARY: binary VTK files are not read; save the file as ASCII");
  }
  if (upper(w[0]) != "ASCII") file.fail("header", "expected ASCII, got '" + w[0] + "'");
  if (!file.next(w) || upper(w[0]) != "DATASET" || w.size() < 2) {
    file.fail("header", "expected DATASET UNSTRUCTURED_GRID");
  }
  if (upper(w[1]) != "UNSTRUCTURED_GRID") {
    file.fail("DATASET", w[1] + ": only UNSTRUCTURED_GRID holds tetrahedra");
  }
}

void readVtkPoints(Words& in, double scale, TetMesh& mesh) {
  TextFile& file = in.file();
  if (!mesh.nodes.empty()) file.fail("POINTS", "given twice");
  const long long count = in.integer("POINTS", "the point count");
  const std::string type = in.take("POINTS", "the points' type");
  if (count < 0) file.fail("POINTS", "the count " + std::to_string(count) + " is negative");
  if (upper(type) != "FLOAT" && upper(type) != "DOUBLE") {
    file.fail("POINTS", "type " + type + ": expected float or double");
  }
  file.requireCount(static_cast<double>(count), kMaxTetNodes, 3 * kMinNumberBytes, "POINTS",
                    "points");
  mesh.nodes.reserve(static_cast<std::size_t>(count));
  for (long long i = 0; i < count; ++i) {
    const std::string item = "point " + std::to_string(i);
    std::array<std::string, 3> words;
    for (std::string& w : words) {
      w = in.take(item, "the " + std::to_string(count) + " points POINTS counts");
    }
    mesh.nodes.push_back(readPoint(file, item, words, scale));
  }
}

// A cell's node (0-based) into `cells`, checked against the points read.
void addCellNode(Words& in, const std::string& item, std::size_t points, VtkCells& cells) {
  cells.nodes.push_back(nodeIndex(in.file(), item, in.take(item, "the cell's nodes"), 0, points));
}

// CELLS n size, then n records "k i1 .. ik" (5.0 and before).
void readVtkCellList(Words& in, long header, long long count, long long size, std::size_t points,
                     VtkCells& cells) {
  for (long long i = 0; i < count; ++i) {
    const std::string item = "cell " + std::to_string(i);
    const long long k = in.integer(item, "the " + std::to_string(count) + " cells CELLS counts");
    cells.lines.push_back(in.file().line());
    if (k < 1 || k > size || static_cast<long long>(cells.nodes.size()) + k + i + 1 > size) {
      in.file().fail(item, "its " + std::to_string(k) + " nodes overrun the " +
                               std::to_string(size) + " numbers CELLS gives");
    }
    for (long long j = 0; j < k; ++j) addCellNode(in, item, points, cells);
    cells.offsets.push_back(cells.nodes.size());
  }
  if (static_cast<long long>(cells.nodes.size()) + count != size) {
    in.file().failAt(header, "CELLS",
                     "the cells hold " +
                         std::to_string(cells.nodes.size() + static_cast<std::size_t>(count)) +
                         " numbers; the header gives " + std::to_string(size));
  }
}

// CELLS offsets connectivity, then OFFSETS and CONNECTIVITY arrays (5.1).
void readVtkOffsets(Words& in, long long offsets, long long size, std::size_t points,
                    VtkCells& cells) {
  TextFile& file = in.file();
  in.take("OFFSETS", "OFFSETS");
  in.take("OFFSETS", "the offsets' type");
  for (long long i = 0; i < offsets; ++i) {
    const long long at =
        in.integer("OFFSETS", "the " + std::to_string(offsets) + " offsets CELLS counts");
    const long long last = i == 0 ? 0 : static_cast<long long>(cells.offsets.back());
    if ((i == 0 && at != 0) || at < last || at > size || (i + 1 == offsets && at != size)) {
      file.fail("offset " + std::to_string(i), "expected offsets rising from 0 to " +
                                                   std::to_string(size) + ", got " +
                                                   std::to_string(at));
    }
    if (i > 0) cells.offsets.push_back(static_cast<std::size_t>(at));
  }
  if (upper(in.take("CONNECTIVITY", "CONNECTIVITY")) != "CONNECTIVITY") {
    file.fail("CELLS", "expected CONNECTIVITY");
  }
  in.take("CONNECTIVITY", "the connectivity's type");
  for (std::size_t cell = 0; cell + 1 < cells.offsets.size(); ++cell) {
    const std::string item = "cell " + std::to_string(cell);
    in.peek();
    cells.lines.push_back(file.line());
    while (cells.nodes.size() < cells.offsets[cell + 1]) addCellNode(in, item, points, cells);
  }
}

void readVtkCells(Words& in, std::size_t points, VtkCells& cells) {
  TextFile& file = in.file();
  if (cells.read) file.fail("CELLS", "given twice");
  cells.read = true;
  if (points == 0) file.fail("CELLS", "before POINTS (or POINTS counts none)");
  const long long count = in.integer("CELLS", "the cell count"),
                  size = in.integer("CELLS", "the cells' size");
  const long header = file.line();
  if (count < 0 || size < 0) file.fail("CELLS", "negative counts");
  file.requireCount(static_cast<double>(count) + static_cast<double>(size), kUnbounded,
                    kMinNumberBytes, "CELLS", "numbers");
  const std::string* next = in.peek();
  const bool offsets = next != nullptr && upper(*next) == "OFFSETS";
  cells.nodes.reserve(static_cast<std::size_t>(size));
  if (offsets) readVtkOffsets(in, count, size, points, cells);
  if (!offsets) readVtkCellList(in, header, count, size, points, cells);
}

bool lowerDimension(long long type) {
  return (type >= 1 && type <= 9) || (type >= 21 && type <= 23);
}

// A cell type as text, with the name of the solid ones (types 11 to 14) that are not read.
std::string typeName(long long type) {
  static constexpr std::array<const char*, 4> kSolids = {"a voxel", "a hexahedron", "a wedge",
                                                         "a pyramid"};
  if (type < 11 || type > 14) return std::to_string(type);
  return std::to_string(type) + " (" + kSolids[static_cast<std::size_t>(type - 11)] + ")";
}

// CELL_TYPES: the tetrahedra of `cells` into `mesh`, cells of lower dimension skipped.
void readVtkTypes(Words& in, const VtkCells& cells, TetMesh& mesh) {
  TextFile& file = in.file();
  if (!cells.read) file.fail("CELL_TYPES", "before CELLS");
  const std::size_t count = cells.offsets.size() - 1;
  const long long given = in.integer("CELL_TYPES", "the cell count");
  if (given != static_cast<long long>(count)) {
    file.fail("CELL_TYPES",
              "counts " + std::to_string(given) + " cells; CELLS counts " + std::to_string(count));
  }
  for (std::size_t i = 0; i < count; ++i) {
    const std::string item = "cell " + std::to_string(i);
    const long long type = in.integer(item, "the " + std::to_string(count) + " cell types");
    const std::size_t nodes = cells.offsets[i + 1] - cells.offsets[i];
    if (lowerDimension(type)) continue;
    if (type != 10 && type != 24) {
      file.fail(item,
                "type " + typeName(type) +
                    " is not read: tetrahedra (10, 24) are kept, cells of lower dimension skipped");
    }
    if (nodes != (type == 10 ? 4u : 10u)) {
      file.failAt(cells.lines[i], item,
                  "a tetrahedron (type " + std::to_string(type) + ") of " + std::to_string(nodes) +
                      " nodes");
    }
    if (static_cast<long long>(mesh.tets.size()) >= kMaxTetrahedra) {
      file.fail(item, "more than the " + std::to_string(kMaxTetrahedra) + " tetrahedra read");
    }
    const auto* n = &cells.nodes[cells.offsets[i]];
    addTet(mesh, {n[0], n[1], n[2], n[3]}, file, cells.lines[i], item);
  }
}

// FIELD name arrays, each "name components tuples type" and its values: skipped.
void skipVtkField(Words& in) {
  in.take("FIELD", "the field's name");
  const long long arrays = in.integer("FIELD", "the array count");
  for (long long a = 0; a < arrays; ++a) {
    in.take("FIELD", "the array's name");
    const long long components = in.integer("FIELD", "the array's components"),
                    tuples = in.integer("FIELD", "the array's tuples");
    in.take("FIELD", "the array's type");
    if (components < 0 || tuples < 0) in.file().fail("FIELD", "negative counts");
    const double values = static_cast<double>(components) * static_cast<double>(tuples);
    in.file().requireCount(values, kUnbounded, kMinNumberBytes, "FIELD", "values");
    for (double v = 0; v < values; ++v) in.take("FIELD", "the array's values");
  }
}

}  // namespace

TetMesh readTetGen(const std::string& node_path, const std::string& ele_path, double scale) {
  if (!std::isfinite(scale) || scale <= 0.0) {
    throw MeshLoadError(node_path + ": scale must be a positive finite number");
  }
  TetMesh mesh;
  TextFile nodes(node_path, true);
  const long long base = readTetGenNodes(nodes, scale, mesh);
  TextFile elements(ele_path, true);
  readTetGenElements(elements, base, mesh);
  mesh.surface = boundaryTriangles(mesh.tets, mesh.nodes);
  return mesh;
}

TetMesh readVtkTets(const std::string& path, double scale) {
  if (!std::isfinite(scale) || scale <= 0.0) {
    throw MeshLoadError(path + ": scale must be a positive finite number");
  }
  TextFile file(path, false);
  readVtkHeader(file);
  Words in(file);
  TetMesh mesh;
  VtkCells cells;
  // The sections in the order VTK writes them, up to CELL_TYPES; what follows is not read.
  bool typed = false;
  while (!typed && in.peek() != nullptr) {
    const std::string key = upper(in.take("", ""));
    if (key == "POINT_DATA" || key == "CELL_DATA") break;
    if (key == "POINTS") {
      readVtkPoints(in, scale, mesh);
    } else if (key == "CELLS") {
      readVtkCells(in, mesh.nodes.size(), cells);
    } else if (key == "CELL_TYPES") {
      readVtkTypes(in, cells, mesh);
      typed = true;
    } else if (key == "FIELD") {
      skipVtkField(in);
    } else if (key == "METADATA") {
      in.skipBlock();
    } else {
      file.fail(key,
                "expected POINTS, CELLS, CELL_TYPES, FIELD, METADATA, POINT_DATA or CELL_DATA");
    }
  }
  if (!typed) file.fail("CELL_TYPES", "the file ends before its CELL_TYPES");
  mesh.surface = boundaryTriangles(mesh.tets, mesh.nodes);
  return mesh;
}

}  // namespace gf::sim
