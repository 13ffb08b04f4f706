// trace.csv: one row per haptic step, written deterministically (shortest round-trip numbers).
#pragma once

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
  TraceWriter(const sim::World& world, const std::string& path);

  /// Appends the row of the world's current state.
  void record(const sim::World& world);

  /// Writes the last rows and puts the file in place (see RowFile::close).
  void close() { file_.close(); }

 private:
  RowFile file_;
  std::vector<int> dynamic_bodies_;
  std::vector<int> oriented_fingers_;  // fingers whose device gives an orientation
  std::vector<double> row_;  // the row being filled
};

}  // namespace gf::app
