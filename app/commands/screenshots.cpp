// `godfinger screenshots`: the reference pictures (visual-regression goldens).
#include <cstdio>
#include <filesystem>

#include "app/commands/commands.hpp"
#include "app/compare/screenshots.hpp"
#include "app/runs/run_folder.hpp"
#include "render/frames/image.hpp"

namespace gf::app {
namespace {

class ScreenshotsCommand final : public Command {
 public:
  CLI::App* add(CLI::App& app) override {
    CLI::App* s = app.add_subcommand("screenshots", "Render the reference pictures (visual-regression goldens) into --out");
    s->add_option("--out", out_, "Folder (default: out/screenshots; --out screenshots from the repository root re-blesses the goldens)");
    return s;
  }

  int run() override {
    std::error_code ec;
    std::filesystem::create_directories(out_, ec);
    if (ec) throw std::runtime_error(out_ + ": cannot create folder: " + ec.message());
    for (const Shot& shot : referenceShots()) {
      const std::string path = (std::filesystem::path(out_) / (shot.name + ".png")).string();
      render::writePng(path, renderShot(shot), 9);
      std::printf("%s\n", path.c_str());
    }
    return 0;
  }

 private:
  std::string out_ = defaultOutFolder("screenshots");
};

}  // namespace

std::unique_ptr<Command> makeScreenshotsCommand(const std::vector<std::string>&) {
  return std::make_unique<ScreenshotsCommand>();
}

}  // namespace gf::app
