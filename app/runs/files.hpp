// Writing a run's files so that a reader never sees half of one: whole through a temporary name
// and a rename, or rows of numbers streamed by a writer thread while the run goes and renamed when
// complete.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace gf::app {

/// Rows a realtime run's ring holds: about 8 s of a 1 kHz run, a disk stalled that long.
inline constexpr std::size_t kRealtimeRingRows = 8192;
/// Rows an offline run's ring holds: its steps wait for the writer, and wake it, when it is a
/// ring behind, so a ring of a few milliseconds' rows keeps the writer busy (0.37 MB for fig8's
/// 45 columns against 2.9 MB).
inline constexpr std::size_t kOfflineRingRows = 1024;

/// How a RowFile writes, beyond its path and columns.
struct RowFileOptions {
  std::size_t ring_rows = kRealtimeRingRows;  ///< rows the ring holds
  /// The writer thread calls this once, when it has formatted `watch_rows` rows, with the rows and
  /// the bytes of text they made (header included): a trace projecting its size. Empty: never.
  std::function<void(std::size_t rows, std::uint64_t bytes)> on_rows;
  std::size_t watch_rows = 0;
  /// Tests only: writing fails once the file would pass this many bytes, part of the last chunk
  /// written as a full disk does (0: never).
  std::uint64_t fail_after_bytes = 0;
};

/// A CSV file of numbers written while a run goes, so a long run's rows never pile up in memory
/// and its owner (the haptic thread) never waits for the disk, a lock or the formatting: each row's
/// numbers go into a single-producer single-consumer ring (lock-free; allocated and touched when
/// the file opens), from which a writer thread formats them (shortest round-trip decimals, as
/// appendNumber) and appends them to `path.tmp`. `close()` writes the rest and renames the file
/// into place; an owner destroyed without `close()` (a run that threw) closes it too, with the
/// rows it reached. A write that fails (a full disk) keeps what was written: the file is cut back
/// to its last whole row and put in place, a valid CSV of the rows before, and close() says so.
/// One owner thread.
class RowFile {
 public:
  /// Opens `path.tmp` and writes the header line of `columns`. Throws std::runtime_error naming
  /// the file when it cannot be created.
  RowFile(std::string path, const std::vector<std::string>& columns, RowFileOptions options = {});
  ~RowFile();
  RowFile(const RowFile&) = delete;
  RowFile& operator=(const RowFile&) = delete;

  std::size_t columns() const;
  /// Appends one row of columns() numbers. Waits only while the ring is full (the writer is
  /// ring_rows rows behind: a disk stalled for seconds). Throws std::runtime_error naming the file
  /// once a write has failed (a full disk).
  void push(const double* row);
  /// Writes everything and renames `path.tmp` to `path`. After an I/O failure (a full disk) the
  /// file is cut back to the last whole row written and put in place all the same (a header
  /// alone when no row was whole; nothing when not even the header was written), and
  /// std::runtime_error is thrown naming the file and the rows kept.
  void close();
  /// How often push() found the ring full and waited for the writer.
  long waits() const;


 private:
  struct Writer;
  std::unique_ptr<Writer> writer_;
};

/// Appends the shortest decimal that reads back as exactly `x`.
void appendNumber(std::string& out, double x);

/// Writes `text` to `path` via `path.tmp` and a rename. Throws std::runtime_error on failure.
void writeFileAtomically(const std::string& path, const std::string& text);

/// 64-bit FNV-1a of `bytes` continued from `h` (start with kFnv1a64Basis).
std::uint64_t fnv1a64(std::uint64_t h, std::string_view bytes);
/// FNV-1a 64's offset basis: the hash of nothing.
inline constexpr std::uint64_t kFnv1a64Basis = 0xcbf29ce484222325ull;

/// 64-bit FNV-1a of a file's bytes as 16 hex digits; empty when it cannot be read. Reads the
/// file in 64 KiB blocks (a 30 MB executable: about 40 ms).
std::string fileFnv1a64(const std::string& path);

/// `h` as 16 hex digits.
std::string hex64(std::uint64_t h);

}  // namespace gf::app
