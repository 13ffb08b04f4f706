#include "app/runs/files.hpp"

#include <atomic>
#include <charconv>
#include <condition_variable>
#include <cstdio>
#include <deque>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

namespace gf::app {

void appendNumber(std::string& out, double x) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  out.append(buf, r.ptr);
}

void writeFileAtomically(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream f(tmp, std::ios::binary);
    f.write(text.data(), static_cast<std::streamsize>(text.size()));
    f.close();
    if (!f) {
      std::error_code ignored;
      std::filesystem::remove(tmp, ignored);  // no half file left behind
      throw std::runtime_error(path + ": cannot write (disk full?)");
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) throw std::runtime_error(path + ": cannot replace: " + ec.message());
}

namespace {
// Room past a full block for the row that fills it, so rows of up to this length never reallocate.
constexpr std::size_t kRowMargin = 64 * 1024;
}  // namespace

struct StreamedFile::Writer {
  std::string path, tmp;
  std::ofstream out;
  std::mutex mutex;
  std::condition_variable changed;
  std::deque<std::unique_ptr<std::string>> full;   // owner -> writer
  std::vector<std::unique_ptr<std::string>> free;  // writer -> owner, emptied, capacity kept
  bool closing = false;
  std::atomic<bool> failed{false};  // set by the writer, seen by the owner at its next hand-over
  bool closed = false;
  std::thread thread;

  void run() {
    for (;;) {
      std::unique_ptr<std::string> next;
      {
        std::unique_lock lock(mutex);
        changed.wait(lock, [&] { return !full.empty() || closing; });
        if (full.empty()) return;
        next = std::move(full.front());
        full.pop_front();
      }
      if (!failed) {
        out.write(next->data(), static_cast<std::streamsize>(next->size()));
        if (!out) failed = true;  // read by the owner only after join()
      }
      next->clear();
      std::lock_guard lock(mutex);
      free.push_back(std::move(next));
    }
  }
};

StreamedFile::StreamedFile(std::string path) : writer_(std::make_unique<Writer>()) {
  Writer& w = *writer_;
  w.path = std::move(path);
  w.tmp = w.path + ".tmp";
  w.out.open(w.tmp, std::ios::binary | std::ios::trunc);
  if (!w.out) throw std::runtime_error(w.tmp + ": cannot create");
  for (int i = 0; i < 3; ++i) {
    auto spare = std::make_unique<std::string>();
    spare->reserve(kBlockBytes + kRowMargin);
    w.free.push_back(std::move(spare));
  }
  block_ = std::move(w.free.back());
  w.free.pop_back();
  w.thread = std::thread([&w] { w.run(); });
}

StreamedFile::~StreamedFile() {
  try {
    close();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "[godfinger] %s\n", e.what());
  }
}

void StreamedFile::handOverFull() {
  // A write that failed (a full disk) stops the owner now, not at close().
  if (writer_->failed.load(std::memory_order_relaxed)) throw std::runtime_error(writer_->path + ": cannot write (disk full?)");
  handOver();
}

void StreamedFile::handOver() {
  Writer& w = *writer_;
  std::unique_ptr<std::string> next;
  {
    std::lock_guard lock(w.mutex);
    w.full.push_back(std::move(block_));
    if (!w.free.empty()) {
      next = std::move(w.free.back());
      w.free.pop_back();
    }
  }
  w.changed.notify_one();
  if (!next) {  // the writer is behind (a slow disk): one more block rather than a wait
    next = std::make_unique<std::string>();
    next->reserve(kBlockBytes + kRowMargin);
  }
  block_ = std::move(next);
}

void StreamedFile::close() {
  Writer& w = *writer_;
  if (w.closed) return;
  w.closed = true;
  if (!block_->empty()) handOver();
  {
    std::lock_guard lock(w.mutex);
    w.closing = true;
  }
  w.changed.notify_one();
  w.thread.join();
  w.out.close();
  if (w.failed || !w.out) {
    std::error_code ignored;
    std::filesystem::remove(w.tmp, ignored);
    throw std::runtime_error(w.path + ": cannot write (disk full?); its rows could not be kept");
  }
  std::error_code ec;
  std::filesystem::rename(w.tmp, w.path, ec);
  if (ec) throw std::runtime_error(w.path + ": cannot replace: " + ec.message());
}

}  // namespace gf::app
