#include "sim/mesh_import.hpp"

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/Importer.hpp>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <string_view>

namespace gf::sim {
namespace {

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// A count read from a header as text: exact up to 1e15, any size (1e+38) beyond (a cast to an
// integer type is undefined past its range).
std::string countText(double count) {
  std::ostringstream s;
  s << std::setprecision(15) << count;
  return s.str();
}

// The next line of `in` that is neither empty nor a comment ('#'), or "" at the end.
std::string contentLine(std::istream& in, long& number) {
  std::string line;
  while (std::getline(in, line)) {
    ++number;
    const std::size_t first = line.find_first_not_of(" \t\r");
    if (first != std::string::npos && line[first] != '#') return line.substr(first);
  }
  return "";
}

// The next line of `in` that is not empty, or "" at the end.
std::string nonEmptyLine(std::istream& in, long& number) {
  std::string line;
  while (std::getline(in, line)) {
    ++number;
    const std::size_t first = line.find_first_not_of(" \t\r");
    if (first != std::string::npos) return line.substr(first);
  }
  return "";
}

// Whether `prefix` (before "OFF") makes an OFF keyword whose counts follow it: [ST][C][N][4] for
// texture coordinates, colours, normals and homogeneous coordinates.
bool offPrefix(std::string_view prefix) {
  for (const std::string_view part : {"ST", "C", "N", "4"}) {
    if (prefix.starts_with(part)) prefix.remove_prefix(part.size());
  }
  return prefix.empty();
}

// Refuses line `number` of an OFF file of `size` bytes when a run of digits in it reads as a
// number above `size`: as a count of vertices, faces or coordinates each needs a byte or more.
void refuseCountsBeyond(const std::string& path, std::uintmax_t size, const std::string& line, long number) {
  for (std::size_t i = 0; i < line.size();) {
    if (!std::isdigit(static_cast<unsigned char>(line[i]))) {
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j < line.size() && std::isdigit(static_cast<unsigned char>(line[j]))) ++j;
    const double value = std::strtod(line.substr(i, j - i).c_str(), nullptr);
    if (value > static_cast<double>(size)) {
      throw MeshLoadError(path + ":" + std::to_string(number) + ": OFF header: " + line.substr(i, j - i) +
                          " is more than its " + std::to_string(size) + " bytes can hold as a count");
    }
    i = j;
  }
}

// Most vertices of an OFF face the importer reads (it skips a longer face).
constexpr long kMaxOffFaceVertices = 9;

// An OFF file's header against what the file holds: the counts it promises must fit in its size
// (checked before anything is allocated: a lying header cannot make us, or the importer, reserve
// gigabytes) and its lines must be there (the importer asserts, aborting the process, otherwise).
// Its lines must also read as the importer reads them, line by line: it takes the edge count
// from the next line when the counts line lacks it, and counts a face it skips (a comment line
// among the faces, a face of 0 or more than 9 vertices) out of the face count without moving
// on, so two of them wrap the count around and it reads far past its faces (a crash).
void checkOff(const std::string& path, std::uintmax_t size) {
  std::ifstream in(path);
  long number = 0;
  std::string line = contentLine(in, number);
  const std::size_t keyword = line.find("OFF");
  std::string counts;
  if (keyword != std::string::npos && offPrefix(std::string_view(line).substr(0, keyword))) {
    counts = line.substr(keyword + 3);
    if (counts.find_first_not_of(" \t\r") == std::string::npos) counts = contentLine(in, number);
  } else if (std::isdigit(static_cast<unsigned char>(line[0]))) {
    counts = line;  // no keyword, which the format allows: the counts come first
  } else {
    // nOFF (a dimension before the counts), a prefix the importer takes without the keyword
    // ("N219647295 327": it reserved 219 million vertices), or not OFF: the importer decides,
    // but no number it may read as a count or dimension can exceed the file's size.
    refuseCountsBeyond(path, size, line, number);
    const std::string next = contentLine(in, number);
    refuseCountsBeyond(path, size, next, number);
    return;
  }
  std::istringstream c(counts);
  double nv = -1, nf = -1, ne = -1;
  c >> nv >> nf >> ne;
  if (!(nv >= 0) || !(nf >= 0) || !(ne >= 0) || nv != std::floor(nv) || nf != std::floor(nf)) {
    throw MeshLoadError(path + ":" + std::to_string(number) + ": OFF header: expected vertex, face and edge counts");
  }
  // A vertex needs at least "0 0 0\n" (6 bytes), a face "3 0 1 2\n" (8).
  if (nv * 6 + nf * 8 > static_cast<double>(size)) {
    throw MeshLoadError(path + ":" + std::to_string(number) + ": OFF header promises " +
                        countText(nv) + " vertices and " +
                        countText(nf) + " faces, more than its " + std::to_string(size) +
                        " bytes can hold");
  }
  long vertices = 0, faces = 0;
  const long want_v = static_cast<long>(nv), want_f = static_cast<long>(nf);
  for (std::string l = nonEmptyLine(in, number); !l.empty(); l = nonEmptyLine(in, number)) {
    if (l[0] == '#') {
      throw MeshLoadError(path + ":" + std::to_string(number) + ": OFF: a comment among the " +
                          (vertices < want_v ? "vertices" : "faces") + " (the importer reads it as one)");
    }
    if (vertices < want_v) {
      ++vertices;
      continue;
    }
    std::istringstream f(l);
    long n = 0;
    f >> n;
    if (!f || n < 1) throw MeshLoadError(path + ":" + std::to_string(number) + ": OFF face " + std::to_string(faces) + ": expected a vertex count");
    if (n > kMaxOffFaceVertices) {
      throw MeshLoadError(path + ":" + std::to_string(number) + ": OFF face " + std::to_string(faces) + " has " +
                          std::to_string(n) + " vertices; the importer reads at most 9");
    }
    for (long k = 0; k < n; ++k) {
      long index = -1;
      f >> index;
      if (!f) throw MeshLoadError(path + ":" + std::to_string(number) + ": OFF face " + std::to_string(faces) + ": expected " + std::to_string(n) + " vertex indices");
      if (index < 0 || index >= want_v) {
        throw MeshLoadError(path + ":" + std::to_string(number) + ": OFF face " + std::to_string(faces) + " names vertex " +
                            std::to_string(index) + " of " + std::to_string(want_v));
      }
    }
    if (++faces == want_f) break;
  }
  if (vertices < want_v || faces < want_f) {
    throw MeshLoadError(path + ": OFF header promises " + std::to_string(want_v) + " vertices and " + std::to_string(want_f) +
                        " faces; the file holds " + std::to_string(vertices) + " and " + std::to_string(faces));
  }
}

// A binary STL's triangle count against its size (84-byte header, 50 bytes a triangle).
void checkStl(const std::string& path, std::uintmax_t size) {
  std::ifstream in(path, std::ios::binary);
  char head[84] = {};
  in.read(head, sizeof head);
  if (in.gcount() < 84 || std::strncmp(head, "solid", 5) == 0) return;  // ASCII STL: the importer reads it
  std::uint32_t count = 0;
  std::memcpy(&count, head + 80, 4);
  if (84 + 50 * static_cast<std::uintmax_t>(count) > size) {
    throw MeshLoadError(path + ": binary STL header promises " + std::to_string(count) + " triangles, more than its " +
                        std::to_string(size) + " bytes hold");
  }
}

// A PLY header's element counts against the file's size (at least one byte per element), and
// its end: the importer reads a header without an end_header line forever.
void checkPly(const std::string& path, std::uintmax_t size) {
  constexpr long kMaxHeaderLines = 10000;
  std::ifstream in(path, std::ios::binary);
  std::string line;
  long number = 0;
  double elements = 0;
  bool ended = false;
  while (!ended && number < kMaxHeaderLines && std::getline(in, line)) {
    ++number;
    std::istringstream l(line);
    std::string word, name;
    double count = -1;
    l >> word;
    ended = word == "end_header";
    if (word != "element") continue;
    l >> name >> count;
    if (!(count >= 0)) throw MeshLoadError(path + ":" + std::to_string(number) + ": PLY element " + name + ": expected a count");
    elements += count;
  }
  if (!ended) {
    throw MeshLoadError(path + ": PLY header has no end_header line" +
                        (number < kMaxHeaderLines ? std::string() : " in its first 10000 lines"));
  }
  if (elements > static_cast<double>(size)) {
    throw MeshLoadError(path + ": PLY header promises " + countText(elements) +
                        " elements, more than its " + std::to_string(size) + " bytes hold");
  }
}

// Headers that lie about what the file holds, before the importer sees them.
void checkHeader(const std::string& path) {
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) throw MeshLoadError(path + ": cannot read mesh: " + ec.message());
  const std::string ext = lower(std::filesystem::path(path).extension().string());
  if (ext == ".off") checkOff(path, size);
  if (ext == ".stl") checkStl(path, size);
  if (ext == ".ply") checkPly(path, size);
}

// The importer's faces before its post-processing sees them: its steps assert (aborting the
// process) on a face without vertices, which a malformed file gives (a binary PLY whose face list
// the parser misreads), and read past the vertices for an index beyond them.
void checkFaces(const std::string& path, const aiScene& scene) {
  for (unsigned mi = 0; mi < scene.mNumMeshes; ++mi) {
    const aiMesh& mesh = *scene.mMeshes[mi];
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      const std::string where = path + ": face " + std::to_string(f) + " of mesh " + std::to_string(mi);
      if (face.mNumIndices == 0 || face.mIndices == nullptr) throw MeshLoadError(where + " has no vertex");
      for (unsigned k = 0; k < face.mNumIndices; ++k) {
        if (face.mIndices[k] >= mesh.mNumVertices) {
          throw MeshLoadError(where + " names vertex " + std::to_string(face.mIndices[k]) + " of " +
                              std::to_string(mesh.mNumVertices));
        }
      }
    }
  }
}

