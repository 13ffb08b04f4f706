// Where rendered frames go: a PNG sequence encoded on its own writer thread, or an MP4 made by
// the ffmpeg binary from raw frames on a pipe. Both are fed by the render thread only.
#pragma once

#include <sys/types.h>

#include <condition_variable>
#include <cstdio>
#include <deque>
#include <vector>
#include <mutex>
#include <string>
#include <thread>

#include "render/frames/image.hpp"

namespace gf::render {

/// The nice value of the threads that draw and encode frames beside a realtime haptic loop
/// (FrameOutputSettings::background_priority, the JPEG stream's encoder; 0..19, higher yields more).
constexpr int kBackgroundNice = 10;

/// Counts of a finished sink.
struct SinkStats {
  long frames = 0;
  double busy_seconds = 0.0;  ///< time spent encoding (PNG) or writing to the pipe (MP4)
  long bytes = 0;             ///< bytes written
  long repeated = 0;          ///< PNG: frames equal to the one before, written without encoding
  long banded = 0;            ///< PNG: frames encoded band by band (PngEncoder), a held scene's
  long bands_compressed = 0;  ///< PNG: the bands those frames compressed (the rest kept)
};

/// frames/000000.png, 000001.png, ... in `folder`, encoded by a writer thread (libdeflate level 1) so
/// the render thread only waits when `queue_depth` frames are already pending. One by default:
/// the next frame is drawn while one is encoded, and a run whose held frames are reused (drawn
/// faster than encoded) keeps one 2.76 MB 1280x720 image waiting, and one spare, rather than
/// three of each (fig8's 10 s with frames: 155-156 MB at its peak, 158-159 with three). A frame whose
/// pixels equal the previous frame's is written with the previous frame's bytes, not encoded
/// again (a scene at rest drawn without a time stamp or an overlay clock gives equal frames;
/// with either, as the bundled scenes are drawn, every frame differs).
class PngSequenceWriter {
 public:
  /// Creates `folder` when missing. Throws ImageError naming it when it cannot.
  PngSequenceWriter(const std::string& folder, int queue_depth = 1);
  ~PngSequenceWriter();
  PngSequenceWriter(const PngSequenceWriter&) = delete;
  PngSequenceWriter& operator=(const PngSequenceWriter&) = delete;
  /// Queues the next frame (takes the pixels). Throws the writer's first error, if any.
  void push(Image&& frame);
  /// An image whose pixel storage a written frame left (empty when none is spare yet): read the
  /// next frame into it, so frames reuse their megabytes instead of faulting in fresh pages.
  Image spare();
  /// Writes what is queued, stops the thread, rethrows the first error. Idempotent.
  SinkStats finish();

 private:
  void run();
  std::string folder_;
  std::size_t depth_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<Image> queue_;
  std::vector<Image> spares_;  // written frames' storage, at most depth_ + 1
  // Writer thread only: the encoder (which keeps the last frame's rows) and the last file's bytes.
  PngEncoder encoder_;
  std::vector<std::uint8_t> previous_png_;
  bool closing_ = false;
  std::string error_;
  SinkStats stats_;
  std::thread thread_;
};

/// An H.264 video (MP4, MOV or MKV by the name's extension) written by `ffmpeg` (libx264,
/// yuv420p, CRF `crf`, `fps` frames per second) from raw RGB frames. ffmpeg writes under a
/// temporary name beside `path` (`path.PID.part`); the file gets its name only once ffmpeg exited
/// 0 without a message and the file holds its whole container (render/frames/video_file.hpp), so a
/// broken video (a disk that filled, a dead ffmpeg) never sits under `path` and an earlier file
/// there stays. Render thread (or one owner thread).
class VideoWriter {
 public:
  /// Starts ffmpeg. Throws ImageError when it cannot be started or the extension is not one of
  /// .mp4, .mov and .mkv.
  VideoWriter(const std::string& path, int width, int height, double fps, int crf = 26);
  /// Ends ffmpeg at once if still running and removes an unfinished temporary file.
  ~VideoWriter();
  VideoWriter(const VideoWriter&) = delete;
  VideoWriter& operator=(const VideoWriter&) = delete;
  /// Writes one frame of the size given at construction. Throws ImageError when ffmpeg failed.
  void push(const Image& frame);
  /// Closes the pipe, waits for ffmpeg, checks what it said, its exit and the file, and renames
  /// the file into place. Throws ImageError naming what failed (then no file is put at `path`).
  SinkStats finish();

 private:
  std::string ffmpegSaid() const;  // " (ffmpeg: MESSAGE)", or "" when it said nothing
  void closeMessages();
  void abandon();  // ends ffmpeg at once (if running) and removes the temporary file
  std::string path_, part_, container_;
  int width_, height_;
  std::FILE* pipe_ = nullptr;  // ffmpeg's standard input
  int messages_ = -1;          // ffmpeg's standard error: a memory file
  pid_t child_ = 0;
  SinkStats stats_;
};

}  // namespace gf::render
