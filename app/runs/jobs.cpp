#include "app/runs/jobs.hpp"

#include "app/runs/run_folder.hpp"

#include <spawn.h>
#include <sys/wait.h>

#include <atomic>
#include <cerrno>
#include <csignal>
#include <exception>
#include <cstdio>
#include <filesystem>
#include <map>

extern char** environ;

namespace gf::app {
namespace {

std::atomic<int> g_signal{0};  // the first SIGINT or SIGTERM since runJobs began
extern "C" void onJobsSignal(int signal) {
  int none = 0;
  g_signal.compare_exchange_strong(none, signal);
}

// Spawns `line` under /bin/sh; returns its pid (or -1).
pid_t spawnShell(const std::string& line) {
  pid_t pid = -1;
  const char* argv[] = {"/bin/sh", "-c", line.c_str(), nullptr};
  if (posix_spawn(&pid, "/bin/sh", nullptr, nullptr, const_cast<char* const*>(argv), environ) != 0) return -1;
  return pid;
}

std::string shellQuote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

}  // namespace

std::string godfingerRunLine(const std::string& godfinger, const std::string& scene, const std::string& dir,
                             const std::vector<std::string>& arguments) {
  const std::string out = std::filesystem::absolute(dir).lexically_normal().string();
  std::string line = "mkdir -p " + shellQuote(out) + " && exec " + shellQuote(godfinger) + " run " +
                     shellQuote(std::filesystem::absolute(scene).string()) + " --out " + shellQuote(out);
  for (const std::string& a : arguments) line.append(1, ' ').append(shellQuote(a));
  return line + " > " + shellQuote(out + "/" + kRunLogFile) + " 2>&1";
}

std::string exactSeconds(double s) {
  char b[32];
  std::snprintf(b, sizeof b, "%.17g", s);
  return b;
}

std::string formatDuration(double s) {
  char b[32];
  if (s >= 60.0) std::snprintf(b, sizeof b, "%dm%02ds", static_cast<int>(s / 60), static_cast<int>(s) % 60);
  else std::snprintf(b, sizeof b, "%.0fs", s);
  return b;
}

bool runJobs(const std::vector<std::string>& lines, int jobs, const std::function<void(std::size_t, int)>& done) {
  g_signal = 0;
  struct sigaction action{}, old_int{}, old_term{};
  action.sa_handler = onJobsSignal;  // no SA_RESTART: waitpid returns on a signal
  sigaction(SIGINT, &action, &old_int);
  sigaction(SIGTERM, &action, &old_term);
  std::map<pid_t, std::size_t> running;
  std::size_t next = 0;
  bool forwarded = false;
  std::exception_ptr failed;  // `done` threw (its output closed): no more lines; the running ones end
  const auto report = [&](std::size_t index, int code) {
    if (failed) return;
    try {
      done(index, code);
    } catch (...) {
      failed = std::current_exception();
    }
  };
  while (true) {
    while (g_signal == 0 && !failed && next < lines.size() && running.size() < static_cast<std::size_t>(std::max(1, jobs))) {
      const pid_t pid = spawnShell(lines[next]);
      if (pid < 0) report(next, -1);
      else running[pid] = next;
      ++next;
    }
    if (running.empty()) break;
    if ((g_signal != 0 || failed) && !forwarded) {  // a signal sent to us alone reaches the running lines too
      for (const auto& [child, index] : running) kill(child, g_signal != 0 ? SIGINT : SIGTERM);
      forwarded = true;
    }
    int status = 0;
    const pid_t pid = waitpid(-1, &status, 0);
    if (pid < 0) {
      if (errno == EINTR) continue;
      break;
    }
    const auto it = running.find(pid);
    if (it == running.end()) continue;
    const std::size_t index = it->second;
    running.erase(it);
    report(index, WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0));
  }
  sigaction(SIGINT, &old_int, nullptr);
  sigaction(SIGTERM, &old_term, nullptr);
  if (failed) std::rethrow_exception(failed);
  return g_signal != 0;
}

int jobsSignal() { return g_signal; }

}  // namespace gf::app
