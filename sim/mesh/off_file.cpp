#include "sim/mesh/off_file.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <string_view>
#include <vector>

namespace gf::sim::detail {
namespace {

// Most vertices a non-convex polygon may have: ear clipping takes time cubic in it.
constexpr std::size_t kMaxEarClippedVertices = 256;
// Bytes a vertex ("0 0 0\n") and a triangle ("3 0 1 2\n") take at least.
constexpr double kMinVertexBytes = 6, kMinFaceBytes = 8;

// The file's content lines: a '#' starts a comment to the end of its line; blank lines are skipped.
class OffLines {
 public:
  explicit OffLines(const std::string& path) : path_(path), in_(path) {
    if (!in_) throw MeshLoadError(path + ": cannot read mesh: cannot open the file");
  }

  // The next content line's words, or false at the end of the file.
  bool next(std::vector<std::string>& words) {
    std::string line;
    while (std::getline(in_, line)) {
      ++number_;
      if (const std::size_t hash = line.find('#'); hash != std::string::npos) line.erase(hash);
      words.clear();
      std::istringstream s(line);
      for (std::string w; s >> w;) words.push_back(w);
      if (!words.empty()) return true;
    }
    return false;
  }

  [[noreturn]] void fail(const std::string& why) const {
    throw MeshLoadError(path_ + ":" + std::to_string(number_) + ": OFF " + why);
  }
  const std::string& path() const { return path_; }
  long line() const { return number_; }

