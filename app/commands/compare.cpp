// `godfinger compare SCENE`: the scene once per contact model, side by side (app/compare).
#include <algorithm>

#include "app/commands/commands.hpp"
#include "app/compare/compare.hpp"

namespace gf::app {
namespace {

class CompareCommand final : public Command {
 public:
  CLI::App* add(CLI::App& app) override {
    CompareOptions& o = options_;
    o.jobs = defaultJobs();
    CLI::App* c = app.add_subcommand(
        "compare", "Run a scene once per contact model (offline, in parallel) and draw one video of the runs side "
                   "by side (3 or 4: a 2 x 2 grid, the frame half again as tall) over a chart of a trace quantity; "
                   "compare.json holds their measures");
    c->add_option("scene", o.scene, "Scene file or bundled scene name")->required();
    c->add_option("--models", models_, "Contact models, comma-separated (1 to 4 of god_object, soft_finger, "
                                       "god_finger, fem_pad, or god_finger_3dof and god_finger_6dof: a god-finger "
                                       "with pad_model disc or oriented)")
        ->default_val("god_object,soft_finger,god_finger");
    c->add_option("--set", o.overrides, "Override a scene field in every run");
    c->add_option("--duration", o.duration, "Simulated seconds (default: the scene's)")->check(CLI::Range(1e-3, 3600.0));
    c->add_option("--out", o.out, "Folder for the runs, compare.json and frames (default: out/compare-SCENE)");
    c->add_option("--video", o.video, "Write the comparison as an MP4 (H.264, via ffmpeg)");
    c->add_flag("--frames", o.frames, "Write the comparison's frames/000000.png ... (always without --video)");
    c->add_flag("--keep-run-frames", o.keep_run_frames, "Keep each run's own frames (MODEL/frames)");
    c->add_option("--camera", o.camera, "Camera of the scene (default: its first)");
    c->add_option("--chart", o.chart, "Quantity charted: of --body, rotation (angle turned, deg), tilt (its axis "
                                      "from upright, deg), height (mm) or speed (m/s); or any trace.csv column "
                                      "(default: tilt; a sphere's rotation)");
    c->add_option("--body", o.body, "Body of the chart (default: the scene's first dynamic body)");
    c->add_option("--jobs", o.jobs, "Runs at a time (default: the number of cores; 1 for step times to publish)")
        ->check(CLI::Range(1, 256));
    c->add_flag("--quiet", o.quiet, "Only errors");
    return c;
  }

  int run() override {
    options_.godfinger = selfExecutable();
    for (std::size_t a = 0; a <= models_.size();) {
      const std::size_t b = std::min(models_.find(',', a), models_.size());
      if (b > a) options_.models.push_back(models_.substr(a, b - a));
      a = b + 1;
    }
    return runCompare(options_);
  }

 private:
  CompareOptions options_;
  std::string models_;
};

}  // namespace

std::unique_ptr<Command> makeCompareCommand(const std::vector<std::string>&) {
  return std::make_unique<CompareCommand>();
}

}  // namespace gf::app
