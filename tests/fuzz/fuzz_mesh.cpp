// Fuzzes the mesh importer (sim::loadMesh: our header checks, assimp, welding) on OBJ, OFF,
// STL (ASCII and binary) and PLY files: the first byte picks the extension, the rest is the
// file. A file that cannot be used must give MeshLoadError; any other outcome is a crash.
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "sim/mesh/mesh_import.hpp"

namespace {

namespace fs = std::filesystem;

constexpr const char* kExtensions[] = {".obj", ".off", ".stl", ".ply"};

// A folder of this process's own in memory when /dev/shm exists (no disk writes per input).
fs::path scratchDir() {
  const fs::path shm = "/dev/shm";
  const fs::path dir = (fs::is_directory(shm) ? shm : fs::temp_directory_path()) /
                       ("gf-fuzz-mesh-" + std::to_string(getpid()));
  fs::create_directories(dir);
  return dir;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  static const fs::path dir = scratchDir();
  const fs::path path = dir / (std::string("mesh") + kExtensions[data[0] % std::size(kExtensions)]);
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data + 1), static_cast<std::streamsize>(size - 1));
  }
  try {
    const gf::sim::Mesh mesh = gf::sim::loadMesh(path.string());
    if (mesh.faceCount() == 0) __builtin_trap();  // loadMesh promises a triangle
  } catch (const gf::sim::MeshLoadError&) {
    // Bad input, named: fine.
  }
  fs::remove(path);
  return 0;
}
