// The `godfinger` command line (app/commands/command_line.hpp): a loop over the subcommands of
// commandTable(), one file each.
#include "app/commands/command_line.hpp"

#include <CLI/CLI.hpp>

#include <csignal>
#include <cstdio>
#include <exception>
#include <memory>
#include <vector>

#include "app/commands/commands.hpp"
#include "app/process/console.hpp"

namespace gf::app {

int runCommandLine(int argc, char** argv) {
  CLI::App app{"godfinger: god-finger contact areas for haptic interaction on Bullet", "godfinger"};
  app.require_subcommand(1);
  app.set_version_flag("--version", versionText,
                       "Print the version, the git commit and the libraries' versions");
  const std::vector<std::string> command_line(argv, argv + argc);
  std::vector<std::pair<CLI::App*, std::unique_ptr<Command>>> commands;
  for (const CommandFactory make : commandTable()) {
    std::unique_ptr<Command> command = make(command_line);
    CLI::App* sub = command->add(app);
    commands.emplace_back(sub, std::move(command));
  }
  if (argc == 1) {  // bare `godfinger`: the usage and the command list
    std::fputs(app.help().c_str(), stdout);
    return 1;
  }
  // A reader that went away (ffmpeg, a closed pipe) is a write error we handle, not a signal
  // that kills the run before it writes what it reached; on standard output it ends the command
  // quietly with 141 (flushOutput).
  std::signal(SIGPIPE, SIG_IGN);
  std::signal(SIGXFSZ, SIG_IGN);  // a file past the size limit: a write error too
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {  // --help, --version, or a bad option: CLI11 says which
    const int status = app.exit(e);
    try {
      flushOutput();
    } catch (const OutputClosed&) {
      return kOutputClosedStatus;
    } catch (const std::exception& error) {
      std::fprintf(stderr, "godfinger: error: %s\n", error.what());
      return 1;
    }
    return status;
  }
  try {
    for (const auto& [sub, command] : commands) {
      if (!sub->parsed()) continue;
      const int status = command->run();
      flushOutput();  // the last lines too: a full disk under `> file` is an error
      return status;
    }
    return 1;
  } catch (const OutputClosed&) {
    return kOutputClosedStatus;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "godfinger: error: %s\n", e.what());
    return 1;
  }
}

}  // namespace gf::app
