#include "render/frames/frame_sinks.hpp"

#include "render/frames/video_file.hpp"

#include <cctype>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <optional>
#include <vector>

#include <fcntl.h>
#include <pthread.h>
#include <sys/mman.h>
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
  pthread_setname_np(pthread_self(), "gf-png");  // for top and perf
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
    // The same pixels as the frame before (the encoder's rows of it): the same file, without
    // encoding it again.
    const bool repeated = !previous_png_.empty() && encoder_.sameAsLast(frame);
    try {
      if (!repeated) previous_png_ = encoder_.encode(frame);
      writeFileAtomically((std::filesystem::path(folder_) / name).string(), previous_png_);
    } catch (const ImageError& e) {
      previous_png_.clear();
      std::lock_guard lock(mutex_);
      if (error_.empty()) error_ = e.what();
      changed_.notify_all();
    }
    std::lock_guard lock(mutex_);
    stats_.busy_seconds += secondsSince(start);
    stats_.bytes += static_cast<long>(previous_png_.size());
    stats_.repeated += repeated ? 1 : 0;
    stats_.banded = encoder_.bandedImages();
    stats_.bands_compressed = encoder_.bandsCompressed();
    if (spares_.size() <= depth_ && !frame.rgb.empty()) spares_.push_back(std::move(frame));
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
    : path_(path), part_(path + "." + std::to_string(getpid()) + ".part"), width_(width), height_(height) {
  const std::optional<std::string> container = videoContainer(path);
  if (!container) throw ImageError(path + ": the video's name must end in .mp4, .mkv or .mov");
  container_ = *container;
  // ffmpeg reads the frames from a pipe on its standard input and writes the file under a
  // temporary name (the container given, as the name does not say it); what it says goes to a
  // memory file read when it ends. It is started without a shell (any path works), in a process
  // group of its own, so a Ctrl-C at the terminal reaches only godfinger, which then ends the
  // video by closing the pipe; and with no signal blocked.
  const std::string size = std::to_string(width) + "x" + std::to_string(height);
  char rate[32], quality[16];
  std::snprintf(rate, sizeof rate, "%g", fps);
  std::snprintf(quality, sizeof quality, "%d", crf);
  std::vector<const char*> argv = {"ffmpeg", "-loglevel", "error", "-y", "-f", "rawvideo", "-pix_fmt",
                                   "rgb24", "-s", size.c_str(), "-r", rate, "-i", "-", "-c:v", "libx264", "-preset",
                                   "veryfast", "-crf", quality, "-pix_fmt", "yuv420p"};
  if (container_ != "matroska") argv.insert(argv.end(), {"-movflags", "+faststart"});
  argv.insert(argv.end(), {"-f", container_.c_str(), part_.c_str(), nullptr});
  messages_ = memfd_create("ffmpeg-stderr", MFD_CLOEXEC);
  if (messages_ < 0) throw ImageError(path + ": cannot start ffmpeg: no memory file for its messages");
  int fds[2];
  if (pipe2(fds, O_CLOEXEC) != 0) {
    closeMessages();
    throw ImageError(path + ": cannot start ffmpeg: no pipe");
  }
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, fds[0], STDIN_FILENO);
  posix_spawn_file_actions_adddup2(&actions, messages_, STDERR_FILENO);
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  sigset_t none;
  sigemptyset(&none);
  posix_spawnattr_setsigmask(&attributes, &none);
  posix_spawnattr_setpgroup(&attributes, 0);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP | POSIX_SPAWN_SETSIGMASK);
  const int failed =
      posix_spawnp(&child_, "ffmpeg", &actions, &attributes, const_cast<char* const*>(argv.data()), environ);
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attributes);
  close(fds[0]);
  if (failed != 0) {
    close(fds[1]);
    closeMessages();
    throw ImageError(path + ": cannot start ffmpeg (is the ffmpeg package installed?): " + std::strerror(failed));
  }
  pipe_ = fdopen(fds[1], "w");
  if (!pipe_) {
    close(fds[1]);
    abandon();
    throw ImageError(path + ": cannot start ffmpeg: no stream");
  }
}

void VideoWriter::closeMessages() {
  if (messages_ >= 0) close(messages_);
  messages_ = -1;
}

void VideoWriter::abandon() {
  if (pipe_) std::fclose(pipe_);
  pipe_ = nullptr;
  if (child_ > 0) {
    kill(child_, SIGKILL);  // its video is not kept: no need to let it finish encoding
    while (waitpid(child_, nullptr, 0) < 0 && errno == EINTR) {
    }
    child_ = 0;
  }
  closeMessages();
  std::error_code ignored;
  std::filesystem::remove(part_, ignored);
}

VideoWriter::~VideoWriter() {
  abandon();  // a video that was not finished is not kept (after finish(), only the fds are left)
}

void VideoWriter::push(const Image& frame) {
  if (!pipe_) throw ImageError(path_ + ": video already finished");
  if (frame.width != width_ || frame.height != height_) throw ImageError(path_ + ": frame size changed");
  const auto start = Clock::now();
  if (std::fwrite(frame.rgb.data(), 1, frame.rgb.size(), pipe_) != frame.rgb.size()) {
    throw ImageError(path_ + ": ffmpeg stopped reading frames" + ffmpegSaid());
  }
  stats_.busy_seconds += secondsSince(start);
  stats_.bytes += static_cast<long>(frame.rgb.size());
  ++stats_.frames;
}

std::string VideoWriter::ffmpegSaid() const {
  std::string text(1024, '\0');
  const ssize_t n = pread(messages_, text.data(), text.size(), 0);
  text.resize(n > 0 ? static_cast<std::size_t>(n) : 0);
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) text.pop_back();
  for (std::size_t at = text.find('\n'); at != std::string::npos; at = text.find('\n', at)) text.replace(at, 1, "; ");
  return text.empty() ? "" : " (ffmpeg: " + text + ")";
}

SinkStats VideoWriter::finish() {
  if (!pipe_) return stats_;
  const bool flushed = std::fclose(pipe_) == 0;  // end of input: ffmpeg finishes the file
  pipe_ = nullptr;
  int status = 0;
  while (waitpid(child_, &status, 0) < 0 && errno == EINTR) {
  }
  child_ = 0;
  // ffmpeg at loglevel error says only what went wrong; a full disk it reports but exits 0 on.
  const std::string said = ffmpegSaid();
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || !said.empty() || !flushed) {
    throw ImageError(path_ + ": ffmpeg failed" + (said.empty() ? " (is the ffmpeg package installed?)" : said) +
                     "; no video written");
  }
  if (const std::optional<std::string> problem = videoFileProblem(part_, container_)) {
    throw ImageError(path_ + ": the video ffmpeg wrote is broken: " + *problem + "; no video written");
  }
  std::error_code ec;
  std::filesystem::rename(part_, path_, ec);
  if (ec) throw ImageError(path_ + ": cannot put the finished video in place: " + ec.message());
  stats_.bytes = static_cast<long>(std::filesystem::file_size(path_, ec));
  return stats_;
}

}  // namespace gf::render
