#include "sim/mesh/decomposition_cache.hpp"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <thread>
#include <unistd.h>
#include <algorithm>

namespace gf::sim {
namespace {

namespace fs = std::filesystem;

// File: the magic line, the key, the part count, then per part its point count and its points
// (x, y, z doubles), all in this machine's byte order (the key changes with the format).
constexpr char kMagic[8] = {'G', 'F', 'H', 'U', 'L', 'L', '1', '\n'};

std::uint64_t fnv1a(std::uint64_t h, const void* data, std::size_t n) {
  const auto* bytes = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < n; ++i) h = (h ^ bytes[i]) * 0x100000001b3ull;
  return h;
}

std::string fileOf(const std::string& dir, std::uint64_t key) {
  char name[40];
  std::snprintf(name, sizeof name, "hull-%016llx.bin", static_cast<unsigned long long>(key));
  return (fs::path(dir) / name).string();
}

}  // namespace

std::string decompositionCacheDir() {
  if (const char* d = std::getenv("GF_CACHE_DIR"); d && *d) return std::strcmp(d, "off") == 0 ? "" : d;
  if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return (fs::path(x) / "godfinger").string();
  if (const char* h = std::getenv("HOME"); h && *h) return (fs::path(h) / ".cache" / "godfinger").string();
  return "";
}

std::uint64_t decompositionKey(const Mesh& mesh, const std::string& settings) {
  std::uint64_t h = 0xcbf29ce484222325ull;
  h = fnv1a(h, kMagic, sizeof kMagic);
  h = fnv1a(h, settings.data(), settings.size());
  h = fnv1a(h, mesh.vertices().data(), mesh.vertices().size() * sizeof(Vec3));
  h = fnv1a(h, mesh.triangles().data(), mesh.triangles().size() * sizeof(mesh.triangles()[0]));
  return h;
}

std::optional<HullParts> loadDecomposition(const std::string& dir, std::uint64_t key) {
  if (dir.empty()) return std::nullopt;
  const std::string path = fileOf(dir, key);
  std::error_code ec;
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec) return std::nullopt;
  std::ifstream in(path, std::ios::binary);
  char magic[sizeof kMagic];
  std::uint64_t stored = 0, parts = 0;
  in.read(magic, sizeof magic);
  in.read(reinterpret_cast<char*>(&stored), sizeof stored);
  in.read(reinterpret_cast<char*>(&parts), sizeof parts);
  if (!in || std::memcmp(magic, kMagic, sizeof kMagic) != 0 || stored != key) return std::nullopt;
  std::uintmax_t used = sizeof kMagic + 2 * sizeof(std::uint64_t);
  if (parts == 0 || parts > (size - used) / sizeof(std::uint64_t)) return std::nullopt;
  HullParts out(parts);
  for (std::vector<Vec3>& part : out) {
    std::uint64_t n = 0;
    in.read(reinterpret_cast<char*>(&n), sizeof n);
    used += sizeof n;
    if (!in || n == 0 || n > (size - used) / (3 * sizeof(double))) return std::nullopt;
    part.resize(n);
    for (Vec3& p : part) {
      double xyz[3];
      in.read(reinterpret_cast<char*>(xyz), sizeof xyz);
      p = Vec3(xyz[0], xyz[1], xyz[2]);
    }
    used += n * 3 * sizeof(double);
    if (!in || !std::all_of(part.begin(), part.end(), [](const Vec3& p) { return p.allFinite(); })) return std::nullopt;
  }
  if (used != size) return std::nullopt;
  return out;
}

bool storeDecomposition(const std::string& dir, std::uint64_t key, const HullParts& parts) {
  if (dir.empty()) return false;
  std::error_code ec;
  fs::create_directories(dir, ec);
  const std::string path = fileOf(dir, key);
  // One temporary name per process and thread: two runs may store the same key at once.
  const std::string tmp = path + ".tmp" + std::to_string(static_cast<unsigned long long>(::getpid())) + "-" +
                          std::to_string(std::hash<std::thread::id>{}(std::this_thread::get_id()));
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    const std::uint64_t count = parts.size();
    out.write(kMagic, sizeof kMagic);
    out.write(reinterpret_cast<const char*>(&key), sizeof key);
    out.write(reinterpret_cast<const char*>(&count), sizeof count);
    for (const std::vector<Vec3>& part : parts) {
      const std::uint64_t n = part.size();
      out.write(reinterpret_cast<const char*>(&n), sizeof n);
      for (const Vec3& p : part) {
        const double xyz[3] = {p.x(), p.y(), p.z()};
        out.write(reinterpret_cast<const char*>(xyz), sizeof xyz);
      }
    }
    out.close();
    if (!out) {
      fs::remove(tmp, ec);
      return false;
    }
  }
  fs::rename(tmp, path, ec);
  if (!ec) return true;
  fs::remove(tmp, ec);
  return false;
}

}  // namespace gf::sim