const std::string kAxisNames[] = {"X", "Y", "Z"};

// Collada's declared unit (<unit meter="...">) and up axis (<up_axis>Z_UP</up_axis>), from the
// file's <asset> block.
void colladaAsset(const std::string& path, MeshFileInfo& info) {
  std::ifstream in(path);
  std::string head(16384, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  if (const std::size_t at = head.find("<unit"); at != std::string::npos) {
    const std::size_t end = head.find('>', at);
    if (const std::size_t m = head.find("meter=", at); m != std::string::npos && m < end) {
      const std::size_t value = head.find_first_of("\"'", m);  // meter="0.01" or meter='0.01'
      if (value != std::string::npos && value < end) info.declared_unit_m = std::strtod(head.c_str() + value + 1, nullptr);
    }
  }
  if (const std::size_t at = head.find("<up_axis>"); at != std::string::npos) {
    const std::size_t axis = head.find_first_not_of(" \t\r\n", at + 9);  // X_UP, Y_UP or Z_UP
    if (axis != std::string::npos) info.declared_up = head.substr(axis, 1);
  }
  info.unit_and_up_applied = true;  // the Collada importer scales and turns the root node
}

void addParts(const aiScene& scene, const aiNode& node, const aiMatrix4x4& parent, MeshFileInfo& info) {
  const aiMatrix4x4 global = parent * node.mTransformation;
  for (unsigned i = 0; i < node.mNumMeshes; ++i) {
    const aiMesh& mesh = *scene.mMeshes[node.mMeshes[i]];
    MeshPart part;
    part.mesh = mesh.mName.C_Str();
    part.node = node.mName.C_Str();
    part.vertices = static_cast<int>(mesh.mNumVertices);
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) part.triangles += mesh.mFaces[f].mNumIndices >= 3 ? static_cast<int>(mesh.mFaces[f].mNumIndices) - 2 : 0;
    for (int r = 0; r < 4; ++r) {
      for (int c = 0; c < 4; ++c) part.transform(r, c) = global[static_cast<unsigned>(r)][static_cast<unsigned>(c)];
    }
    info.parts.push_back(part);
  }
  for (unsigned i = 0; i < node.mNumChildren; ++i) addParts(scene, *node.mChildren[i], global, info);
}

}  // namespace

