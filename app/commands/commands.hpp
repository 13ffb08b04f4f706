// The subcommands of `godfinger`, one file each (app/commands/NAME.cpp): each adds its options to
// the command line and runs when it is the one given. main() is a loop over commandTable().
#pragma once

#include <CLI/CLI.hpp>

#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "sim/scene/settings.hpp"

namespace gf::app {

/// One subcommand: options bound to its own members by add(), then run() once parsed.
class Command {
 public:
  virtual ~Command() = default;
  /// Adds the subcommand and its options to `app` and returns it.
  virtual CLI::App* add(CLI::App& app) = 0;
  /// Runs the parsed command; returns the exit status. Throws InputError for bad input and
  /// std::runtime_error for a failure (main prints either and exits 1).
  virtual int run() = 0;
};

/// Makes one subcommand; `argv` is the whole command line (a run records it in summary.json).
using CommandFactory = std::unique_ptr<Command> (*)(const std::vector<std::string>& argv);

/// Every subcommand's factory, in the order `godfinger --help` lists them.
std::span<const CommandFactory> commandTable();

/// `godfinger --version`: this build, its libraries and the OpenGL it would render with.
std::string versionText();

/// A command-line check by the validator of setting `name` of `table` (the value in its unit).
template <class Desc>
CLI::Validator settingCheck(std::span<const sim::Setting<Desc>> table, std::string_view name) {
  const sim::Setting<Desc>* s = sim::findSetting(table, name);
  return CLI::Validator(
      [s](std::string& text) -> std::string {
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        if (text.empty() || *end != '\0') return "expected a number, got '" + text + "'";
        return sim::checkGiven(*s, v).value_or("");
      },
      std::string(s->unit.empty() ? "" : "(" + std::string(s->unit) + ")"));
}

/// The default of --jobs: the machine's cores (at least 1).
int defaultJobs();

/// The path of the running godfinger executable (the runs of check, compare and study start it).
std::string selfExecutable();

/// The factories, one per file of app/commands.
std::unique_ptr<Command> makeRunCommand(const std::vector<std::string>& argv);
std::unique_ptr<Command> makePatchCommand(const std::vector<std::string>& argv);
std::unique_ptr<Command> makeStudyCommand(const std::vector<std::string>& argv);
std::unique_ptr<Command> makeExperimentCommand(const std::vector<std::string>& argv);
std::unique_ptr<Command> makeCheckCommand(const std::vector<std::string>& argv);
std::unique_ptr<Command> makeCompareCommand(const std::vector<std::string>& argv);
std::unique_ptr<Command> makeListCommand(const std::vector<std::string>& argv);
std::unique_ptr<Command> makeLiveCommand(const std::vector<std::string>& argv);
std::unique_ptr<Command> makeMeshInfoCommand(const std::vector<std::string>& argv);
std::unique_ptr<Command> makePlotCommand(const std::vector<std::string>& argv);
std::unique_ptr<Command> makeSchemaCommand(const std::vector<std::string>& argv);
std::unique_ptr<Command> makeScreenshotsCommand(const std::vector<std::string>& argv);
std::unique_ptr<Command> makeBenchCommand(const std::vector<std::string>& argv);

}  // namespace gf::app
