// Writing a run's files so that a reader never sees half of one: whole through a temporary name
// and a rename, or rows of numbers streamed by a writer thread while the run goes and renamed when
// complete.
#pragma once

#include <memory>
#include <string>
#include <vector>

namespace gf::app {

/// A CSV file of numbers written while a run goes, so a long run's rows never pile up in memory
/// and its owner (the haptic thread) never waits for the disk, a lock or the formatting: each row's
/// numbers go into a single-producer single-consumer ring (lock-free; allocated and touched when
/// the file opens), from which a writer thread formats them (shortest round-trip decimals, as
/// appendNumber) and appends them to `path.tmp`. `close()` writes the rest and renames the file
/// into place, so an earlier file is only replaced by a complete one; an owner destroyed without
/// `close()` (a run that threw) closes it too, with the rows it reached. One owner thread.
class RowFile {
 public:
  /// Opens `path.tmp` and writes the header line of `columns`. Throws std::runtime_error naming
  /// the file when it cannot be created.
  RowFile(std::string path, const std::vector<std::string>& columns, std::size_t ring_rows = kRingRows);
  ~RowFile();
  RowFile(const RowFile&) = delete;
  RowFile& operator=(const RowFile&) = delete;

  std::size_t columns() const;
  /// Appends one row of columns() numbers. Waits only while the ring is full (the writer is
  /// ring_rows rows behind: a disk stalled for seconds). Throws std::runtime_error naming the file
  /// once a write has failed (a full disk).
  void push(const double* row);
  /// Writes everything and renames `path.tmp` to `path`. Throws std::runtime_error on I/O failure
  /// (a full disk), naming the file; the earlier `path`, if any, is then left as it was.
  void close();
  /// How often push() found the ring full and waited for the writer.
  long waits() const;

  static constexpr std::size_t kRingRows = 8192;  ///< about 8 s of a 1 kHz run

 private:
  struct Writer;
  std::unique_ptr<Writer> writer_;
};

/// Appends the shortest decimal that reads back as exactly `x`.
void appendNumber(std::string& out, double x);

/// Writes `text` to `path` via `path.tmp` and a rename. Throws std::runtime_error on failure.
void writeFileAtomically(const std::string& path, const std::string& text);

}  // namespace gf::app
