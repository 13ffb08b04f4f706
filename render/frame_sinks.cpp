#include "render/frame_sinks.hpp"

#include <chrono>
#include <filesystem>
#include <sys/wait.h>

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
  // Quoting: the path goes to the shell inside single quotes; a quote in it is refused.
  if (path.find('\'') != std::string::npos) throw ImageError(path + ": quote in video path");
  char command[1024];
  std::snprintf(command, sizeof command,
                "ffmpeg -loglevel error -y -f rawvideo -pix_fmt rgb24 -s %dx%d -r %g -i - "
                "-c:v libx264 -preset veryfast -crf %d -pix_fmt yuv420p -movflags +faststart '%s'",
                width, height, fps, crf, path.c_str());
  pipe_ = popen(command, "w");
  if (!pipe_) throw ImageError(path + ": cannot start ffmpeg");
}

VideoWriter::~VideoWriter() {
  if (pipe_) pclose(pipe_);
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
  const int status = pclose(pipe_);
  pipe_ = nullptr;
  if (status == -1 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    throw ImageError(path_ + ": ffmpeg failed (is the ffmpeg package installed?)");
  }
  std::error_code ec;
  stats_.bytes = static_cast<long>(std::filesystem::file_size(path_, ec));
  return stats_;
}

}  // namespace gf::render
