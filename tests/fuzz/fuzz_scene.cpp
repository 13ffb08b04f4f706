// Fuzzes the scene-file reader (app::parseSceneText) and its --set overrides: the input is a
// scene file, optionally followed by lines "%%" each starting an override (FIELD=VALUE). Meshes
// are resolved against assets/hard-cases, so the hard cases' and the bundled scenes' mesh
// paths ("meshes/...", "../meshes/...") load. Bad input must give InputError.
#include <cstdint>
#include <string>
#include <vector>

#include "app/scene/scene_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string input(reinterpret_cast<const char*>(data), size);
  // Split at "\n%%\n": the scene text, then one override per part.
  std::vector<std::string> parts;
  for (std::size_t at = 0;;) {
    const std::size_t next = input.find("\n%%\n", at);
    parts.push_back(input.substr(at, next == std::string::npos ? std::string::npos : next - at));
    if (next == std::string::npos) break;
    at = next + 4;
  }
  const std::vector<std::string> overrides(parts.begin() + 1, parts.end());
  try {
    const gf::app::SessionDesc s =
        gf::app::parseSceneText(parts[0], "fuzz.toml", GF_SOURCE_DIR "/assets/hard-cases", overrides);
    if (s.scene.bodies.empty()) __builtin_trap();  // the reader promises a body
  } catch (const gf::app::InputError&) {
    // Bad input, named: fine.
  }
  return 0;
}
