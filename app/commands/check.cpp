#include "app/commands/check.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "app/commands/commands.hpp"
#include "app/runs/jobs.hpp"
#include "app/runs/run_folder.hpp"
#include "app/runs/run_reader.hpp"
#include "app/scene/data_folder.hpp"
#include "app/scene/scene_file.hpp"
#include "app/process/console.hpp"

namespace gf::app {
namespace {

namespace fs = std::filesystem;

// How close the run came to each limit: the check nearest to failing, as "name worst (limit)".
std::string closest(const nlohmann::json& checks) {
  std::string out;
  double nearest = -HUGE_VAL;
  for (const nlohmann::json& c : checks) {
    if (!c.value("checked", false) || c["worst"].is_null() || c["name"] == "finite") continue;
    const double worst = c["worst"].get<double>(), limit = c["limit"].get<double>();
    // How much of the limit is used: worst / limit for "at most" checks, limit / worst for
    // "at least" ones (1: at the limit).
    const bool at_least = c.value("kind", "at_most") == "at_least";
    const double share = at_least ? (worst > 0.0 ? limit / worst : HUGE_VAL) : (limit != 0.0 ? worst / limit : worst);
    if (share > nearest) {
      nearest = share;
      char b[160];
      std::snprintf(b, sizeof b, "%s %.4g (limit %.4g)", c["name"].get<std::string>().c_str(), worst, limit);
      out = b;
    }
  }
  return out;
}

}  // namespace

std::vector<std::string> checkedScenes(const std::vector<std::string>& paths) {
  std::vector<std::string> out;
  for (const std::string& given : paths) {
    const std::string p = resolveDataPath(given);
    if (fs::is_directory(p)) {
      std::vector<std::string> found;
      for (const auto& e : fs::recursive_directory_iterator(p)) {
        if (e.is_regular_file() && e.path().extension() == ".toml") found.push_back(e.path().string());
      }
      if (found.empty()) throw InputError(p, 0, 0, "", "no scene file (*.toml) in this folder");
      std::sort(found.begin(), found.end());
      out.insert(out.end(), found.begin(), found.end());
    } else {
      out.push_back(resolveScenePath(p));
    }
  }
  return out;
}

namespace {

// The scenes to run; the ones a live device drives are listed as skipped (they cannot run
// offline) and counted in `live`.
std::vector<std::string> offlineScenes(const CheckOptions& options, int& live) {
  std::vector<std::string> scenes;
  for (const std::string& s : checkedScenes(options.paths)) {
    bool udp = false, web = false;
    try {
      const SessionDesc session = loadSceneFile(s, options.overrides);
      udp = !session.udp_devices.empty();
      web = !session.web_devices.empty();
    } catch (const std::exception&) {
      // the run reports why it does not load
    }
    if (!udp && !web) {
      scenes.push_back(s);
      continue;
    }
    std::printf("%-5s %-40s %s\n", "SKIP", fs::path(s).stem().string().c_str(),
                udp ? "a live UDP device drives it: run it with --realtime and a device program"
                    : "the browser view's pointer drives it: run it with --realtime --serve PORT");
    ++live;
  }
  return scenes;
}

// The failed checks of a run, each as "name worst (limit) at t".
std::vector<std::string> failedChecks(const nlohmann::json& checks) {
  std::vector<std::string> failures;
  for (const nlohmann::json& c : checks) {
    if (c.value("passed", true)) continue;
    char b[200];
    if (c["worst"].is_null()) std::snprintf(b, sizeof b, "%s not finite", c["name"].get<std::string>().c_str());
    else std::snprintf(b, sizeof b, "%s %.4g (limit %.4g) at t = %.4f s", c["name"].get<std::string>().c_str(),
                       c["worst"].get<double>(), c["limit"].get<double>(), c["time_s"].get<double>());
    failures.push_back(b);
  }
  return failures;
}

// One scene's line (PASS, FAIL or ERROR with its worst figure) from its exit code and run folder.
std::string resultLine(const std::string& name, int code, const fs::path& dir, bool& passed) {
  const nlohmann::json summary = readSummary(dir);
  char head[96];
  passed = false;
  if ((code != 0 && code != 3) || !summary.is_object() || !summary.contains("expectations")) {
    std::snprintf(head, sizeof head, "%-5s %-40s ", "ERROR", name.c_str());
    return head + ("exit " + std::to_string(code) + ": " + lastLogLine(dir));
  }
  const nlohmann::json& checks = summary.at("expectations").at("checks");
  const std::vector<std::string> failures = failedChecks(checks);
  passed = failures.empty();
  std::snprintf(head, sizeof head, "%-5s %-40s ", passed ? "PASS" : "FAIL", name.c_str());
  std::string detail;
  if (passed) {
    detail = std::to_string(checks.size()) + " checks";
    const std::string c = closest(checks);
    if (!c.empty()) detail += "; closest: " + c;
  } else {
    detail = failures.front();
    if (failures.size() > 1) detail += " (+" + std::to_string(failures.size() - 1) + " more)";
  }
  const long recoveries = summary.value("counters", nlohmann::json::object()).value("nan_recoveries", 0L);
  if (recoveries > 0) detail += "; " + std::to_string(recoveries) + " steps rolled back";
  return head + detail;
}

}  // namespace

int runCheck(const CheckOptions& options) {
  const RunFolder folder(options.out);  // the scenes' runs go under it: one check at a time
  int live = 0;  // scenes a live device drives: they cannot run offline
  const std::vector<std::string> scenes = offlineScenes(options, live);
  std::vector<std::string> names, lines;
  for (const std::string& s : scenes) {
    std::string name = fs::path(s).stem().string();
    for (const std::string& other : names) {
      if (other == name) name = fs::path(s).parent_path().filename().string() + "-" + name;
    }
    names.push_back(name);
    std::vector<std::string> arguments;
    for (const std::string& o : options.overrides) arguments.insert(arguments.end(), {"--set", o});
    if (options.max_duration > 0.0) arguments.insert(arguments.end(), {"--max-duration", exactSeconds(options.max_duration)});
    lines.push_back(godfingerRunLine(options.godfinger, s, (fs::path(options.out) / name).string(), arguments));
  }
  int failed = 0, passed = 0;
  const bool interrupted = runJobs(lines, options.jobs, [&](std::size_t i, int code) {
    bool ok = false;
    std::printf("%s\n", resultLine(names[i], code, fs::absolute(options.out) / names[i], ok).c_str());
    ++(ok ? passed : failed);
    flushOutput();
  });
  const std::size_t skipped = scenes.size() - static_cast<std::size_t>(passed + failed);
  std::printf("%zu scenes: %d passed, %d failed, %zu not run%s", scenes.size() + static_cast<std::size_t>(live), passed,
              failed, skipped + static_cast<std::size_t>(live), interrupted ? " (interrupted)" : "");
  if (live > 0) std::printf(" (%d with a live device)", live);
  std::printf("; runs in %s/\n", options.out.c_str());
  if (interrupted) return 130;
  return failed == 0 ? 0 : 1;
}

namespace {

class CheckCommand final : public Command {
 public:
  CLI::App* add(CLI::App& app) override {
    CheckOptions& o = options_;
    o.jobs = defaultJobs();
    CLI::App* c = app.add_subcommand("check", "Run scenes offline and check their [expect] tables; one line each, "
                                              "exit 1 if any fails");
    c->add_option("paths", o.paths, "Scene files, folders of them, or bundled scene names")->required();
    c->add_option("--out", o.out, "Folder for the runs (default: out/check)");
    c->add_option("--set", o.overrides, "Override a field of every scene, e.g. --set world.contact_solver=aggregate");
    c->add_option("--jobs", o.jobs, "Scenes at a time (default: the number of cores)")->check(CLI::Range(1, 256));
    c->add_option("--max-duration", o.max_duration,
                  "Run each scene for at most this many simulated seconds (a short variant: its end-of-run "
                  "limits are left unchecked)")
        ->check(settingCheck(sim::sceneSettings(), "duration"));
    return c;
  }

  int run() override {
    options_.godfinger = selfExecutable();
    return runCheck(options_);
  }

 private:
  CheckOptions options_;
};

}  // namespace

std::unique_ptr<Command> makeCheckCommand(const std::vector<std::string>&) { return std::make_unique<CheckCommand>(); }

}  // namespace gf::app
