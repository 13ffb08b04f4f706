// The newest frame as a JPEG, for watchers of a running session (a browser, ffplay, VLC): an
// encoder thread of its own takes the newest frame pushed, encodes it with libjpeg-turbo and
// hands the bytes to every reader. Frames pushed faster than it encodes are dropped, and so are
// frames no reader waits for: a slow reader gets the newest frame, never a backlog.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "render/frames/image.hpp"

namespace gf::render {

/// One encoded frame; `bytes` is shared by every reader and never changes.
struct JpegFrame {
  std::shared_ptr<const std::vector<std::uint8_t>> bytes;
  long number = 0;     ///< the frame's number as pushed (increasing; 0: none yet)
  double time = 0.0;   ///< s: simulated time of the frame
};

/// What the encoder did.
struct JpegStats {
  long pushed = 0;          ///< frames handed to push()
  long encoded = 0;         ///< frames encoded
  double encode_seconds = 0.0;  ///< time spent encoding (wall clock)
  long bytes = 0;           ///< bytes of the frames encoded
};

class JpegStream {
 public:
  /// `quality` 1..100. `background`: the encoder thread lowers itself to nice 10, like the render
  /// thread of a realtime run. Throws ImageError when libjpeg-turbo cannot start.
  explicit JpegStream(int quality = 80, bool background = false);
  ~JpegStream();
  JpegStream(const JpegStream&) = delete;
  JpegStream& operator=(const JpegStream&) = delete;

  /// The newest frame, number `number` (greater than every number pushed before) at simulated
  /// time `time`: copied when a reader is waiting for a newer one or none has been encoded yet,
  /// otherwise dropped. Any one thread (the render thread).
  void push(const Image& image, long number, double time);
  /// The newest encoded frame (number 0 when none yet). Any thread.
  JpegFrame newest() const;
  /// Waits until a frame newer than `after` is encoded, the stream closes or `timeout` passes;
  /// returns the newest (check `number > after`). Any thread.
  JpegFrame waitNewer(long after, std::chrono::milliseconds timeout);
  /// Readers waiting in waitNewer now (for tests). Any thread.
  int waiting() const;
  /// Wakes every waiting reader and stops the encoder; newest() still answers. Idempotent.
  void close();
  bool closed() const;
  JpegStats stats() const;

 private:
  void run();
  class Compressor;
  std::unique_ptr<Compressor> compressor_;
  int quality_;
  bool background_;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  Image pending_;           // the newest frame pushed, not yet encoded
  double pending_time_ = 0.0;
  long pending_number_ = 0;
  bool has_pending_ = false;
  int waiting_ = 0;         // readers in waitNewer
  bool closing_ = false;
  JpegFrame newest_;
  JpegStats stats_;
  std::thread thread_;
};

}  // namespace gf::render
