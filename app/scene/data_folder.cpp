#include "app/scene/data_folder.hpp"

#include <algorithm>
#include <cstdlib>
#include <filesystem>

#include "app/scene/input_error.hpp"

namespace gf::app {

namespace fs = std::filesystem;

std::string dataDir() {
  if (const char* env = std::getenv("GODFINGER_DATA"); env && *env) return env;
  std::error_code ec;
  const fs::path exe = fs::canonical("/proc/self/exe", ec);
  if (!ec) {
    // Installed (<prefix>/bin and <prefix>/share/godfinger), then a build tree's copy (the
    // executable in <build>, or a test in a folder of it).
    for (const fs::path& candidate : {exe.parent_path() / GF_INSTALLED_DATA, exe.parent_path() / "share" / "godfinger",
                                      exe.parent_path().parent_path() / "share" / "godfinger"}) {
      if (fs::is_directory(candidate / "scenes", ec)) return candidate.lexically_normal().string();
    }
  }
  // An application embedding the installed library, anywhere: the prefix it was installed to.
  if (fs::is_directory(fs::path(GF_PREFIX_DATA) / "scenes", ec)) return GF_PREFIX_DATA;
  return GF_ASSET_DIR;
}

std::string bundledSceneDir() {
  if (const char* env = std::getenv("GODFINGER_SCENES"); env && *env) return env;
  return (fs::path(dataDir()) / "scenes").string();
}

std::string resolveDataPath(const std::string& path) {
  std::error_code ec;
  const fs::path given(path);
  if (path.empty() || fs::exists(given, ec) || given.is_absolute()) return path;
  // Bundled data as the repository names it (assets/meshes/...) or as the data folder does.
  const auto first = given.begin();
  const fs::path in_data = *first == "assets" ? given.lexically_relative("assets") : given;
  const fs::path bundled = fs::path(dataDir()) / in_data;
  return fs::exists(bundled, ec) ? bundled.lexically_normal().string() : path;
}

std::string resolveScenePath(const std::string& given) {
  const std::string scene = resolveDataPath(given);
  std::error_code unreadable;  // a name too long for a path, say: no such file either
  if (fs::is_regular_file(scene, unreadable)) return scene;
  const fs::path bundled = fs::path(bundledSceneDir()) / (scene + ".toml");
  if (scene.find('/') == std::string::npos && fs::is_regular_file(bundled, unreadable)) return bundled.string();
  throw InputError(scene, 0, 0, "", "no such scene file, and no bundled scene of that name (see `godfinger list`)");
}

std::string resolveBundledFile(const std::string& name_or_path, const std::string& folder, const std::string& what,
                               const std::string& shown) {
  std::error_code unreadable;
  if (fs::is_regular_file(name_or_path, unreadable)) return name_or_path;
  const fs::path bundled = fs::path(folder) / (name_or_path + ".toml");
  if (name_or_path.find('/') == std::string::npos && fs::is_regular_file(bundled, unreadable)) return bundled.string();
  throw InputError(name_or_path, 0, 0, "", "no such " + what + " file, and no bundled " + what + " of that name (" + shown + ")");
}

std::vector<std::string> bundledScenePaths() {
  std::vector<std::string> out;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(bundledSceneDir(), ec)) {
    if (e.path().extension() == ".toml") out.push_back(e.path().string());
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace gf::app
