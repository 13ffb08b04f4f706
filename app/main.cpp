// The `godfinger` command: run built-in sessions and list them.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>

#include "app/builtin_scenes.hpp"
#include "app/session.hpp"

namespace {

struct RunArgs {
  std::string scene = "pinch";
  std::string out = "out";
  double duration = 0.0;
  int n_sgo = 8;
  bool realtime = false;
};

void addRun(CLI::App& app, RunArgs& args) {
  CLI::App* run = app.add_subcommand("run", "Run a session and write trace.csv and summary.json");
  run->add_option("--scene", args.scene, "Built-in scene to run (see `godfinger list`)");
  run->add_option("--out", args.out, "Output folder (created if missing)");
  run->add_option("--duration", args.duration, "Simulated seconds (default: the scene's)")
      ->check(CLI::NonNegativeNumber);
  run->add_option("--n-sgo", args.n_sgo, "SGOs per finger; 0 is the classic god-object")
      ->check(CLI::Range(0, 64));
  run->add_flag("--realtime", args.realtime, "Pace steps on the wall clock (absolute deadlines)");
}

int runCommand(const RunArgs& args) {
  const gf::sim::SceneDesc scene = gf::app::makeBuiltinScene(args.scene, {args.n_sgo, args.duration});
  const gf::sim::LoopStats stats = gf::app::runSession(scene, {args.out, args.realtime, true});
  std::printf("%s: %ld steps, step median %.1f us, p99 %.1f us; wrote %s/trace.csv and %s/summary.json\n",
              scene.name.c_str(), stats.steps, stats.step_median_us, stats.step_p99_us,
              args.out.c_str(), args.out.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"godfinger: god-finger contact areas for haptic interaction on Bullet"};
  app.require_subcommand(1);
  RunArgs run_args;
  addRun(app, run_args);
  app.add_subcommand("list", "List the built-in scenes");
  CLI11_PARSE(app, argc, argv);
  try {
    if (app.got_subcommand("list")) {
      for (const gf::app::BuiltinScene& s : gf::app::builtinScenes()) {
        std::printf("%-12s %s\n", s.name, s.summary);
      }
      return 0;
    }
    return runCommand(run_args);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "godfinger: error: %s\n", e.what());
    return 1;
  }
}
