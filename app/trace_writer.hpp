// trace.csv: one row per haptic step, written deterministically (shortest round-trip numbers).
#pragma once

#include <string>

#include "sim/world.hpp"

namespace gf::app {

/// Accumulates trace rows in memory; `save` writes them. Haptic thread only.
class TraceWriter {
 public:
  /// Prepares the header for the world's dynamic bodies and fingers; reserves `expected_rows`.
  /// Columns: t; per dynamic body its pose (.px .py .pz .qx .qy .qz .qw); per finger its
  /// coupling force and SGO count (.fx .fy .fz .n_sgo); per dynamic body its linear (.vx .vy
  /// .vz, m/s) and angular (.wx .wy .wz, rad/s, world frame) velocity.
  TraceWriter(const sim::World& world, long expected_rows);

  /// Appends the row of the world's current state; does not allocate within `expected_rows`.
  void record(const sim::World& world);

  /// Writes header and rows to `path` through a temporary file renamed into place, so an
  /// earlier file is only replaced by a complete one. Throws std::runtime_error on I/O failure.
  void save(const std::string& path) const;

 private:
  std::string text_;
  std::vector<int> dynamic_bodies_;
};

/// Appends the shortest decimal that reads back as exactly `x`.
void appendNumber(std::string& out, double x);

/// Writes `text` to `path` via `path.tmp` and a rename. Throws std::runtime_error on failure.
void writeFileAtomically(const std::string& path, const std::string& text);

}  // namespace gf::app
