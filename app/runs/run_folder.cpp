#include "app/runs/run_folder.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <vector>

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include "render/frames/video_file.hpp"

namespace gf::app {
namespace {

namespace fs = std::filesystem;

// The size of the probe that proves a folder writable (one file system block).
constexpr std::size_t kProbeBytes = 4096;

std::string withoutTemporarySuffix(std::string name) {
  for (const char* suffix : {".part", ".tmp"}) {
    if (name.ends_with(suffix)) name.resize(name.size() - std::strlen(suffix));
  }
  return name;
}

// The frame sequence (000000.png ...) and its temporary names.
bool isFrameName(const std::string& name) {
  const std::string stem = withoutTemporarySuffix(name);
  return stem.size() == 10 && stem.ends_with(".png") &&
         std::all_of(stem.begin(), stem.begin() + 6, [](char c) { return c >= '0' && c <= '9'; });
}

// Contact snapshots and close-ups (t0.500.json, t0.500-left.png) and their temporary names.
bool isContactName(const std::string& name) {
  const std::string stem = withoutTemporarySuffix(name);
  return stem.size() > 2 && stem[0] == 't' && stem[1] >= '0' && stem[1] <= '9' &&
         (stem.ends_with(".json") || stem.ends_with(".png"));
}

// Removes the files of `folder` whose names are `ours`, nothing else; returns how many of them
// were temporary (.part, .tmp: a run that died writing them). Throws std::runtime_error naming a
// file it cannot remove.
int sweep(const fs::path& folder, bool (*ours)(const std::string&)) {
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) return 0;
  std::vector<fs::path> doomed;
  for (const fs::directory_entry& e : fs::directory_iterator(folder, ec)) {
    if (e.is_regular_file(ec) && ours(e.path().filename().string())) doomed.push_back(e.path());
  }
  int temporary = 0;
  for (const fs::path& p : doomed) {
    if (!fs::remove(p, ec) && ec) throw std::runtime_error(p.string() + ": cannot remove an earlier run's file: " + ec.message());
    temporary += withoutTemporarySuffix(p.filename().string()) != p.filename().string();
  }
  return temporary;
}

// The pid in a video's temporary name (NAME.mp4.PID.part, as render::VideoWriter names it), or -1
// when `name` is not one.
pid_t videoPartPid(const std::string& name) {
  if (!name.ends_with(".part")) return -1;
  const std::string stem = name.substr(0, name.size() - 5);
  const std::size_t dot = stem.rfind('.');
  if (dot == std::string::npos || dot + 1 == stem.size() || !render::videoContainer(stem.substr(0, dot))) return -1;
  const std::string digits = stem.substr(dot + 1);
  if (digits.size() > 9 || !std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; })) {
    return -1;
  }
  return static_cast<pid_t>(std::stol(digits));
}

// Whether a process `pid` exists (one of another user's counts: EPERM).
bool processAlive(pid_t pid) { return pid > 0 && (kill(pid, 0) == 0 || errno == EPERM); }

// The pid written into a held lock file, or "" when it cannot be read.
std::string lockHolder(int fd) {
  char text[32] = {};
  const ssize_t n = pread(fd, text, sizeof text - 1, 0);
  std::string pid(text, n > 0 ? static_cast<std::size_t>(n) : 0);
  while (!pid.empty() && !std::isdigit(static_cast<unsigned char>(pid.back()))) pid.pop_back();
  return pid;
}

// Creates `folder` and its parents. Throws std::runtime_error naming it and `what` it is for.
void createFolder(const fs::path& folder, const std::string& what) {
  std::error_code ec;
  fs::create_directories(folder, ec);
  if (ec || !fs::is_directory(folder)) {
    throw std::runtime_error(folder.string() + ": cannot create the folder for " + what +
                             (ec ? ": " + ec.message() : ": a file is in the way"));
  }
}

// The bytes of the files `ours` names in `folder`.
std::uintmax_t bytesOf(const fs::path& folder, bool (*ours)(const std::string&)) {
  std::error_code ec;
  std::uintmax_t bytes = 0;
  if (!fs::is_directory(folder, ec)) return 0;
  for (const fs::directory_entry& e : fs::directory_iterator(folder, ec)) {
    if (e.is_regular_file(ec) && ours(e.path().filename().string())) bytes += e.file_size(ec);
  }
  return bytes;
}

// A run's own files at the top of its folder (trace.csv, summary.json, ... and their temporary names).
bool isRunFileName(const std::string& name) {
  const std::string stem = withoutTemporarySuffix(name);
  return stem == kTraceFile || stem == kForcesFile || stem == kForceChartFile || stem == kSummaryFile;
}

std::string megabytes(std::uintmax_t bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f MB", static_cast<double>(bytes) / 1e6);
  return text;
}

}  // namespace

std::string defaultOutFolder(const std::string& name) { return (fs::path(kDefaultOutRoot) / name).string(); }

std::string contactStem(double t) {
  char name[48];
  std::snprintf(name, sizeof name, "t%.3f", t);
  return name;
}

