// trace.csv: one row per haptic step, written deterministically (shortest round-trip numbers).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "app/runs/files.hpp"
#include "sim/world/world.hpp"

namespace gf::app {

/// Whether the finger's device gives an orientation: a keyframe's (q, a CSV's qw..qz, or the
/// device's tilt) other than the identity. Only then does trace.csv record it.
bool deviceGivesOrientation(const sim::FingerDesc& finger);

/// trace.csv's columns for a scene, in order (as TraceWriter documents them).
std::vector<std::string> traceColumns(const sim::SceneDesc& scene);

/// A trace whose projection reaches this size by the run's end is warned about once (bytes).
inline constexpr double kTraceWarnBytes = 100e6;

/// The rows after which the writer projects a trace's size (its bytes a row by then).
inline constexpr std::size_t kTraceWatchRows = 1000;

/// How trace.csv is written beyond its columns.
struct TraceOptions {
  int every_steps = 1;  ///< a row every this many haptic steps (traceStride of record.trace_rate)
  bool warn_size = true;  ///< project the size after kTraceWatchRows rows; warn once past kTraceWarnBytes
  std::uint64_t fail_after_bytes = 0;  ///< tests only: a disk that fills (RowFileOptions)
  /// Rows the writer may fall behind (RowFileOptions::ring_rows): a realtime run's loop must never
  /// wait for the disk (kRealtimeRingRows); an offline run's may, and holds less (kOfflineRingRows).
  std::size_t ring_rows = kRealtimeRingRows;
};

/// The haptic steps between two trace rows for `trace_rate_hz` (0: every step, 1).
int traceStride(double haptic_rate_hz, double trace_rate_hz);

/// The warning for a trace of `bytes_per_row` written every `every_steps` steps of a run of
/// `duration_s` at `haptic_rate_hz`, when it reaches kTraceWarnBytes by the run's end: the rate an
/// hour, the size at the end and how to thin it (record.trace_rate) or drop it; "" otherwise.
std::string traceSizeWarning(double haptic_rate_hz, double duration_s, int every_steps, double bytes_per_row);

/// trace.csv, streamed to its file while the run goes (haptic thread only; no allocation, no lock
/// and no formatting on it: RowFile).
class TraceWriter {
 public:
  /// Writes the header for the world's dynamic bodies and fingers.
  /// Columns: t; per dynamic body its pose (.px .py .pz .qx .qy .qz .qw); per finger its
  /// coupling force (.fx .fy .fz), SGO count (.n_sgo), contact radius (.r), proxy and device
  /// positions (.px .py .pz, .dx .dy .dz); per dynamic body its linear (.vx .vy .vz, m/s) and
  /// angular (.wx .wy .wz, rad/s, world frame) velocity; per finger the force sent to the
  /// device (.sent_fx .sent_fy .sent_fz) and its port energy (.port_energy); per two fingers
  /// A, B (A before B) their patches' overlap (A+B.overlap_mm2, mm^2); last, per finger whose
  /// device gives an orientation (deviceGivesOrientation), that orientation (.dqw .dqx .dqy .dqz).
  /// With `options.every_steps` > 1, a row every that many steps (its time a multiple of the
  /// row interval). With `options.warn_size`, the writer thread prints traceSizeWarning on stderr
  /// once, after kTraceWatchRows rows.
  TraceWriter(const sim::World& world, const std::string& path, TraceOptions options = {});

  /// Appends the row of the world's current state, when this step is one of the rows.
  void record(const sim::World& world);

  /// Writes the last rows and puts the file in place (see RowFile::close).
  void close() { file_.close(); }

  /// The size warning the writer printed, "" when none; call after close() (owner thread).
  const std::string& sizeWarning() const { return *size_warning_; }

 private:
  std::shared_ptr<std::string> size_warning_ = std::make_shared<std::string>();  // set by the writer thread
  int every_steps_ = 1;
  long steps_ = 0;  // record() calls
  RowFile file_;
  std::vector<int> dynamic_bodies_;
  std::vector<int> oriented_fingers_;  // fingers whose device gives an orientation
  std::vector<double> row_;  // the row being filled
};

}  // namespace gf::app
