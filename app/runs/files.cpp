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
#include <utility>
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

std::uint64_t fnv1a64(std::uint64_t h, std::string_view bytes) {
  for (const char c : bytes) h = (h ^ static_cast<unsigned char>(c)) * 0x100000001b3ull;
  return h;
}

std::string hex64(std::uint64_t h) {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(h));
  return text;
}

std::string fileFnv1a64(const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) return {};
  std::uint64_t h = kFnv1a64Basis;
  std::vector<char> buffer(65536);
  for (std::size_t n; (n = std::fread(buffer.data(), 1, buffer.size(), f)) > 0;) h = fnv1a64(h, {buffer.data(), n});
  const bool read = std::ferror(f) == 0;
  std::fclose(f);
  return read ? hex64(h) : std::string();
}

namespace {
// The writer's text is handed to the file once it holds this much (256 kB: about 3 writes a
// second for fig8's trace at 1 kHz, 786 kB/s, and 0.8 MB less held than at 1 MB).
constexpr std::size_t kWriteBytes = std::size_t{1} << 18;
// How long the writer sleeps when it finds the ring empty (the owner wakes it only when the ring
// is full, when it waits anyway; close() does).
constexpr auto kWriterPoll = std::chrono::milliseconds(10);
}  // namespace

struct RowFile::Writer {
  std::string path, tmp;
  std::ofstream out;
  std::size_t columns = 0;
  RowFileOptions options;
  std::vector<double> ring;                 // ring_rows rows of `columns` numbers
  alignas(64) std::atomic<std::size_t> head{0};  // rows pushed (owner)
  alignas(64) std::atomic<std::size_t> tail{0};  // rows formatted (writer)
  std::atomic<bool> failed{false};          // set by the writer, seen by the owner at its next push
  long waits = 0;                           // owner only
  // Writer thread, then close(): what is on disk for sure (whole rows, the header included).
  std::uint64_t written_bytes = 0, formatted_bytes = 0;
  std::size_t written_rows = 0;
  std::mutex mutex;                         // close() only: never taken by push()
  std::condition_variable closing_changed;
  bool closing = false;
  bool closed = false;
  bool watched = false;                     // on_rows was called
  std::thread thread;

  // Appends `text` (`rows` whole rows) to the file and flushes it, so a failure is seen at the
  // chunk it hit and every byte before it is known to be written.
  void writeText(std::string& text, std::size_t rows) {
    if (!failed && !text.empty()) {
      const std::uint64_t limit = options.fail_after_bytes;
      if (limit > 0 && written_bytes + text.size() > limit) {  // a full disk, as a test asks for
        out.write(text.data(), static_cast<std::streamsize>(limit - written_bytes));
        out.flush();
        failed = true;
      } else {
        out.write(text.data(), static_cast<std::streamsize>(text.size()));
        out.flush();
        if (!out) failed = true;
        else written_bytes += text.size(), written_rows += rows;
      }
    }
    text.clear();
  }

  // After a failed write, the length of the file up to the last whole row that reached the disk
  // (a chunk that failed may be there in part) and the rows before it.
  std::pair<std::uint64_t, std::size_t> wholeRows() const {
    std::error_code ec;
    const std::uint64_t size = std::filesystem::file_size(tmp, ec);
    if (ec || size <= written_bytes) return {written_bytes, written_rows};
    std::ifstream in(tmp, std::ios::binary);
    in.seekg(static_cast<std::streamoff>(written_bytes));
    std::string rest(size - written_bytes, '\0');
    in.read(rest.data(), static_cast<std::streamsize>(rest.size()));
    rest.resize(static_cast<std::size_t>(std::max<std::streamsize>(0, in.gcount())));
    const std::size_t last = rest.rfind('\n');
    if (last == std::string::npos) return {written_bytes, written_rows};
    const auto lines = static_cast<std::size_t>(std::count(rest.begin(), rest.begin() + static_cast<std::ptrdiff_t>(last) + 1, '\n'));
    // With nothing written before, the first line is the header.
    return {written_bytes + last + 1, written_rows + lines - (written_bytes == 0 ? 1 : 0)};
  }