MeshFileInfo describeMeshFile(const std::string& path) {
  checkHeader(path);
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(path, 0);
  if (scene == nullptr) throw MeshLoadError(path + ": cannot read mesh: " + importer.GetErrorString());
  checkFaces(path, *scene);
  MeshFileInfo info;
  int up_axis = -1;
  bool up_negative = false;
  if (scene->mMetaData) {
    for (unsigned i = 0; i < scene->mMetaData->mNumProperties; ++i) {
      const std::string key = scene->mMetaData->mKeys[i].C_Str();
      const aiMetadataEntry& e = scene->mMetaData->mValues[i];
      if (key == "SourceAsset_Format" && e.mType == AI_AISTRING) info.format = static_cast<const aiString*>(e.mData)->C_Str();
      // FBX: centimetres per unit, and the up axis as 0, 1, 2 with a sign.
      double unit = 0.0;
      if (e.mType == AI_DOUBLE) unit = *static_cast<const double*>(e.mData);
      if (e.mType == AI_FLOAT) unit = *static_cast<const float*>(e.mData);
      if (key == "UnitScaleFactor" && unit > 0.0) info.declared_unit_m = 0.01 * unit;
      if (key == "UpAxis" && e.mType == AI_INT32) up_axis = std::clamp(*static_cast<const std::int32_t*>(e.mData), 0, 2);
      if (key == "UpAxisSign" && e.mType == AI_INT32) up_negative = *static_cast<const std::int32_t*>(e.mData) < 0;
    }
  }
  if (up_axis >= 0) info.declared_up = (up_negative ? "-" : "") + kAxisNames[up_axis];
  const std::string ext = lower(std::filesystem::path(path).extension().string());
  if (ext == ".dae") colladaAsset(path, info);
  if (ext == ".gltf" || ext == ".glb") {
    info.declared_unit_m = 1.0;
    info.declared_up = kAxisNames[1];
  }
  if (scene->mRootNode) addParts(*scene, *scene->mRootNode, aiMatrix4x4(), info);
  return info;
}

