// The newest frame as a JPEG, for watchers of a running session (a browser, ffplay, VLC): an
// encoder thread of its own takes the newest frame pushed, encodes it with libjpeg-turbo and
// hands the bytes to every reader. Frames pushed faster than it encodes are dropped; the newest
// one pushed is kept, and encoded when a reader asks, so a newcomer gets what is drawn now (a
// session stepped on command may draw nothing more for a long time) and a slow reader never a
// backlog. Nobody watching, nothing is encoded.
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
  /// The browser view's moves the frame's state has taken and reached (sim::Snapshot's).
  long moves_taken = 0, moves_arrived = 0;
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
  /// time `time`: copied in place of the one kept (storage reused), and encoded at once when a
  /// reader waits or none has been encoded yet; `moves_taken` and `moves_arrived` go with it
  /// (JpegFrame). Any one thread (the render thread).
  void push(const Image& image, long number, double time, long moves_taken = 0, long moves_arrived = 0);
  /// The width (pixels) frames are shown at from now on: each frame is shrunk by the largest
  /// whole factor that keeps it at least that wide (shrinkFactor, shrinkByBlocks) before
  /// encoding; 0, or a width of at least the frame's, encodes frames as pushed. When that
  /// changes the factor and no newer frame is pushed, the newest one is encoded again for the
  /// next reader (waitNewer returns no frame of another factor, unless the last encoding
  /// failed: then the newest encoded frame stands as it is). Any thread.
  void setWidth(int width);
  /// The newest encoded frame (number 0 when none yet). Any thread.
  JpegFrame newest() const;
  /// Waits until a frame newer than `after`, and no older than the newest pushed before the
  /// call, is encoded, the stream closes or `timeout` passes; returns the newest (check
  /// `number > after`). waitNewer(0, ...) is the frame drawn now. Any thread.
  JpegFrame waitNewer(long after, std::chrono::milliseconds timeout);
  /// Readers waiting in waitNewer now (for tests). Any thread.
  int waiting() const;
  /// Wakes every waiting reader and stops the encoder; newest() still answers. Idempotent.
  void close();
  bool closed() const;
  JpegStats stats() const;

 private:
  void run();
  bool encodeWanted() const;  // mutex_ held
  bool newestStale() const;   // mutex_ held: newest_ is of another factor than width_ asks
  class Compressor;
  std::unique_ptr<Compressor> compressor_;
  int quality_;
  int width_ = 0;           // setWidth's (mutex_)
  int newest_factor_ = 1;   // the factor newest_ was shrunk by
  int newest_source_width_ = 0;  // the width of the frame newest_ was encoded from
  bool background_;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  Image pending_;           // the newest frame pushed, not yet encoded
  double pending_time_ = 0.0;
  long pending_number_ = 0;
  long pending_taken_ = 0, pending_arrived_ = 0;
  bool has_pending_ = false;
  long encoding_number_ = 0;  // the frame the encoder took last
  int waiting_ = 0;         // readers in waitNewer
  bool closing_ = false;
  JpegFrame newest_;
  JpegStats stats_;
  std::thread thread_;
};

}  // namespace gf::render
