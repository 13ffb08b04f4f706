#include "sim/mesh/mesh_import.hpp"

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
#include <vector>

#include "sim/mesh/off_file.hpp"

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

// A binary STL's triangle count against its size (84-byte header, 50 bytes a triangle), both
// ways: fewer bytes than the count needs, or room for more whole triangles than it counts. A
// file starting with "solid" is ASCII unless its size is exactly what its count needs.
void checkStl(const std::string& path, std::uintmax_t size) {
  std::ifstream in(path, std::ios::binary);
  char head[84] = {};
  in.read(head, sizeof head);
  if (in.gcount() < 84) return;  // too short for binary: the importer decides
  std::uint32_t count = 0;
  std::memcpy(&count, head + 80, 4);
  const std::uintmax_t needs = 84 + 50 * static_cast<std::uintmax_t>(count);
  if (std::strncmp(head, "solid", 5) == 0 && needs != size) return;  // ASCII STL: the importer reads it
  if (needs > size) {
    throw MeshLoadError(path + ": binary STL header promises " + std::to_string(count) + " triangles, more than its " +
                        std::to_string(size) + " bytes hold");
  }
  if (const std::uintmax_t more = (size - needs) / 50; more > 0) {
    throw MeshLoadError(path + ": binary STL header counts " + std::to_string(count) + " triangles; the file holds " +
                        std::to_string(size - needs) + " bytes more, room for " + std::to_string(more) +
                        " more (a wrong count would drop them)");
  }
}

// A PLY file's header: its format and elements, each with its properties' sizes in bytes.
struct PlyProperty {
  int bytes = 0;       ///< a scalar's size, or a list's item size
  int count_bytes = 0; ///< a list's count size; 0 for a scalar
  bool count_signed = false;
  bool is_signed = false;  ///< the scalar's or the items' type
  bool is_float = false;
};
struct PlyElement {
  std::string name;
  double count = 0;
  std::vector<PlyProperty> properties;
};
struct PlyHeader {
  std::string format;  ///< "ascii", "binary_little_endian" or "binary_big_endian"
  std::vector<PlyElement> elements;
  std::streamoff body = 0;  ///< where the elements start
  long header_lines = 0;    ///< the header's lines, end_header's included
};

// Bytes of a PLY type (0 for an unknown name) and whether it is signed.
int plyBytes(const std::string& type, bool* is_signed = nullptr) {
  static const std::pair<const char*, int> kTypes[] = {
      {"char", -1}, {"uchar", 1}, {"int8", -1}, {"uint8", 1}, {"short", -2}, {"ushort", 2}, {"int16", -2},
      {"uint16", 2}, {"int", -4}, {"uint", 4}, {"int32", -4}, {"uint32", 4}, {"float", 4}, {"float32", 4},
      {"double", 8}, {"float64", 8}};
  for (const auto& [name, bytes] : kTypes) {
    if (type != name) continue;
    if (is_signed) *is_signed = bytes < 0;
    return std::abs(bytes);
  }
  return 0;
}

// The header, its end required (the importer reads a header without an end_header line forever)
// and its counts checked against the file's size (at least one byte per element).
// A header line's words as the importer splits them: at spaces and tabs only, a carriage return
// ending the line dropped. Another space character (a vertical tab, a form feed) is part of a
// word to it: "end_header\v..." ends no header, and its reader seeks for the end forever.
std::vector<std::string> plyHeaderWords(std::string line) {
  if (line.ends_with('\r')) line.pop_back();
  std::vector<std::string> words;
  for (std::size_t at = 0; at < line.size();) {
    const std::size_t end = std::min(line.find_first_of(" \t", at), line.size());
    if (end > at) words.push_back(line.substr(at, end - at));
    at = end + 1;
  }
  return words;
}

