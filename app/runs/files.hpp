// Writing a run's files so that a reader never sees half of one: whole through a temporary name
// and a rename, or streamed by a writer thread while the run goes and renamed when complete.
#pragma once

#include <memory>
#include <string>

namespace gf::app {

/// A text file written while a run goes, so a long run's rows never pile up in memory: the
/// owner appends to `block()` and calls `rowDone()` after each row; every full block (1 MiB) goes
/// to a writer thread that appends it to `path.tmp`, and the owner carries on in a recycled block
/// (no allocation once the writer keeps up). `close()` writes the rest and renames the file into
/// place, so an earlier file is only replaced by a complete one; an owner destroyed without
/// `close()` (a run that threw) closes it too, with the rows it reached. One owner thread.
class StreamedFile {
 public:
  /// Opens `path.tmp`. Throws std::runtime_error naming it when it cannot be created.
  explicit StreamedFile(std::string path);
  ~StreamedFile();
  StreamedFile(const StreamedFile&) = delete;
  StreamedFile& operator=(const StreamedFile&) = delete;

  std::string& block() { return *block_; }
  /// Hands the block to the writer when it is full.
  void rowDone() {
    if (block_->size() >= kBlockBytes) handOverFull();
  }
  /// Writes everything and renames `path.tmp` to `path`. Throws std::runtime_error on I/O failure
  /// (a full disk), naming the file; the earlier `path`, if any, is then left as it was.
  void close();

  static constexpr std::size_t kBlockBytes = std::size_t{1} << 20;

 private:
  struct Writer;
  void handOver();
  void handOverFull();  // handOver, throwing std::runtime_error first when a write has failed
  std::unique_ptr<Writer> writer_;
  std::unique_ptr<std::string> block_;
};

/// Appends the shortest decimal that reads back as exactly `x`.
void appendNumber(std::string& out, double x);

/// Writes `text` to `path` via `path.tmp` and a rename. Throws std::runtime_error on failure.
void writeFileAtomically(const std::string& path, const std::string& text);

}  // namespace gf::app
