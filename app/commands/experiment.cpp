// `godfinger experiment EXPERIMENT`: an experiment's trials, each a `godfinger run` of its task's
// scene under its condition by a simulated participant; the outputs laid out BIDS-like.
#include <cstdio>
#include <filesystem>

#include "app/commands/commands.hpp"
#include "app/experiment/experiment.hpp"
#include "app/experiment/web_participant.hpp"
#include "app/runs/run_folder.hpp"
#include "app/scene/input_error.hpp"

namespace gf::app {
namespace {

struct ExperimentArgs {
  std::string experiment, out, report;
  int jobs = defaultJobs();
  int stop_after = 0;
  bool restart = false;
  int participant = 0;
  std::string serve = "8080", token;
};

class ExperimentCommand final : public Command {
 public:
  CLI::App* add(CLI::App& app) override {
    ExperimentArgs& a = args_;
    CLI::App* s = app.add_subcommand("experiment", "Run an experiment: manipulation tasks under conditions in counterbalanced "
                                                    "orders by simulated participants; write BIDS-like trial tables");
    s->add_option("experiment", a.experiment, "Experiment file, or the name of a bundled experiment (assets/experiments)");
    s->add_option("--out", a.out, "Output folder (default: out/experiment-NAME); a rerun into it resumes");
    s->add_option("--jobs", a.jobs, "Trials at a time (default: the number of cores)")->check(CLI::Range(1, 256));
    s->add_flag("--restart", a.restart, "Run every trial again, even those an earlier run into --out finished");
    participant_ = s->add_option("--participant", a.participant, "A web experiment: the participant (1..participants) this session runs; "
                                                  "their order of conditions follows the number")
        ->check(CLI::Range(1, 99));
    serve_ = s->add_option("--serve", a.serve, "A web experiment: [HOST:]PORT of the participant's page (default 8080 on loopback; "
                                      "any other address needs a token)");
    token_ = s->add_option("--token", a.token, "A web experiment: the token the page needs (default $GODFINGER_TOKEN; generated "
                                      "beyond loopback)");
    // Hidden (no group): start at most N trials, then write the tables and exit 130 as if
    // interrupted; for the tests of resuming.
    s->add_option("--stop-after", a.stop_after, "")->check(CLI::Range(1, 1000000))->group("");
    report_ = s->add_subcommand("report", "Write report.md, conditions.tsv and the charts of an experiment's folder again "
                                          "(from the trials it holds)");
    report_->add_option("folder", a.report, "The experiment's output folder")->required();
    return s;
  }

  int run() override {
    if (report_->parsed()) {
      if (!std::filesystem::is_regular_file(std::filesystem::path(args_.report) / kExperimentRecord)) {
        throw commandLineError("report", args_.report + ": no experiment there (no " + kExperimentRecord + ")");
      }
      const RunFolder folder(args_.report);  // no experiment writes into it meanwhile
      reportExperiment(args_.report);
      std::printf("wrote %s/report.md\n", args_.report.c_str());
      return 0;
    }
    if (args_.experiment.empty()) throw commandLineError("experiment", "missing: an experiment file or a bundled experiment's name");
    const ExperimentDesc e = loadExperimentFile(args_.experiment);
    ExperimentOptions options;
    options.out = args_.out.empty() ? defaultOutFolder("experiment-" + e.name) : args_.out;
    options.out = std::filesystem::absolute(options.out).lexically_normal().string();
    options.jobs = args_.jobs;
    options.godfinger = selfExecutable();
    options.restart = args_.restart;
    options.stop_after = args_.stop_after;
    if (e.device != "simulated") {  // a person: web or UDP
      if (args_.participant == 0) throw commandLineError("--participant", "missing: an experiment of people (device = \"" + e.device + "\") runs one participant a session");
      if (args_.participant > e.participants) {
        throw commandLineError("--participant", std::to_string(args_.participant) + ": the experiment has " +
                                                    std::to_string(e.participants) + " participants");
      }
      options.participant = args_.participant;
      options.serve = parseServe(args_.serve, tokenOrEnvironment(args_.token));
      const RunFolder folder(options.out);
      return runWebParticipant(e, options);
    }
    for (const CLI::Option* o : {participant_, serve_, token_}) {
      if (o->count() > 0) {
        throw commandLineError(o->get_name(), "is for an experiment of people (device = \"web\" or \"udp\"); this one's "
                                              "participants are simulated");
      }
    }
    const RunFolder folder(options.out);  // the experiment's folder is this command's while it writes
    return runExperiment(e, options);
  }

 private:
  ExperimentArgs args_;
  CLI::App* report_ = nullptr;
  CLI::Option *participant_ = nullptr, *serve_ = nullptr, *token_ = nullptr;
};

}  // namespace

std::unique_ptr<Command> makeExperimentCommand(const std::vector<std::string>&) {
  return std::make_unique<ExperimentCommand>();
}

}  // namespace gf::app
