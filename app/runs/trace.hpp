// trace.csv: one row per haptic step, written deterministically (shortest round-trip numbers).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "sim/world.hpp"

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

/// trace.csv's columns for a scene, in order (as TraceWriter documents them).
std::vector<std::string> traceColumns(const sim::SceneDesc& scene);

/// trace.csv, streamed to its file while the run goes (haptic thread only).
class TraceWriter {
 public:
  /// Writes the header for the world's dynamic bodies and fingers.
  /// Columns: t; per dynamic body its pose (.px .py .pz .qx .qy .qz .qw); per finger its
  /// coupling force (.fx .fy .fz), SGO count (.n_sgo), contact radius (.r), proxy and device
  /// positions (.px .py .pz, .dx .dy .dz); per dynamic body its linear (.vx .vy .vz, m/s) and
  /// angular (.wx .wy .wz, rad/s, world frame) velocity.
  TraceWriter(const sim::World& world, const std::string& path);

  /// Appends the row of the world's current state.
  void record(const sim::World& world);

  /// Writes the last rows and puts the file in place (see StreamedFile::close).
  void close() { file_.close(); }

 private:
  StreamedFile file_;
  std::vector<int> dynamic_bodies_;
};

/// Appends the shortest decimal that reads back as exactly `x`.
void appendNumber(std::string& out, double x);

/// Writes `text` to `path` via `path.tmp` and a rename. Throws std::runtime_error on failure.
void writeFileAtomically(const std::string& path, const std::string& text);

}  // namespace gf::app
