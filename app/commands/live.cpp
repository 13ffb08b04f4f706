// `godfinger live SCENE`: an interactive session, one command a line on standard input.
#include <iostream>

#include "app/commands/commands.hpp"
#include "app/scene/data_folder.hpp"
#include "app/session/live.hpp"

namespace gf::app {
namespace {

class LiveCommand final : public Command {
 public:
  CLI::App* add(CLI::App& app) override {
    CLI::App* live = app.add_subcommand("live", "Interactive session: one command a line on standard input");
    live->add_option("scene", options_.scene_path, "Scene file or bundled scene name")->required();
    live->add_option("--set", options_.overrides, "Override a scene field");
    live->add_option("--out", options_.out_dir, "Folder for snapshots (contacts/)");
    return live;
  }

  int run() override {
    options_.scene_path = resolveScenePath(options_.scene_path);
    options_.stop_on_interrupt = true;
    return runLive(options_, std::cin, std::cout);
  }

 private:
  LiveOptions options_;
};

}  // namespace

std::unique_ptr<Command> makeLiveCommand(const std::vector<std::string>&) { return std::make_unique<LiveCommand>(); }

}  // namespace gf::app
