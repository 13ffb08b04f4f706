// `godfinger run SCENE`: one session, offline or realtime, into its run folder.
#include <cstdio>
#include <filesystem>

#include "app/commands/commands.hpp"
#include "app/scene/data_folder.hpp"
#include "app/scene/scene_file.hpp"
#include "app/process/interrupt.hpp"
#include "app/runs/run_folder.hpp"
#include "app/session/session.hpp"

namespace gf::app {
namespace {

class RunCommand final : public Command {
 public:
  explicit RunCommand(const std::vector<std::string>& argv) : command_line_(argv) {}

  CLI::App* add(CLI::App& app) override {
    CLI::App* run = app.add_subcommand("run", "Run a scene; write trace.csv, summary.json and contacts/");
    run->add_option("scene", scene_, "Scene file, or the name of a bundled scene (godfinger list)")->required();
    run->add_option("--out", out_, "Output folder (created if missing; default: out/run-SCENE)");
    run->add_option("--set", overrides_, "Override a scene field, e.g. --set fingers.left.n_sgo=0");
    run->add_option("--duration", duration_, "Simulated seconds (default: the scene's)")
        ->check(settingCheck(sim::sceneSettings(), "duration"));
    run->add_option("--max-duration", max_duration_,
                    "Simulated seconds at most: a short variant of a long scene (its end-of-run [expect] limits, "
                    "ends_above and max_roll_ratio, are then left unchecked)")
        ->check(settingCheck(sim::sceneSettings(), "duration"));
    run->add_flag("--realtime", realtime_, "Pace steps on the wall clock (absolute deadlines)");
    run->add_flag("--no-fifo", no_fifo_, "Realtime: do not ask for SCHED_FIFO for the haptic loop (run as a user "
                                         "without root or CAP_SYS_NICE does)");
    run->add_flag("--no-yield", no_yield_, "Realtime: keep the render thread and encoders at normal priority "
                                           "instead of nice 10");
    run->add_flag("--pin", pin_, "Realtime: keep the haptic loop alone on the last CPU and the renderer and "
                                 "writers on the others (for a CPU kept free for the loop)");
    run->add_option("--spin-us", spin_us_, "Realtime: sleep until this long before each step's deadline, then "
                                           "spin (us; default 0: sleep)")
        ->check(CLI::Range(0.0, 1000.0));
    run->add_flag("--quiet", quiet_, "No progress lines on stderr");
    run->add_flag("--frames", frames_, "Write frames/000000.png ... at 60 frames per simulated second");
    run->add_option("--video", video_, "Write an MP4 of the frames (H.264, via ffmpeg)");
    run->add_option("--serve", serve_, "Realtime: serve the browser view on [HOST:]PORT (default host 127.0.0.1; "
                                       "0: any free port): the frames, the state and live commands");
    run->add_option("--token", token_, "--serve: require this token from every request (one is generated when "
                                       "HOST is not loopback)");
    run->add_option("--camera", camera_, "Camera of the scene to render (default: its first)");
    run->add_option("--expectations", expectations_, "check: exit 3 when an [expect] of the scene fails (default); "
                                                     "report: only print them and write them into summary.json")
        ->check(CLI::IsMember({"check", "report"}));
    return run;
  }

  int run() override {
    SessionDesc session = loadSceneFile(resolveScenePath(scene_), overrides_);
    session.overrides = overrides_;
    if (out_.empty()) out_ = defaultOutFolder("run-" + session.scene.name);
    if (duration_ > 0.0) session.scene.duration = duration_;
    cut_short_ = max_duration_ > 0.0 && max_duration_ < session.scene.duration;
    if (cut_short_) session.scene.duration = max_duration_;
    sessionCamera(session, camera_);  // an unknown camera fails before anything runs
    if (!video_.empty() && std::filesystem::is_directory(video_)) {
      throw commandLineError("--video", video_ + " is a folder; give a file such as out.mp4");
    }
    std::vector<ExpectFailure> failed;
    const sim::LoopStats stats = runSession(session, options(failed));
    std::printf("%s: %ld steps, step median %.1f us, p99 %.1f us; wrote %s/\n", session.scene.name.c_str(),
                stats.steps, stats.step_median_us, stats.step_p99_us, out_.c_str());
    if (frames_) std::printf("frames: %s/frames/\n", out_.c_str());
    if (!video_.empty()) std::printf("video: %s\n", video_.c_str());
    // Ctrl-C or SIGTERM: the outputs hold the time reached; the shell's status for the signal.
    // A signal while the outputs were being finished ends with its status too (they are complete).
    if (stats.stopped || interruptSignal() != 0) return interruptedStatus();
    // 3: the run was fine, the scene's expectations were not.
    return failed.empty() || expectations_ == "report" ? 0 : 3;
  }

 private:
  SessionOptions options(std::vector<ExpectFailure>& failed) const {
    SessionOptions o{out_, realtime_, !quiet_, frames_, video_, camera_};
    o.expect_failures = &failed;
    o.cut_short = cut_short_;
    o.stop_on_interrupt = true;
    o.fifo = !no_fifo_;
    o.yield_render = !no_yield_;
    o.pin_cpus = pin_;
    o.spin_us = spin_us_;
    o.command_line = redactedToken(command_line_);
    if (!serve_.empty()) o.serve = parseServe(serve_, tokenOrEnvironment(token_));
    else if (!token_.empty()) throw commandLineError("--token", "goes with --serve");
    return o;
  }

  std::string scene_;
  std::string out_;  // default: out/run-SCENE
  std::vector<std::string> overrides_;
  double duration_ = 0.0, max_duration_ = 0.0;
  bool cut_short_ = false;
  bool realtime_ = false, frames_ = false, no_fifo_ = false, no_yield_ = false, pin_ = false, quiet_ = false;
  std::string video_, camera_, serve_, token_;
  std::string expectations_ = "check";
  double spin_us_ = 0.0;
  std::vector<std::string> command_line_;
};

}  // namespace

std::unique_ptr<Command> makeRunCommand(const std::vector<std::string>& argv) {
  return std::make_unique<RunCommand>(argv);
}

}  // namespace gf::app
