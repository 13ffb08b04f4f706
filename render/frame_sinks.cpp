#include "render/frame_sinks.hpp"

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <filesystem>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace gf::render {
namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace

PngSequenceWriter::PngSequenceWriter(const std::string& folder, int queue_depth)
    : folder_(folder), depth_(static_cast<std::size_t>(std::max(1, queue_depth))) {
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  if (ec) throw ImageError(folder + ": cannot create folder: " + ec.message());
  thread_ = std::thread([this] { run(); });
}

PngSequenceWriter::~PngSequenceWriter() {
  try {
    finish();
  } catch (const ImageError&) {
    // Reported by finish() when the owner calls it; a destructor must not throw.
  }
}

void PngSequenceWriter::push(Image&& frame) {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [&] { return queue_.size() < depth_ || !error_.empty(); });
  if (!error_.empty()) throw ImageError(error_);
  queue_.push_back(std::move(frame));
  changed_.notify_all();
}

Image PngSequenceWriter::spare() {
  std::lock_guard lock(mutex_);
  if (spares_.empty()) return {};
  Image out = std::move(spares_.back());
  spares_.pop_back();
  return out;
}

void PngSequenceWriter::run() {
  for (;;) {
    Image frame;
    long index = 0;
    {
      std::unique_lock lock(mutex_);
      changed_.wait(lock, [&] { return !queue_.empty() || closing_; });
      if (queue_.empty()) return;
      frame = std::move(queue_.front());
      queue_.pop_front();
      index = stats_.frames++;
      changed_.notify_all();
    }
    const auto start = Clock::now();
    char name[32];
    std::snprintf(name, sizeof name, "%06ld.png", index);
    try {
      writePng((std::filesystem::path(folder_) / name).string(), frame);
    } catch (const ImageError& e) {
      std::lock_guard lock(mutex_);
      if (error_.empty()) error_ = e.what();
      changed_.notify_all();
    }
    std::lock_guard lock(mutex_);
    stats_.busy_seconds += secondsSince(start);
    if (spares_.size() <= depth_) spares_.push_back(std::move(frame));
  }
}

SinkStats PngSequenceWriter::finish() {
  {
    std::lock_guard lock(mutex_);
    closing_ = true;
    changed_.notify_all();
  }
  if (thread_.joinable()) thread_.join();
  if (!error_.empty()) throw ImageError(error_);
  return stats_;
}

VideoWriter::VideoWriter(const std::string& path, int width, int height, double fps, int crf)
    : path_(path), width_(width), height_(height) {
  // ffmpeg reads the frames from a pipe on its standard input. It is started without a shell
  // (any path works), in a process group of its own, so a Ctrl-C at the terminal reaches only
  // godfinger, which then ends the video by closing the pipe; and with no signal blocked.
  const std::string size = std::to_string(width) + "x" + std::to_string(height);
  char rate[32], quality[16];
  std::snprintf(rate, sizeof rate, "%g", fps);
  std::snprintf(quality, sizeof quality, "%d", crf);
  const char* argv[] = {"ffmpeg", "-loglevel", "error", "-y", "-f", "rawvideo", "-pix_fmt", "rgb24", "-s",
                        size.c_str(), "-r", rate, "-i", "-", "-c:v", "libx264", "-preset", "veryfast", "-crf",
                        quality, "-pix_fmt", "yuv420p", "-movflags", "+faststart", path.c_str(), nullptr};
  int fds[2];
  if (pipe2(fds, O_CLOEXEC) != 0) throw ImageError(path + ": cannot start ffmpeg: no pipe");
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, fds[0], STDIN_FILENO);
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  sigset_t none;
  sigemptyset(&none);
  posix_spawnattr_setsigmask(&attributes, &none);
  posix_spawnattr_setpgroup(&attributes, 0);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP | POSIX_SPAWN_SETSIGMASK);
  const int failed = posix_spawnp(&child_, "ffmpeg", &actions, &attributes, const_cast<char* const*>(argv), environ);
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attributes);
  close(fds[0]);
  if (failed != 0) {
    close(fds[1]);
    throw ImageError(path + ": cannot start ffmpeg (is the ffmpeg package installed?): " + std::strerror(failed));
  }
  pipe_ = fdopen(fds[1], "w");
  if (!pipe_) {
    close(fds[1]);
    waitpid(child_, nullptr, 0);
    throw ImageError(path + ": cannot start ffmpeg: no stream");
  }
}

VideoWriter::~VideoWriter() {
  if (!pipe_) return;
  std::fclose(pipe_);
  waitpid(child_, nullptr, 0);
}

void VideoWriter::push(const Image& frame) {
  if (!pipe_) throw ImageError(path_ + ": video already finished");
  if (frame.width != width_ || frame.height != height_) throw ImageError(path_ + ": frame size changed");
  const auto start = Clock::now();
  if (std::fwrite(frame.rgb.data(), 1, frame.rgb.size(), pipe_) != frame.rgb.size()) {
    throw ImageError(path_ + ": ffmpeg stopped reading frames");
  }
  stats_.busy_seconds += secondsSince(start);
  stats_.bytes += static_cast<long>(frame.rgb.size());
  ++stats_.frames;
}

SinkStats VideoWriter::finish() {
  if (!pipe_) return stats_;
  std::fclose(pipe_);  // end of input: ffmpeg finishes the file
  pipe_ = nullptr;
  int status = 0;
  while (waitpid(child_, &status, 0) < 0 && errno == EINTR) {
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    throw ImageError(path_ + ": ffmpeg failed (is the ffmpeg package installed?)");
  }
  std::error_code ec;
  stats_.bytes = static_cast<long>(std::filesystem::file_size(path_, ec));
  return stats_;
}

}  // namespace gf::render