 private:
  std::string path_;
  std::ifstream in_;
  long number_ = 0;
};

// `word` as a number, or false when it is not one in whole.
bool number(const std::string& word, double& value) {
  char* end = nullptr;
  errno = 0;
  value = std::strtod(word.c_str(), &end);
  return end != word.c_str() && *end == '\0';
}

// `word` as a whole number in [0, limit], or false.
bool count(const std::string& word, double limit, long& value) {
  double v = 0.0;
  if (!number(word, v) || !(v >= 0.0) || v != std::floor(v) || v > limit) return false;
  value = static_cast<long>(v);
  return true;
}

// A count as text: exact up to 1e15, any size (1e+38) beyond.
std::string countText(double c) {
  std::ostringstream s;
  s << std::setprecision(15) << c;
  return s.str();
}

// What the keyword says: [ST][C][N][4][n]OFF, each prefix optional in that order.
struct Keyword {
  bool found = false, homogeneous = false, dimension = false;
};

Keyword readKeyword(const std::string& word) {
  Keyword k;
  if (word.size() < 3 || word.compare(word.size() - 3, 3, "OFF") != 0) return k;
  std::string_view prefix(word.data(), word.size() - 3);
  for (const std::string_view part : {"ST", "C", "N", "4", "n"}) {
    if (!prefix.starts_with(part)) continue;
    prefix.remove_prefix(part.size());
    if (part == "4") k.homogeneous = true;
    if (part == "n") k.dimension = true;
  }
  k.found = prefix.empty();
  return k;
}

// The header: the keyword (optional), the dimension after nOFF, then the vertex, face and
// (optional) edge counts, checked against the file's size before anything is reserved for them.
Keyword readHeader(OffLines& lines, OffFile& off, std::uintmax_t size) {
  std::vector<std::string> w;
  if (!lines.next(w)) lines.fail("file holds nothing");
  const Keyword k = readKeyword(w[0]);
  std::size_t at = k.found ? 1 : 0;
  double v = 0.0;
  if (!k.found && !number(w[0], v)) lines.fail("header: expected the OFF keyword or the vertex, face and edge counts, got '" + w[0] + "'");
  if (at < w.size() && w[at] == "BINARY") lines.fail("header: binary OFF is not read; save the file as text");
  const auto words = [&] {  // the next word, on the next content line when this one has no more
    if (at < w.size()) return;
    if (!lines.next(w)) lines.fail("header: the file ends before the vertex, face and edge counts");
    at = 0;
  };
  if (k.dimension) {
    words();
    long dimension = 0;
    if (!count(w[at], 1e6, dimension) || dimension != 3) lines.fail("header: dimension " + w[at] + ": only 3 is read");
    ++at;
  }
  words();
  double nv = -1, nf = -1, ne = 0;
  if (w.size() < at + 2 || !number(w[at], nv) || !number(w[at + 1], nf) ||
      (w.size() > at + 2 && !number(w[at + 2], ne)) || !(nv >= 0) || !(nf >= 0) || !(ne >= 0) ||
      nv != std::floor(nv) || nf != std::floor(nf)) {
    lines.fail("header: expected vertex, face and edge counts");
  }
  if (nv * kMinVertexBytes + nf * kMinFaceBytes > static_cast<double>(size)) {
    throw MeshLoadError(lines.path() + ":" + std::to_string(lines.line()) + ": OFF header promises " + countText(nv) +
                        " vertices and " + countText(nf) + " faces, more than its " + std::to_string(size) +
                        " bytes can hold");
  }
  off.vertices = static_cast<long>(nv);
  off.faces = static_cast<long>(nf);
  return k;
}

// The header counts more than the file holds.
[[noreturn]] void endsEarly(const OffLines& lines, const OffFile& off, long vertices, long faces) {
  throw MeshLoadError(lines.path() + ": OFF header counts " + std::to_string(off.vertices) + " vertices and " +
                      std::to_string(off.faces) + " faces; the file holds " + std::to_string(vertices) + " and " +
                      std::to_string(faces));
}

void readVertices(OffLines& lines, const Keyword& k, double scale, OffFile& off) {
  std::vector<std::string> w;
  const std::size_t coordinates = k.homogeneous ? 4 : 3;
  off.mesh.positions.reserve(static_cast<std::size_t>(off.vertices));
  for (long i = 0; i < off.vertices; ++i) {
    if (!lines.next(w)) endsEarly(lines, off, i, 0);
    double c[4] = {0, 0, 0, 1};
    for (std::size_t j = 0; j < coordinates; ++j) {
      if (j >= w.size() || !number(w[j], c[j])) {
        lines.fail("vertex " + std::to_string(i) + ": expected " + std::to_string(coordinates) + " coordinates");
      }
    }
    const Vec3 p = scale / c[3] * Vec3(c[0], c[1], c[2]);
    if (!p.allFinite()) lines.fail("vertex " + std::to_string(i) + " is not finite");
    off.mesh.positions.push_back(p);
  }
}

// Whether the polygon turns one way only about `normal`: then a fan splits it.
bool convex(const std::vector<Vec3>& p, const Vec3& normal) {
  const std::size_t n = p.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 turn = (p[(i + 1) % n] - p[i]).cross(p[(i + 2) % n] - p[(i + 1) % n]);
    if (turn.dot(normal) < 0.0) return false;
  }
  return true;
}

// Whether q lies in triangle abc (about `normal`, edges included).
bool inside(const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& normal) {
  return (b - a).cross(q - a).dot(normal) >= 0.0 && (c - b).cross(q - b).dot(normal) >= 0.0 &&
         (a - c).cross(q - c).dot(normal) >= 0.0;
}

// Ear clipping of a simple polygon (indices `face` into `pos`): triangles appended to `out`;
// what is left when no ear is found (a self-touching polygon) is split as a fan.
void earClip(std::vector<std::int32_t> face, const std::vector<Vec3>& pos, const Vec3& normal,
             std::vector<std::array<std::int32_t, 3>>& out) {
  const auto at = [&](std::size_t i) { return pos[static_cast<std::size_t>(face[i % face.size()])]; };
  while (face.size() > 3) {
    bool clipped = false;
    for (std::size_t i = 0; i < face.size() && !clipped; ++i) {
      const Vec3 a = at(i), b = at(i + 1), c = at(i + 2);
      if ((b - a).cross(c - b).dot(normal) <= 0.0) continue;  // a reflex or flat corner
      bool empty = true;
      for (std::size_t j = 3; j < face.size() && empty; ++j) empty = !inside(at(i + j), a, b, c, normal);
      if (!empty) continue;
      out.push_back({face[i], face[(i + 1) % face.size()], face[(i + 2) % face.size()]});
      face.erase(face.begin() + static_cast<std::ptrdiff_t>((i + 1) % face.size()));
      clipped = true;
    }
    if (!clipped) break;
  }
  for (std::size_t i = 1; i + 1 < face.size(); ++i) out.push_back({face[0], face[i], face[i + 1]});
}

void splitPolygon(OffLines& lines, long index, const std::vector<std::int32_t>& face, OffFile& off) {
  auto& out = off.mesh.triangles;
  std::vector<Vec3> p;
  for (const std::int32_t v : face) p.push_back(off.mesh.positions[static_cast<std::size_t>(v)]);
  Vec3 normal = Vec3::Zero();  // Newell's normal
  for (std::size_t i = 0; i < p.size(); ++i) normal += p[i].cross(p[(i + 1) % p.size()]);
  if (normal.squaredNorm() == 0.0 || convex(p, normal)) {
    for (std::size_t i = 1; i + 1 < face.size(); ++i) out.push_back({face[0], face[i], face[i + 1]});
    return;
  }
  if (face.size() > kMaxEarClippedVertices) {
    lines.fail("face " + std::to_string(index) + ": a non-convex polygon of " + std::to_string(face.size()) +
               " vertices; at most " + std::to_string(kMaxEarClippedVertices) + " are split into triangles");
  }
  earClip(face, off.mesh.positions, normal, out);
}

void readFaces(OffLines& lines, OffFile& off) {
  std::vector<std::string> w;
  std::vector<std::int32_t> face;
  for (long i = 0; i < off.faces; ++i) {
    if (!lines.next(w)) endsEarly(lines, off, off.vertices, i);
    const std::string which = "face " + std::to_string(i);
    long n = 0;
    if (!count(w[0], 1e9, n) || n == 0) lines.fail(which + ": expected a vertex count, got '" + w[0] + "'");
    if (w.size() < static_cast<std::size_t>(n) + 1) {
      lines.fail(which + ": expected " + std::to_string(n) + " vertex indices, got " + std::to_string(w.size() - 1));
    }
    face.clear();
    for (long k = 1; k <= n; ++k) {
      long v = -1;
      if (!count(w[static_cast<std::size_t>(k)], 1e15, v) || v >= off.vertices) {
        lines.fail(which + " names vertex " + w[static_cast<std::size_t>(k)] + " of " + std::to_string(off.vertices));
      }
      face.push_back(static_cast<std::int32_t>(v));
    }
    if (n == 3) off.mesh.triangles.push_back({face[0], face[1], face[2]});
    if (n > 3) splitPolygon(lines, i, face, off);  // faces of 1 or 2 vertices are points and lines
  }
  if (lines.next(w)) {
    lines.fail("header counts " + std::to_string(off.vertices) + " vertices and " + std::to_string(off.faces) +
               " faces; the file holds more (this line is beyond them)");
  }
}

}  // namespace

OffFile readOffFile(const std::string& path, double scale) {
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) throw MeshLoadError(path + ": cannot read mesh: " + ec.message());
  OffLines lines(path);
  OffFile off;
  const Keyword k = readHeader(lines, off, size);
  readVertices(lines, k, scale, off);
  readFaces(lines, off);
  return off;
}

}  // namespace gf::sim::detail
