// `godfinger study STUDY`: an accuracy study, its runs as `godfinger run` processes (or as job
// lines for GNU parallel or a Slurm array, collected afterwards).
#include <algorithm>
#include <filesystem>

#include "app/commands/commands.hpp"
#include "app/runs/run_folder.hpp"
#include "app/scene/input_error.hpp"
#include "app/study/study.hpp"

namespace gf::app {
namespace {

struct StudyArgs {
  std::string study, out, emit_jobs, collect;
  std::vector<std::string> overrides;
  int jobs = defaultJobs();
  int stop_after = 0;
  bool quick = false, restart = false;
};

class StudyCommand final : public Command {
 public:
  CLI::App* add(CLI::App& app) override {
    StudyArgs& a = args_;
    CLI::App* s = app.add_subcommand("study", "Run an accuracy study: every configuration as a `godfinger run`; write "
                                               "results.csv, work-precision.png and report.md");
    s->add_option("study", a.study, "Study file, or the name of a bundled study (assets/studies)")->required();
    s->add_option("--out", a.out, "Output folder (default: out/study-NAME; with --collect, the collected folder)");
    s->add_option("--jobs", a.jobs, "Runs at a time (default: the number of cores); --jobs 1 for published step times")
        ->check(CLI::Range(1, 256));
    s->add_option("--set", a.overrides, "Override a scene field in every run, e.g. --set duration=2");
    s->add_flag("--quick", a.quick, "The study's small grid (for tests)");
    s->add_option("--emit-jobs", a.emit_jobs, "Write one shell command line per run into this file (for GNU parallel "
                                              "or a Slurm array) instead of running");
    s->add_option("--collect", a.collect, "Collect the run folders a job runner wrote under this folder");
    s->add_flag("--restart", a.restart, "Run every configuration again, even those an earlier run into --out "
                                         "finished with the same executable, scene file and settings (kept otherwise)");
    // Hidden (no group): start at most N runs, then collect and exit 130 as if interrupted; for
    // the tests of resuming.
    s->add_option("--stop-after", a.stop_after, "")->check(CLI::Range(1, 1000000))->group("");
    s->get_option("--emit-jobs")->excludes("--collect");
    s->get_option("--restart")->excludes("--collect")->excludes("--emit-jobs");
    return s;
  }

  int run() override {
    const StudyArgs& a = args_;
    const StudyDesc study = loadStudyFile(a.study);
    bool quick = a.quick;
    std::vector<std::string> overrides = a.overrides;
    if (!a.collect.empty()) {
      if (!std::filesystem::is_directory(a.collect)) {
        throw commandLineError("--collect", a.collect + ": no such folder");
      }
      // The runs' folder names come from the grid: collect the grid they were made with.
      if (const std::optional<StudyGrid> grid = readStudyGrid(a.collect)) {
        if ((a.quick && !grid->quick) || (!a.overrides.empty() && a.overrides != grid->extra)) {
          throw commandLineError("--collect",
                           a.collect + " holds runs made " + (grid->quick ? "with" : "without") + " --quick and " +
                               std::to_string(grid->extra.size()) + " --set (see its grid.json); give the same or none");
        }
        quick = grid->quick;
        overrides = grid->extra;
      }
    }
    const StudyPlan plan = expandStudy(study, quick, overrides);
    // The --quick grid's own overrides are checked too, whichever grid runs.
    if (!quick) expandStudy(study, true, overrides);
    StudyOptions options;
    options.out = a.out.empty() ? (a.collect.empty() ? defaultOutFolder("study-" + study.name) : a.collect) : a.out;
    options.jobs = a.jobs;
    options.godfinger = selfExecutable();
    options.restart = a.restart;
    options.stop_after = a.stop_after;
    const RunFolder folder(options.out);  // the study's folder is this command's while it writes
    if (!a.emit_jobs.empty()) {
      emitStudyJobs(plan, options, a.emit_jobs);
      return 0;
    }
    if (!a.collect.empty()) return collectStudy(plan, a.collect, options.out, false);
    return runStudy(plan, options);
  }

 private:
  StudyArgs args_;
};

}  // namespace

std::unique_ptr<Command> makeStudyCommand(const std::vector<std::string>&) { return std::make_unique<StudyCommand>(); }

}  // namespace gf::app
