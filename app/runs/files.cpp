#include "app/runs/files.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <charconv>
#include <condition_variable>
#include <cstdio>
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
// The writer's text is handed to the file once it holds this much.
constexpr std::size_t kWriteBytes = std::size_t{1} << 20;
// How long the writer sleeps when it finds the ring empty (the owner never wakes it: close() does).
constexpr auto kWriterPoll = std::chrono::milliseconds(10);
}  // namespace

struct RowFile::Writer {
  std::string path, tmp;
  std::ofstream out;
  std::size_t columns = 0, ring_rows = 0;
  std::vector<double> ring;                 // ring_rows rows of `columns` numbers
  alignas(64) std::atomic<std::size_t> head{0};  // rows pushed (owner)
  alignas(64) std::atomic<std::size_t> tail{0};  // rows formatted (writer)
  std::atomic<bool> failed{false};          // set by the writer, seen by the owner at its next push
  long waits = 0;                           // owner only
  std::mutex mutex;                         // close() only: never taken by push()
  std::condition_variable closing_changed;
  bool closing = false;
  bool closed = false;
  std::thread thread;

  void writeText(std::string& text) {
    if (!failed && !text.empty()) {
      out.write(text.data(), static_cast<std::streamsize>(text.size()));
      if (!out) failed = true;
    }
    text.clear();
  }

  void run() {
    std::string text;
    text.reserve(kWriteBytes + 64 * 1024);
    for (;;) {
      const std::size_t h = head.load(std::memory_order_acquire);
      std::size_t t = tail.load(std::memory_order_relaxed);
      if (t == h) {
        writeText(text);
        std::unique_lock lock(mutex);
        if (closing && tail.load(std::memory_order_relaxed) == head.load(std::memory_order_acquire)) return;
        closing_changed.wait_for(lock, kWriterPoll);
        continue;
      }
      for (; t != h; ++t) {
        const double* row = &ring[(t % ring_rows) * columns];
        for (std::size_t c = 0; c < columns; ++c) {
          if (c > 0) text += ',';
          appendNumber(text, row[c]);
        }
        text += '\n';
        if (text.size() >= kWriteBytes) {
          tail.store(t + 1, std::memory_order_release);
          writeText(text);
        }
      }
      tail.store(t, std::memory_order_release);
    }
  }
};

RowFile::RowFile(std::string path, const std::vector<std::string>& columns, std::size_t ring_rows)
    : writer_(std::make_unique<Writer>()) {
  Writer& w = *writer_;
  w.path = std::move(path);
  w.tmp = w.path + ".tmp";
  w.out.open(w.tmp, std::ios::binary | std::ios::trunc);
  if (!w.out) throw std::runtime_error(w.tmp + ": cannot create");
  std::string header;
  for (const std::string& c : columns) header.append(header.empty() ? "" : ",").append(c);
  header += '\n';
  w.writeText(header);
  w.columns = columns.size();
  w.ring_rows = std::max<std::size_t>(1, ring_rows);
  w.ring.assign(w.ring_rows * w.columns, 0.0);  // touched now, so the run takes no page fault in it
  w.thread = std::thread([&w] { w.run(); });
}

RowFile::~RowFile() {
  try {
    close();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "[godfinger] %s\n", e.what());
  }
}

std::size_t RowFile::columns() const { return writer_->columns; }
long RowFile::waits() const { return writer_->waits; }

void RowFile::push(const double* row) {
  Writer& w = *writer_;
  // A write that failed (a full disk) stops the owner now, not at close().
  if (w.failed.load(std::memory_order_relaxed)) throw std::runtime_error(w.path + ": cannot write (disk full?)");
  const std::size_t h = w.head.load(std::memory_order_relaxed);
  if (h - w.tail.load(std::memory_order_acquire) == w.ring_rows) {
    ++w.waits;  // the writer is a whole ring behind: wait for it rather than lose a row
    while (h - w.tail.load(std::memory_order_acquire) == w.ring_rows) {
      if (w.failed.load(std::memory_order_relaxed)) throw std::runtime_error(w.path + ": cannot write (disk full?)");
      std::this_thread::yield();
    }
  }
  std::copy(row, row + w.columns, &w.ring[(h % w.ring_rows) * w.columns]);
  w.head.store(h + 1, std::memory_order_release);
}

void RowFile::close() {
  Writer& w = *writer_;
  if (w.closed) return;
  w.closed = true;
  {
    std::lock_guard lock(w.mutex);
    w.closing = true;
  }
  w.closing_changed.notify_one();
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
