// Helpers of the tests that run the godfinger binary: fresh output folders, exit statuses, a
// child process whose stderr is read line by line and that can be signalled like a terminal's
// Ctrl-C, and readers of what a run wrote.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <csignal>

#include <sys/types.h>
#include <sys/wait.h>

namespace gf::app::test {

namespace fs = std::filesystem;

inline const std::string kBin = std::string(GF_BINARY_DIR) + "/godfinger";
inline const std::string kFig8 = std::string(GF_SOURCE_DIR) + "/assets/scenes/fig8-pinch-oscillation.toml";

// A fresh, empty folder of this build's own (two build trees may run their tests at once).
inline fs::path freshFolder(const std::string& name) {
  const fs::path dir = fs::path(GF_BINARY_DIR) / "test-outputs" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// The exit status of a shell command (the signal's 128 + n when one ended it).
inline int exitStatus(const std::string& command) {
  const int status = std::system(command.c_str());
  if (status == -1) return -1;
  if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
  return WEXITSTATUS(status);
}

inline std::string readFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

inline nlohmann::json summaryOf(const fs::path& dir) { return nlohmann::json::parse(readFile(dir / "summary.json")); }

// The time of trace.csv's last row.
inline double lastTraceTime(const fs::path& dir) {
  std::ifstream in(dir / "trace.csv");
  std::string line, last;
  while (std::getline(in, line)) {
    if (!line.empty()) last = line;
  }
  return std::stod(last.substr(0, last.find(',')));
}

inline long countFiles(const fs::path& dir) {
  return fs::is_directory(dir) ? std::distance(fs::directory_iterator(dir), fs::directory_iterator{}) : 0;
}

// The frames and MP4's duration as ffprobe reads it (negative when it cannot read the file).
inline double videoSeconds(const fs::path& video) {
  const std::string command = "ffprobe -v error -show_entries format=duration -of csv=p=0 \"" + video.string() + "\"";
  std::FILE* p = popen(command.c_str(), "r");
  if (!p) return -1.0;
  char line[128] = {};
  const bool read = std::fgets(line, sizeof line, p) != nullptr;
  const int status = pclose(p);
  if (!read || status != 0) return -1.0;
  return std::atof(line);
}

// Starts `command` (its stderr is what we read; stdout goes to `stdout_file`) and returns its pid
// and a stream of its stderr lines.
struct Child {
  std::FILE* lines = nullptr;
  pid_t pid = 0;
};

// The child runs in a session and process group of its own (setsid keeps its pid: sh is not a
// group leader), so kill(-pid, ...) is what a terminal's Ctrl-C does: the signal reaches every
// process of the group.
inline Child start(const std::string& command, const std::string& stdout_file) {
  Child c;
  c.lines = popen(("sh -c 'echo $$; exec setsid " + command + " 2>&1 >" + stdout_file + "'").c_str(), "r");
  if (!c.lines) return c;
  char line[64] = {};
  if (std::fgets(line, sizeof line, c.lines)) c.pid = static_cast<pid_t>(std::atol(line));
  return c;
}

// Reads lines until one contains `text`; false at end of output.
inline bool waitForLine(std::FILE* lines, const std::string& text) {
  char line[4096];
  while (std::fgets(line, sizeof line, lines)) {
    if (std::string(line).find(text) != std::string::npos) return true;
  }
  return false;
}

// The rest of a child's output, line by line, and its exit status (128 + signal when one ended it).
struct Ended {
  std::vector<std::string> lines;
  int status = -1;
};

inline Ended finishLines(Child& c) {
  Ended e;
  char line[4096];
  while (std::fgets(line, sizeof line, c.lines)) e.lines.emplace_back(line);
  const int status = pclose(c.lines);
  e.status = WIFSIGNALED(status) ? 128 + WTERMSIG(status) : WEXITSTATUS(status);
  return e;
}

// Reads the rest and returns the exit status (128 + signal when one ended it).
inline int finish(Child& c) { return finishLines(c).status; }

// Reads lines until one contains `text` and returns it; empty at end of output.
inline std::string lineWith(std::FILE* lines, const std::string& text) {
  char line[4096];
  while (std::fgets(line, sizeof line, lines)) {
    if (std::string(line).find(text) != std::string::npos) return line;
  }
  return "";
}

/// Kills a child's process group when it goes out of scope, unless `done` (a failed assertion
/// does not leave a run behind).
struct KillGroupOnExit {
  pid_t pid;
  bool done = false;
  ~KillGroupOnExit() {
    if (!done) kill(-pid, SIGKILL);
  }
};

}  // namespace gf::app::test