PlyHeader readPlyHeader(const std::string& path, std::ifstream& in, std::uintmax_t size) {
  constexpr long kMaxHeaderLines = 10000;
  PlyHeader h;
  std::string line;
  long number = 0;
  double elements = 0;
  bool ended = false;
  while (!ended && number < kMaxHeaderLines && std::getline(in, line)) {
    ++number;
    const std::vector<std::string> w = plyHeaderWords(line);
    const auto nth = [&w](std::size_t i) { return i < w.size() ? w[i] : std::string(); };
    const std::string word = nth(0), a = nth(1), b = nth(2), c = nth(3);
    ended = word == "end_header";
    if (word == "format") {
      // The importer read a header with a garbled format word (fuzz_mesh) for over a minute.
      if (a != "ascii" && a != "binary_little_endian" && a != "binary_big_endian") {
        throw MeshLoadError(path + ":" + std::to_string(number) +
                            ": PLY format: expected ascii, binary_little_endian or binary_big_endian, got '" + a + "'");
      }
      h.format = a;
    }
    if (word == "property" && !h.elements.empty()) {
      PlyProperty p;
      const std::string& type = a == "list" ? c : a;
      p.bytes = plyBytes(type, &p.is_signed);
      p.is_float = type.starts_with("float") || type == "double";
      if (a == "list") p.count_bytes = plyBytes(b, &p.count_signed);
      if (p.bytes == 0 || (a == "list" && p.count_bytes == 0)) {
        throw MeshLoadError(path + ":" + std::to_string(number) + ": PLY property: unknown type in '" + line + "'");
      }
      if (a == "list" && (b.starts_with("float") || b == "double")) {
        throw MeshLoadError(path + ":" + std::to_string(number) + ": PLY property: a list's count type must be an integer type, got '" + b + "'");
      }
      h.elements.back().properties.push_back(p);
    }
    if (word != "element") continue;
    const double count = std::strtod(b.c_str(), nullptr);
    if (!(count >= 0)) throw MeshLoadError(path + ":" + std::to_string(number) + ": PLY element " + a + ": expected a count");
    h.elements.push_back({a, count, {}});
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
  h.body = in.tellg();
  h.header_lines = number;
  return h;
}

// The header's element counts ("vertex 8, face 12").
std::string plyCounts(const PlyHeader& h) {
  std::string s;
  for (const PlyElement& e : h.elements) s += (s.empty() ? "" : ", ") + e.name + " " + countText(e.count);
  return s;
}

// The largest count a list's count type holds (a negative one is no count).
double plyCountLimit(const PlyProperty& p) {
  return std::ldexp(1.0, 8 * p.count_bytes - (p.count_signed ? 1 : 0)) - 1.0;
}

// Whether assimp's reader takes `word` whole as a value of the property's type: digits (after a
// sign for a signed type) for an integer, [sign] digits [. digits] [e [sign] digits] or nan/inf
// for a floating-point one. Its number readers stop at the first character they do not take
// and read the rest as the next value ("0+4000000000": a 0, then a count of 4e9).
bool plyWordReadWhole(const std::string& word, bool is_signed, bool is_float) {
  std::size_t i = 0;
  const auto digits = [&] {
    const std::size_t from = i;
    while (i < word.size() && std::isdigit(static_cast<unsigned char>(word[i]))) ++i;
    return i > from;
  };
  if ((is_signed || is_float) && i < word.size() && (word[i] == '+' || word[i] == '-')) ++i;
  if (!is_float) return digits() && i == word.size();
  std::string rest = lower(word.substr(i));
  if (rest == "nan" || rest == "inf" || rest == "infinity") return true;
  const bool whole = digits();
  bool fraction = false;
  if (i < word.size() && word[i] == '.') {
    ++i;
    fraction = digits();
  }
  if (!whole && !fraction) return false;
  if (i < word.size() && (word[i] == 'e' || word[i] == 'E')) {
    ++i;
    if (i < word.size() && (word[i] == '+' || word[i] == '-')) ++i;
    if (!digits()) return false;
  }
  return i == word.size();
}

// One ASCII element's line: a word per scalar; per list, a whole count its type holds and as
// many items after it; each word one assimp reads whole. The importer sizes a list by its count
// before reading the items (a count of 4e10 asked it for 300 GB).
void checkPlyAsciiLine(const std::string& path, long number, const std::string& line, const PlyElement& e) {
  std::istringstream words(line);
  std::string word;
  const auto where = [&](std::size_t k) {
    return path + ":" + std::to_string(number) + ": PLY " + e.name + " property " + std::to_string(k + 1) + ": ";
  };
  const auto value = [&](std::size_t k, const PlyProperty& p) {
    if (!(words >> word)) throw MeshLoadError(where(k) + "the line ends before it");
    if (!plyWordReadWhole(word, p.is_signed, p.is_float)) {
      throw MeshLoadError(where(k) + "'" + word + "' is not " + (p.is_float ? "a number" : p.is_signed ? "a whole number" : "a whole number from 0"));
    }
  };
  for (std::size_t k = 0; k < e.properties.size(); ++k) {
    const PlyProperty& p = e.properties[k];
    if (p.count_bytes == 0) {
      value(k, p);
      continue;
    }
    if (!(words >> word)) throw MeshLoadError(where(k) + "the line ends before it");
    const std::string digits = word.starts_with('+') && p.count_signed ? word.substr(1) : word;
    const bool whole = !digits.empty() && digits.size() <= 15 && plyWordReadWhole(digits, false, false);
    const double count = whole ? std::strtod(digits.c_str(), nullptr) : -1.0;
    if (!whole || count > plyCountLimit(p)) {
      throw MeshLoadError(where(k) + "list count '" + word + "' is not a whole number from 0 to " + countText(plyCountLimit(p)));
    }
    for (double i = 0; i < count; ++i) {
      if (!(words >> word)) {
        throw MeshLoadError(where(k) + "list counts " + countText(count) + " items; the line holds " + countText(i));
      }
      if (!plyWordReadWhole(word, p.is_signed, p.is_float)) {
        throw MeshLoadError(where(k) + "item '" + word + "' is not " + (p.is_float ? "a number" : "a whole number"));
      }
    }
  }
}

// An ASCII PLY holds one element a line: as many content lines as the header counts elements,
// each holding what its element's properties read.
void checkPlyAsciiBody(const std::string& path, std::ifstream& in, const PlyHeader& h) {
  double counted = 0, lines = 0;
  for (const PlyElement& e : h.elements) counted += e.count;
  std::size_t element = 0;
  double of_element = 0;  // lines of the current element so far
  long number = h.header_lines;
  for (std::string line; std::getline(in, line);) {
    ++number;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    ++lines;
    while (element < h.elements.size() && of_element >= h.elements[element].count) {
      ++element;
      of_element = 0;
    }
    if (element < h.elements.size()) checkPlyAsciiLine(path, number, line, h.elements[element]);
    ++of_element;
  }
  if (lines != counted) {
    throw MeshLoadError(path + ": PLY header counts " + countText(counted) + " elements (" + plyCounts(h) +
                        "); the file holds " + countText(lines) + " lines of them");
  }
}

// A binary PLY's elements walked through (lists by their counts) to the end of the file: the
// header may count neither more elements than the file holds nor fewer.
void checkPlyBinaryBody(const std::string& path, std::ifstream& in, const PlyHeader& h, std::uintmax_t size) {
  const bool big_endian = h.format == "binary_big_endian";
  std::uintmax_t at = static_cast<std::uintmax_t>(h.body);
  for (const PlyElement& e : h.elements) {
    const auto lists = std::count_if(e.properties.begin(), e.properties.end(), [](const PlyProperty& p) { return p.count_bytes > 0; });
    for (double i = 0; i < e.count && at <= size; ++i) {
      if (lists == 0) {  // fixed-size rows: all at once
        std::uintmax_t row = 0;
        for (const PlyProperty& p : e.properties) row += static_cast<std::uintmax_t>(p.bytes);
        at += row * static_cast<std::uintmax_t>(e.count);
        break;
      }
      for (const PlyProperty& p : e.properties) {
        if (p.count_bytes == 0 || p.bytes == 0) {
          at += static_cast<std::uintmax_t>(p.bytes);
          continue;
        }
        unsigned char b[4] = {};  // a count is an integer type of at most 4 bytes (readPlyHeader)
        in.seekg(static_cast<std::streamoff>(at));
        if (!in.read(reinterpret_cast<char*>(b), p.count_bytes)) break;
        std::uint32_t n = 0;
        for (int k = 0; k < p.count_bytes; ++k) n = n << 8 | b[big_endian ? k : p.count_bytes - 1 - k];
        if (p.count_signed && (b[big_endian ? 0 : p.count_bytes - 1] & 0x80)) {  // the importer reads it unsigned: 4e9
          throw MeshLoadError(path + ": PLY " + e.name + " " + countText(i) + " (byte " + std::to_string(at) +
                              "): a list's count is negative");
        }
        at += static_cast<std::uintmax_t>(p.count_bytes) + static_cast<std::uintmax_t>(n) * static_cast<std::uintmax_t>(p.bytes);
      }
    }
  }
  if (at > size) {
    throw MeshLoadError(path + ": PLY header counts " + plyCounts(h) + "; the file ends before the last of them (" +
                        std::to_string(at - size) + " bytes short)");
  }
  if (at < size) {
    std::string rest(static_cast<std::size_t>(std::min<std::uintmax_t>(size - at, 64)), '\0');
    in.clear();
    in.seekg(static_cast<std::streamoff>(at));
    in.read(rest.data(), static_cast<std::streamsize>(rest.size()));
    if (size - at > 64 || rest.find_first_not_of(std::string(" \t\r\n\0", 5)) != std::string::npos) {
      throw MeshLoadError(path + ": PLY header counts " + plyCounts(h) + "; the file holds " + std::to_string(size - at) +
                          " bytes more after them (a wrong count would drop them)");
    }
  }
}

// A PLY file's header and body agree: every element the header counts is there, and no more.
void checkPly(const std::string& path, std::uintmax_t size) {
  std::ifstream in(path, std::ios::binary);
  const PlyHeader h = readPlyHeader(path, in, size);
  const bool known = std::all_of(h.elements.begin(), h.elements.end(), [](const PlyElement& e) {
    return std::all_of(e.properties.begin(), e.properties.end(), [](const PlyProperty& p) { return p.bytes > 0; });
  });
  if (h.format == "ascii") checkPlyAsciiBody(path, in, h);
  if (h.format.starts_with("binary") && known) checkPlyBinaryBody(path, in, h, size);
}

// Headers that lie about what the file holds, before the importer sees them.
void checkHeader(const std::string& path) {
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) throw MeshLoadError(path + ": cannot read mesh: " + ec.message());
  const std::string ext = lower(std::filesystem::path(path).extension().string());
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
  info.unit_applied = true;
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

// An FBX file's unit in metres: its UnitScaleFactor counts centimetres (1: the unit is 1 cm);
// 1 when the importer gives none.
double fbxUnit(const aiScene& scene) {
  if (scene.mMetaData == nullptr) return 1.0;
  for (unsigned i = 0; i < scene.mMetaData->mNumProperties; ++i) {
    const aiMetadataEntry& e = scene.mMetaData->mValues[i];
    if (std::string(scene.mMetaData->mKeys[i].C_Str()) != "UnitScaleFactor") continue;
    double unit = 0.0;
    if (e.mType == AI_DOUBLE) unit = *static_cast<const double*>(e.mData);
    if (e.mType == AI_FLOAT) unit = *static_cast<const float*>(e.mData);
    if (unit > 0.0 && std::isfinite(unit)) return 0.01 * unit;
  }
  return 1.0;
}

bool isFbx(const std::string& path) { return lower(std::filesystem::path(path).extension().string()) == ".fbx"; }
bool isOff(const std::string& path) { return lower(std::filesystem::path(path).extension().string()) == ".off"; }

// An OFF file, read by our reader: one part, no declared unit or up axis.
MeshFileInfo describeOffFile(const std::string& path) {
  const detail::OffFile off = detail::readOffFile(path, 1.0);
  MeshFileInfo info;
  info.format = "OFF (Object File Format)";
  MeshPart part;
  part.vertices = static_cast<int>(off.vertices);
  part.triangles = static_cast<int>(off.mesh.triangles.size());
  info.parts.push_back(part);
  return info;
}

}  // namespace

MeshFileInfo describeMeshFile(const std::string& path) {
  if (isOff(path)) return describeOffFile(path);
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
  info.unit_applied = isFbx(path) && info.declared_unit_m > 0.0;  // readMeshFile applies it
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
  if (isOff(path)) {
    RawMesh off = detail::readOffFile(path, scale).mesh;
    if (off.triangles.empty()) throw MeshLoadError(path + ": the file holds no triangle");
    return off;
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
  const double unit = isFbx(path) ? fbxUnit(*scene) : 1.0;  // the file's declared unit in metres
  RawMesh raw;
  for (unsigned mi = 0; mi < scene->mNumMeshes; ++mi) {
    const aiMesh* mesh = scene->mMeshes[mi];
    if (!(mesh->mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;
    const auto base = static_cast<std::int32_t>(raw.positions.size());
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      const aiVector3D& p = mesh->mVertices[v];
      const Vec3 q = scale * unit * Vec3(p.x, p.y, p.z);
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
