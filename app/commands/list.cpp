// `godfinger list`: the bundled scenes, a line each.
#include <cstdio>
#include <filesystem>

#include "app/commands/commands.hpp"
#include "app/scene/data_folder.hpp"
#include "app/scene/scene_file.hpp"

namespace gf::app {
namespace {

class ListCommand final : public Command {
 public:
  CLI::App* add(CLI::App& app) override { return app.add_subcommand("list", "List the bundled scenes"); }

  int run() override {
    for (const std::string& path : bundledScenePaths()) {
      const std::string name = std::filesystem::path(path).stem().string();
      try {
        const SessionDesc s = loadSceneFile(path);
        std::printf("%-24s %s\n", name.c_str(), s.summary.c_str());
      } catch (const std::exception& e) {
        std::printf("%-24s (does not load: %s)\n", name.c_str(), e.what());
      }
    }
    return 0;
  }
};

}  // namespace

std::unique_ptr<Command> makeListCommand(const std::vector<std::string>&) { return std::make_unique<ListCommand>(); }

}  // namespace gf::app