RunFolder::RunFolder(const fs::path& dir) {
  createFolder(dir, "the outputs");
  const fs::path lock = dir / kLockFile;
  fd_ = open(lock.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) throw std::runtime_error(dir.string() + ": cannot lock the output folder: " + std::strerror(errno));
  if (flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    const std::string pid = lockHolder(fd_);
    close(fd_);
    fd_ = -1;
    if (error == ENOSYS || error == ENOLCK || error == EOPNOTSUPP) {  // a file system without locks
      std::fprintf(stderr, "[godfinger] %s: the file system does not lock files (%s): a second run into this "
                   "folder at the same time would not be refused\n", dir.c_str(), std::strerror(error));
      return;
    }
    if (error != EWOULDBLOCK) throw std::runtime_error(dir.string() + ": cannot lock the output folder: " + std::strerror(error));
    throw std::runtime_error(dir.string() + ": another godfinger" + (pid.empty() ? "" : " (pid " + pid + ")") +
                             " is writing into this folder; wait for it to end or give another --out");
  }
  // The holder's pid, for the message a second run gives (failing to write it costs only that).
  const std::string pid = std::to_string(getpid()) + "\n";
  if (ftruncate(fd_, 0) == 0 && pwrite(fd_, pid.data(), pid.size(), 0) < 0) {
    // the lock holds all the same
  }
}

RunFolder::~RunFolder() {
  if (fd_ >= 0) close(fd_);  // closing the last descriptor releases the lock
}

void requireWritableFolder(const fs::path& folder, const std::string& what) {
  createFolder(folder, what);
  std::error_code ec;
  const fs::path probe = folder / (".godfinger-probe-" + std::to_string(getpid()));
  std::FILE* f = std::fopen(probe.c_str(), "wb");
  if (!f) throw std::runtime_error(folder.string() + ": cannot write " + what + " there: " + std::strerror(errno));
  const std::vector<char> block(kProbeBytes, '\0');
  const bool written = std::fwrite(block.data(), 1, block.size(), f) == block.size();
  const bool closed = std::fclose(f) == 0;
  const int error = errno;
  fs::remove(probe, ec);
  if (!written || !closed) {
    throw std::runtime_error(folder.string() + ": cannot write " + what + " there: " +
                             std::strerror(error != 0 ? error : ENOSPC));
  }
}

void requireRoom(const fs::path& folder, std::uintmax_t bytes, const std::string& what) {
  struct statvfs s {};
  // No figure to check against (or a file system that reports none, as some FUSE and virtual
  // ones do): the probe decides.
  if (statvfs(folder.c_str(), &s) != 0 || s.f_blocks == 0) return;
  const std::uintmax_t free_bytes = static_cast<std::uintmax_t>(s.f_bavail) * s.f_frsize;
  if (free_bytes >= bytes) return;
  throw std::runtime_error(folder.string() + ": too little room for " + what + ": about " + megabytes(bytes) +
                           " needed, " + megabytes(free_bytes) + " free; nothing was changed");
}

void clearRunOutputs(const fs::path& dir) {
  const int temporary = sweep(dir, isRunFileName) + sweep(dir / kFramesFolder, isFrameName) +
                        sweep(dir / kContactsFolder, isContactName);
  if (temporary > 0) {
    std::fprintf(stderr, "[godfinger] %s: removed %d unfinished file%s (.part, .tmp) of an earlier run that ended "
                 "without finishing them\n", dir.c_str(), temporary, temporary == 1 ? "" : "s");
  }
}

void clearFrames(const fs::path& folder) { sweep(folder, isFrameName); }

int removeStaleVideoParts(const fs::path& folder) {
  std::error_code ec;
  int removed = 0;
  for (const fs::directory_entry& e : fs::directory_iterator(folder, ec)) {
    const pid_t pid = videoPartPid(e.path().filename().string());
    if (pid < 0 || pid == getpid() || processAlive(pid) || !e.is_regular_file(ec)) continue;
    std::error_code gone;
    if (!fs::remove(e.path(), gone)) continue;  // removed meanwhile, or not ours to remove: left
    std::fprintf(stderr, "[godfinger] %s: removed the unfinished video of a run that is gone (pid %d)\n",
                 e.path().c_str(), static_cast<int>(pid));
    ++removed;
  }
  return removed;
}

std::uintmax_t runOutputBytes(const fs::path& dir) {
  return bytesOf(dir, isRunFileName) + bytesOf(dir / kFramesFolder, isFrameName) +
         bytesOf(dir / kContactsFolder, isContactName);
}

std::string frameFileName(long k) {
  char name[32];
  std::snprintf(name, sizeof name, "%06ld.png", k);
  return name;
}

void requireVideoPath(const std::string& path) {
  const fs::path video(path);
  std::error_code ec;
  if (fs::is_directory(video, ec)) throw std::runtime_error(path + " is a folder; give a file such as out.mp4");
  if (!render::videoContainer(path)) throw std::runtime_error(path + ": the video's name must end in .mp4, .mkv or .mov");
  const fs::path folder = video.parent_path().empty() ? fs::path(".") : video.parent_path();
  requireWritableFolder(folder, "the video");
  removeStaleVideoParts(folder);
}

}  // namespace gf::app
