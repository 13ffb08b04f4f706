// The whole `godfinger` command line: every subcommand of commandTable() added to one CLI11 app,
// parsed, and the given one run. Kept behind this one function so main.cpp compiles without CLI11
// (the commands' unit compiles it once).
#pragma once

namespace gf::app {

/// Parses `argv` and runs the subcommand it names; returns the process's exit status (1 for bad
/// input or an error, printed on stderr; kOutputClosedStatus when standard output went away).
/// Main thread, once per process; ignores SIGPIPE and SIGXFSZ (write errors are handled).
int runCommandLine(int argc, char** argv);

}  // namespace gf::app
