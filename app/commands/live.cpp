// `godfinger live SCENE`: an interactive session, one command a line on standard input.
#include <filesystem>
#include <iostream>

#include "app/commands/commands.hpp"
#include "app/runs/run_folder.hpp"
#include "app/scene/data_folder.hpp"
#include "app/scene/input_error.hpp"
#include "app/session/live.hpp"

namespace gf::app {
namespace {

class LiveSubcommand final : public Command {
 public:
  CLI::App* add(CLI::App& app) override {
    CLI::App* live = app.add_subcommand("live", "Interactive session: one command a line on standard input");
    live->add_option("scene", options_.scene_path, "Scene file or bundled scene name")->required();
    live->add_option("--set", options_.overrides, "Override a scene field");
    out_ = live->add_option("--out", options_.out_dir, "Folder for snapshots (contacts/) and recorded frames (frames/) (default: out/live-SCENE)");
    live->add_option("--serve", serve_, "Serve the browser view on [HOST:]PORT (default host 127.0.0.1; 0: any free "
                                        "port): frames after every command, the state, and commands from the page");
    live->add_option("--token", token_, "--serve: require this token from every request (one is generated when "
                                        "HOST is not loopback)");
    live->add_option("--camera", options_.camera, "--serve: camera of the frames (default: the scene's first)");
    return live;
  }

  int run() override {
    options_.scene_path = resolveScenePath(options_.scene_path);
    if (out_->count() == 0) {
      options_.out_dir = defaultOutFolder("live-" + std::filesystem::path(options_.scene_path).stem().string());
    }
    options_.stop_on_interrupt = true;
    if (!serve_.empty()) options_.serve = parseServe(serve_, tokenOrEnvironment(token_));
    else if (!token_.empty()) throw commandLineError("--token", "goes with --serve");
    return runLive(options_, std::cin, std::cout);
  }

 private:
  LiveOptions options_;
  std::string serve_, token_;
  CLI::Option* out_ = nullptr;
};

}  // namespace

std::unique_ptr<Command> makeLiveCommand(const std::vector<std::string>&) { return std::make_unique<LiveSubcommand>(); }

}  // namespace gf::app