  void watch(std::size_t rows) {
    if (watched || !options.on_rows || rows < options.watch_rows) return;
    watched = true;
    options.on_rows(rows, formatted_bytes);
  }

  void run() {
    std::string text;
    std::size_t rows = 0;  // in `text`
    text.reserve(kWriteBytes + 64 * 1024);
    for (;;) {
      const std::size_t h = head.load(std::memory_order_acquire);
      std::size_t t = tail.load(std::memory_order_relaxed);
      if (t == h) {
        writeText(text, std::exchange(rows, 0));
        std::unique_lock lock(mutex);
        if (closing && tail.load(std::memory_order_relaxed) == head.load(std::memory_order_acquire)) return;
        closing_changed.wait_for(lock, kWriterPoll);
        continue;
      }
      for (; t != h; ++t) {
        const std::size_t before = text.size();
        const double* row = &ring[(t % options.ring_rows) * columns];
        for (std::size_t c = 0; c < columns; ++c) {
          if (c > 0) text += ',';
          appendNumber(text, row[c]);
        }
        text += '\n';
        formatted_bytes += text.size() - before;
        ++rows;
        if (text.size() >= kWriteBytes) {
          tail.store(t + 1, std::memory_order_release);
          writeText(text, std::exchange(rows, 0));
        }
      }
      tail.store(t, std::memory_order_release);
      watch(t);
    }
  }
};

RowFile::RowFile(std::string path, const std::vector<std::string>& columns, RowFileOptions options)
    : writer_(std::make_unique<Writer>()) {
  Writer& w = *writer_;
  w.path = std::move(path);
  w.tmp = w.path + ".tmp";
  w.options = std::move(options);
  w.options.ring_rows = std::max<std::size_t>(1, w.options.ring_rows);
  w.out.open(w.tmp, std::ios::binary | std::ios::trunc);
  if (!w.out) throw std::runtime_error(w.tmp + ": cannot create");
  std::string header;
  for (const std::string& c : columns) header.append(header.empty() ? "" : ",").append(c);
  header += '\n';
  w.formatted_bytes = header.size();
  w.writeText(header, 0);
  w.columns = columns.size();
  w.ring.assign(w.options.ring_rows * w.columns, 0.0);  // touched now, so the run takes no page fault in it
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
  if (h - w.tail.load(std::memory_order_acquire) == w.options.ring_rows) {
    ++w.waits;  // the writer is a whole ring behind: wait for it rather than lose a row
    w.closing_changed.notify_one();  // and wake it from its nap (kWriterPoll) if it took one
    while (h - w.tail.load(std::memory_order_acquire) == w.options.ring_rows) {
      if (w.failed.load(std::memory_order_relaxed)) throw std::runtime_error(w.path + ": cannot write (disk full?)");
      std::this_thread::yield();
    }
  }
  std::copy(row, row + w.columns, &w.ring[(h % w.options.ring_rows) * w.columns]);
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
  std::error_code ec;
  const bool failed = w.failed || !w.out;
  // After a failure, what reached the disk up to its last whole row (the header included).
  const auto [length, rows] = failed ? w.wholeRows() : std::pair<std::uint64_t, std::size_t>{0, 0};
  if (failed && length == 0) {  // not even the header: nothing worth keeping
    std::filesystem::remove(w.tmp, ec);
    throw std::runtime_error(w.path + ": cannot write (disk full?); nothing could be kept");
  }
  if (failed) std::filesystem::resize_file(w.tmp, length, ec);
  if (!ec) std::filesystem::rename(w.tmp, w.path, ec);
  if (ec) throw std::runtime_error(w.path + ": cannot replace: " + ec.message());
  if (failed) {
    throw std::runtime_error(w.path + ": cannot write (disk full?); kept its first " + std::to_string(rows) +
                             " rows (a valid CSV up to its last whole row)");
  }
}

}  // namespace gf::app
