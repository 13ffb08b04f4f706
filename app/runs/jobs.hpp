// Shell command lines run as child processes, a bounded number at a time: the studies' runs and
// `godfinger check`'s scenes. SIGINT or SIGTERM stops starting lines and is passed to the
// running ones.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace gf::app {

/// Runs `lines` under /bin/sh, `jobs` at a time, in order of start. After each ends, `done(i,
/// exit_code)` is called (exit_code -1: could not start; 128 + signal: killed by a signal).
/// Returns true when it was interrupted (the lines not started were skipped). When `done` throws,
/// no further line starts, the running ones get SIGTERM and are waited for, and the exception is
/// rethrown.
bool runJobs(const std::vector<std::string>& lines, int jobs, const std::function<void(std::size_t, int)>& done);

/// The signal (SIGINT or SIGTERM) that interrupted the last runJobs, 0 if none.
int jobsSignal();

/// The shell line of one `godfinger run` of `scene` into `dir` (created), with `arguments`
/// (each a single word, quoted here), its output in dir/run.log. Paths are made absolute, so the
/// line works from any folder; `exec` makes the runner wait on godfinger itself, so a Ctrl-C
/// reaches it.
std::string godfingerRunLine(const std::string& godfinger, const std::string& scene, const std::string& dir,
                             const std::vector<std::string>& arguments);

/// "1m05s", "42s".
std::string formatDuration(double seconds);

/// Seconds as a run's command line takes them (`--duration`, `--max-duration`), exactly: 17
/// significant digits.
std::string exactSeconds(double seconds);

}  // namespace gf::app