RawMesh readMeshFile(const std::string& path, double scale) {
  if (!std::isfinite(scale) || scale <= 0.0) {
    throw MeshLoadError(path + ": scale must be a positive finite number");
  }
  checkHeader(path);
  Assimp::Importer importer;
  // Only triangles are kept; welding is ours (assimp's ignores tolerance and splits by normals).
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  // Read, check the faces, then triangulate and flatten the node tree.
  const aiScene* scene = importer.ReadFile(path, 0);
  if (scene != nullptr) {
    checkFaces(path, *scene);
    scene = importer.ApplyPostProcessing(aiProcess_Triangulate | aiProcess_PreTransformVertices |
                                         aiProcess_SortByPType);
  }
  if (scene == nullptr) {
    throw MeshLoadError(path + ": cannot read mesh: " + importer.GetErrorString());
  }
  RawMesh raw;
  for (unsigned mi = 0; mi < scene->mNumMeshes; ++mi) {
    const aiMesh* mesh = scene->mMeshes[mi];
    if (!(mesh->mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;
    const auto base = static_cast<std::int32_t>(raw.positions.size());
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      const aiVector3D& p = mesh->mVertices[v];
      const Vec3 q = scale * Vec3(p.x, p.y, p.z);
      if (!q.allFinite()) {
        throw MeshLoadError(path + ": vertex " + std::to_string(v) + " of mesh " +
                            std::to_string(mi) + " is not finite");
      }
      raw.positions.push_back(q);
    }
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices != 3) continue;
      for (unsigned k = 0; k < 3; ++k) {
        if (face.mIndices[k] >= mesh->mNumVertices) {
          throw MeshLoadError(path + ": face " + std::to_string(f) + " of mesh " + std::to_string(mi) + " names vertex " +
                              std::to_string(face.mIndices[k]) + " of " + std::to_string(mesh->mNumVertices));
        }
      }
      raw.triangles.push_back({base + static_cast<std::int32_t>(face.mIndices[0]),
                               base + static_cast<std::int32_t>(face.mIndices[1]),
                               base + static_cast<std::int32_t>(face.mIndices[2])});
    }
  }
  if (raw.triangles.empty()) throw MeshLoadError(path + ": the file holds no triangle");
  return raw;
}

Mesh loadMesh(const std::string& path, double scale, const MeshBuildSettings& settings) {
  const RawMesh raw = readMeshFile(path, scale);
  Mesh mesh = buildMesh(raw.positions, raw.triangles, settings);
  if (mesh.faceCount() == 0) {
    throw MeshLoadError(path + ": every triangle is degenerate (zero area)");
  }
  return mesh;
}

std::shared_ptr<const Mesh> MeshCache::load(const std::string& path, double scale) {
  std::shared_ptr<const Mesh>& slot = meshes_[{path, scale}];
  if (!slot) {
    slot = std::make_shared<const Mesh>(loadMesh(path, scale));
    ++files_read_;
  }
  return slot;
}

}  // namespace gf::sim
