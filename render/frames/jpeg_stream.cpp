#include "render/frames/jpeg_stream.hpp"

#include <turbojpeg.h>

#include <pthread.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>

#include "render/frames/frame_sinks.hpp"
#include "render/frames/shrink.hpp"

namespace gf::render {
namespace {

using Clock = std::chrono::steady_clock;

}  // namespace

// libjpeg-turbo's compressor: made by the constructor (which throws when it cannot), used by the
// encoder thread only.
class JpegStream::Compressor {
 public:
  Compressor() : handle_(tjInitCompress()) {
    if (!handle_) throw ImageError(std::string("libjpeg-turbo: ") + tjGetErrorStr2(nullptr));
  }
  ~Compressor() { tjDestroy(handle_); }
  Compressor(const Compressor&) = delete;
  Compressor& operator=(const Compressor&) = delete;

  // `image` as a baseline JPEG (4:2:0, fast DCT) into `out`, whose storage is reused.
  void encode(const Image& image, int quality, std::vector<std::uint8_t>& out) {
    out.resize(tjBufSize(image.width, image.height, TJSAMP_420));
    unsigned char* data = out.data();
    unsigned long size = out.size();
    if (tjCompress2(handle_, image.rgb.data(), image.width, 0, image.height, TJPF_RGB, &data, &size, TJSAMP_420,
                    quality, TJFLAG_FASTDCT | TJFLAG_NOREALLOC) != 0) {
      throw ImageError(std::string("libjpeg-turbo: ") + tjGetErrorStr2(handle_));
    }
    out.resize(size);
  }

 private:
  tjhandle handle_;
};

JpegStream::JpegStream(int quality, bool background) : quality_(quality), background_(background) {
  if (quality < 1 || quality > 100) throw ImageError("JPEG quality must be 1..100");
  compressor_ = std::make_unique<Compressor>();
  thread_ = std::thread([this] { run(); });
}

JpegStream::~JpegStream() { close(); }

void JpegStream::push(const Image& image, long number, double time, long moves_taken, long moves_arrived) {
  std::lock_guard lock(mutex_);
  ++stats_.pushed;
  if (closing_) return;
  // Kept as the newest drawn (its storage reused), encoded only when a reader asks for it.
  pending_.width = image.width;
  pending_.height = image.height;
  pending_.rgb.assign(image.rgb.begin(), image.rgb.end());
  pending_time_ = time;
  pending_number_ = number;
  pending_taken_ = moves_taken;
  pending_arrived_ = moves_arrived;
  has_pending_ = true;
  if (encodeWanted()) changed_.notify_all();
}

bool JpegStream::newestStale() const {
  return newest_.number > 0 && shrinkFactor(newest_source_width_, width_) != newest_factor_;
}

bool JpegStream::encodeWanted() const {
  return (has_pending_ || newestStale()) && (waiting_ > 0 || newest_.number == 0);
}

void JpegStream::setWidth(int width) {
  std::lock_guard lock(mutex_);
  width_ = std::max(0, width);
  changed_.notify_all();  // an encoding now wanted, or a reader's frame no longer stale
}

JpegFrame JpegStream::newest() const {
  std::lock_guard lock(mutex_);
  return newest_;
}

JpegFrame JpegStream::waitNewer(long after, std::chrono::milliseconds timeout) {
  std::unique_lock lock(mutex_);
  // Newer than `after`, and no older than the newest pushed now: a newcomer sees what is drawn.
  const long wanted = std::max(after + 1, has_pending_ ? pending_number_ : encoding_number_);
  ++waiting_;
  if (encodeWanted()) changed_.notify_all();
  changed_.wait_for(lock, timeout, [&] { return (newest_.number >= wanted && !newestStale()) || closing_; });
  --waiting_;
  return newest_;
}

void JpegStream::close() {
  {
    std::lock_guard lock(mutex_);
    closing_ = true;
    changed_.notify_all();
  }
  if (thread_.joinable()) thread_.join();
}

int JpegStream::waiting() const {
  std::lock_guard lock(mutex_);
  return waiting_;
}

bool JpegStream::closed() const {
  std::lock_guard lock(mutex_);
  return closing_;
}

JpegStats JpegStream::stats() const {
  std::lock_guard lock(mutex_);
  return stats_;
}

void JpegStream::run() {
  pthread_setname_np(pthread_self(), "gf-jpeg");
  if (background_) setpriority(PRIO_PROCESS, static_cast<id_t>(gettid()), kBackgroundNice);
  Image frame, shrunk;
  bool frame_is_newest = false;  // `frame` holds the pixels of newest_
  std::vector<std::uint8_t> bytes;
  for (;;) {
    double time = 0.0;
    long number = 0, taken = 0, arrived = 0;
    int factor = 1;
    bool again = false;  // the frame kept from the last encoding, for a watcher's new width
    {
      std::unique_lock lock(mutex_);
      changed_.wait(lock, [&] { return encodeWanted() || closing_; });
      if (closing_) return;
      again = !has_pending_;
      if (again && !frame_is_newest) {  // (the last encoding failed): newest_ stands as it is
        newest_factor_ = shrinkFactor(newest_source_width_, width_);
        changed_.notify_all();
        continue;
      }
      if (again) {
        time = newest_.time, number = newest_.number, taken = newest_.moves_taken, arrived = newest_.moves_arrived;
      } else {
        std::swap(frame, pending_);
        time = pending_time_;
        number = pending_number_;
        taken = pending_taken_;
        arrived = pending_arrived_;
        encoding_number_ = number;
        has_pending_ = false;
      }
      factor = shrinkFactor(frame.width, width_);
    }
    const auto begin = Clock::now();
    try {
      if (factor > 1) shrinkByBlocks(frame, factor, shrunk);
      compressor_->encode(factor > 1 ? shrunk : frame, quality_, bytes);
    } catch (const ImageError&) {
      frame_is_newest = false;  // skipped; the next one may encode
      continue;
    }
    frame_is_newest = true;
    auto shared = std::make_shared<const std::vector<std::uint8_t>>(bytes);
    const double seconds = std::chrono::duration<double>(Clock::now() - begin).count();
    std::lock_guard lock(mutex_);
    newest_ = {std::move(shared), number, time, taken, arrived};
    newest_factor_ = factor;
    newest_source_width_ = frame.width;
    ++stats_.encoded;
    stats_.encode_seconds += seconds;
    stats_.bytes += static_cast<long>(newest_.bytes->size());
    changed_.notify_all();
  }
}

}  // namespace gf::render
